// Diffusion profiles as scene data: the root PRESKIN_materials_skin extension's "profiles" (every
// kind, names, materials' profile and profileBlend), their one-line errors, assigning a profile
// by material name, and ProfileLibrary: layers in scene order, baking against LutSet::bake, the
// on-disk cache (miss, hit, damaged entry, a folder that cannot be written) and LUT folders from
// `preskin bake`. Tables are baked at 16 or 24 texels to keep the tests fast.
#include "unit/GltfTestFiles.h"

#include "support/Process.h"

#include <preskin/ProfileLibrary.h>

#include <fmt/core.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <fstream>

namespace preskin::test {
namespace {

LutBakeSettings smallSettings() { return LutBakeSettings::withSize(16); }

std::shared_ptr<const LutSet> smallDefault() {
    static const auto set =
        std::make_shared<const LutSet>(LutSet::bake(DiffusionProfile::deonLuebke(), smallSettings()));
    return set;
}

nlohmann::json burleyJson(double albedoR) {
    return {{"type", "normalizedDiffusion"},
            {"name", "burley"},
            {"albedo", {albedoR, 0.5, 0.4}},
            {"meanFreePathMm", {1.0, 0.4, 0.25}}};
}

nlohmann::json gaussiansJson() {
    return {{"type", "sumOfGaussians"},
            {"name", "two Gaussians"},
            {"gaussians",
             {{{"varianceMm2", 0.02}, {"weights", {0.3, 0.5, 0.7}}},
              {{"varianceMm2", 0.6}, {"weights", {0.7, 0.5, 0.3}}}}}};
}

// The triangle scene with `profiles` at the root and one material using `skin`.
fs::path writeProfileScene(const fs::path& dir, const nlohmann::json& profiles, const nlohmann::json& skin) {
    GltfBuilder b = triangleScene();
    b.doc["extensionsUsed"] = {"PRESKIN_materials_skin"};
    b.doc["extensions"]["PRESKIN_materials_skin"]["profiles"] = profiles;
    b.doc["materials"] = {{{"name", "face"}, {"extensions", {{"PRESKIN_materials_skin", skin}}}}};
    b.doc["meshes"][0]["primitives"][0]["material"] = 0;
    return b.writeGltf(dir);
}

bool sameTables(const LutSet& a, const LutSet& b) {
    return a.diffuse().rgb == b.diffuse().rgb && a.penumbra().rgb == b.penumbra().rgb &&
        a.shTransfer().rgb == b.shTransfer().rgb && a.transmittance().rgb == b.transmittance().rgb;
}

TEST(SceneProfiles, EveryKindLoadsFromGltf) {
    TempDir dir;
    const LutSet baked =
        LutSet::bake(DiffusionProfile::burley({0.9, 0.6, 0.5}, {2.0, 1.0, 0.5}), LutBakeSettings::withSize(24));
    baked.save(dir / "baked");
    const fs::path path = writeProfileScene(dir.path(),
                                            {{{"type", "deonLuebke"}},
                                             burleyJson(0.8),
                                             gaussiansJson(),
                                             {{"type", "lutFolder"}, {"name", "baked"}, {"uri", "baked"}}},
                                            {{"profile", 2}});
    const Scene scene = Scene::load(path);
    ASSERT_EQ(scene.profiles.size(), 4u);
    EXPECT_EQ(scene.profiles[0].name, "profiles[0]");
    ASSERT_TRUE(scene.profiles[0].profile);
    EXPECT_EQ(scene.profiles[0].profile->toJson(), DiffusionProfile::deonLuebke().toJson());
    ASSERT_TRUE(scene.profiles[1].profile);
    EXPECT_EQ(scene.profiles[1].profile->kind(), DiffusionProfile::Kind::NormalizedDiffusion);
    EXPECT_DOUBLE_EQ(scene.profiles[1].profile->albedo().r, 0.8);
    EXPECT_EQ(scene.profiles[2].name, "two Gaussians");
    ASSERT_TRUE(scene.profiles[2].profile);
    EXPECT_EQ(scene.profiles[2].profile->gaussians().size(), 2u);
    EXPECT_FALSE(scene.profiles[3].profile);
    EXPECT_EQ(scene.profiles[3].lutFolder, fs::weakly_canonical(dir / "baked"));
    ASSERT_TRUE(scene.materials[0].skin);
    EXPECT_EQ(scene.materials[0].skin->profile, 2);

    // Layer i + 1 is profile i: baked with the library's settings, or the LUT folder as saved.
    TempDir cache;
    const ProfileLibrary library =
        ProfileLibrary::forScene(scene, smallDefault(), smallSettings(), {true, cache.path()});
    ASSERT_EQ(library.layerCount(), 5u);
    EXPECT_EQ(&library.layer(0), smallDefault().get());
    EXPECT_TRUE(sameTables(library.layer(2), LutSet::bake(*scene.profiles[1].profile, smallSettings())));
    EXPECT_TRUE(sameTables(library.layer(3), LutSet::bake(*scene.profiles[2].profile, smallSettings())));
    EXPECT_TRUE(sameTables(library.layer(4), baked));
    EXPECT_EQ(library.layer(4).settings(), LutBakeSettings::withSize(24));
    EXPECT_EQ(library.stats().lutFolders, 1);
    EXPECT_EQ(library.stats().baked, 3);
}

TEST(SceneProfiles, BlendAndAssignByName) {
    TempDir dir;
    GltfBuilder b = triangleScene();
    b.doc["extensionsUsed"] = {"PRESKIN_materials_skin"};
    b.doc["extensions"]["PRESKIN_materials_skin"]["profiles"] = {burleyJson(0.8), gaussiansJson(), burleyJson(0.5)};
    b.doc["images"] = {{{"uri", "weights.png"}}};
    encodeImage(dir.path(), "weights.png", 2, 2, 4, std::vector<uint8_t>(16, 128));
    b.doc["textures"] = {{{"source", 0}}};
    nlohmann::json skin = {{"profile", 0}};
    skin["profileBlend"]["profiles"] = {1, 2};
    skin["profileBlend"]["weightTexture"]["index"] = 0;
    nlohmann::json faceJson = {{"name", "face"}};
    faceJson["extensions"]["PRESKIN_materials_skin"] = skin;
    b.doc["materials"] = nlohmann::json::array({faceJson, {{"name", "cloth"}}});
    b.doc["meshes"][0]["primitives"][0]["material"] = 0;
    Scene scene = Scene::load(b.writeGltf(dir.path()));
    const SkinMaterial& face = *scene.materials[0].skin;
    EXPECT_EQ(face.profile, 0);
    EXPECT_EQ(face.blendProfiles, (std::vector<int>{1, 2}));
    EXPECT_EQ(face.profileWeightTexture.image, 0);

    EXPECT_FALSE(scene.materials[1].skin);
    scene.setSkinProfile("cloth", 2);
    ASSERT_TRUE(scene.materials[1].skin);
    EXPECT_EQ(scene.materials[1].skin->profile, 2);
    scene.setSkinProfile("all", -1);
    EXPECT_EQ(scene.materials[0].skin->profile, -1);
    EXPECT_EQ(scene.materials[1].skin->profile, -1);
    EXPECT_THROW(scene.setSkinProfile("cloth", 3), Error);
    EXPECT_THROW(scene.setSkinProfile("nose", 0), Error);
}

// Each kind of bad profile data: one line naming the file and the field.
TEST(SceneProfiles, BadProfileDataIsOneLineNamingTheField) {
    TempDir dir;
    const std::string profiles = "extensions.PRESKIN_materials_skin.profiles";
    struct Case {
        const char* name;
        nlohmann::json profiles;
        nlohmann::json skin;
        std::vector<std::string> fragments;
    };
    nlohmann::json albedoAboveOne = burleyJson(1.5);
    nlohmann::json negativeVariance = gaussiansJson();
    negativeVariance["gaussians"][1]["varianceMm2"] = -0.5;
    // One-element lists are written as arrays explicitly: `{x}` of one json is a copy of x under
    // clang (CWG 2137) and an array of one under GCC.
    const std::vector<Case> cases = {
        {"unknown_kind",
         nlohmann::json::array({{{"type", "dipole"}}}),
         nlohmann::json::object(),
         {profiles + "[0].type", "'dipole'"}},
        {"albedo_above_one",
         {burleyJson(0.8), albedoAboveOne},
         nlohmann::json::object(),
         {profiles + "[1].albedo[0]", "(0, 1]"}},
        {"negative_variance",
         nlohmann::json::array({negativeVariance}),
         nlohmann::json::object(),
         {profiles + "[0].gaussians[1].varianceMm2"}},
        {"missing_lut_folder",
         nlohmann::json::array({{{"type", "lutFolder"}, {"uri", "nowhere"}}}),
         nlohmann::json::object(),
         {profiles + "[0].uri", "'nowhere' not found"}},
        {"layer_out_of_range",
         nlohmann::json::array({burleyJson(0.8)}),
         {{"profile", 1}},
         {"materials[0].extensions.PRESKIN_materials_skin.profile", "1 is out of range", "1 profiles"}},
        {"blend_out_of_range",
         nlohmann::json::array({burleyJson(0.8)}),
         {{"profileBlend", {{"profiles", {0, 4}}, {"weightTexture", {{"index", 0}}}}}},
         {"profileBlend.profiles[1]", "4 is out of range"}},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        const fs::path sub = dir / c.name;
        fs::create_directories(sub);
        std::vector<const char*> fragments;
        for (const std::string& f : c.fragments) fragments.push_back(f.c_str());
        expectLoadError(writeProfileScene(sub, c.profiles, c.skin), fragments);
    }
    // NaN is not JSON: the file's JSON reader refuses it, naming the file.
    const fs::path nanScene =
        writeProfileScene(dir.path(), nlohmann::json::array({burleyJson(0.8)}), nlohmann::json::object());
    std::string text = readFile(nanScene);
    text.replace(text.find("0.8"), 3, "NaN");
    writeText(nanScene, text);
    const std::string message = loadError(nanScene);
    EXPECT_EQ(message.rfind(nanScene.string() + ": JSON: ", 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    // Through the API a NaN reaches the profile's own check.
    try {
        (void)DiffusionProfile::burley({std::nan(""), 0.5, 0.5}, {1.0, 1.0, 1.0});
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("albedo[0]: must be finite"), std::string::npos) << e.what();
    }
}

TEST(ProfileLibrary, CacheMissHitAndDamagedEntry) {
    Scene scene;
    SkinProfile a{"a", DiffusionProfile::burley({0.8, 0.5, 0.4}, {1.0, 0.4, 0.25}), {}};
    SkinProfile b{"b", DiffusionProfile::burley({0.6, 0.5, 0.4}, {2.0, 0.8, 0.5}), {}};
    scene.profiles = {a, b};
    TempDir cache;
    const ProfileCacheOptions options{true, cache.path()};

    const ProfileLibrary miss = ProfileLibrary::forScene(scene, smallDefault(), smallSettings(), options);
    EXPECT_EQ(miss.stats().baked, 2);
    EXPECT_EQ(miss.stats().cacheHits, 0);
    EXPECT_TRUE(miss.warnings().empty());
    const fs::path entryA = profileCacheEntry(cache.path(), *a.profile, smallSettings());
    const fs::path entryB = profileCacheEntry(cache.path(), *b.profile, smallSettings());
    EXPECT_NE(entryA, entryB);
    EXPECT_TRUE(fs::exists(entryA / "manifest.json"));
    EXPECT_TRUE(fs::exists(entryB / "diffuse.f16"));  // raw half floats: read without decoding
    // Other bake settings are another entry.
    EXPECT_NE(profileCacheEntry(cache.path(), *a.profile, LutBakeSettings::withSize(24)), entryA);

    const ProfileLibrary hit = ProfileLibrary::forScene(scene, smallDefault(), smallSettings(), options);
    EXPECT_EQ(hit.stats().cacheHits, 2);
    EXPECT_EQ(hit.stats().baked, 0);
    EXPECT_TRUE(sameTables(hit.layer(1), miss.layer(1)));
    EXPECT_TRUE(sameTables(hit.layer(2), miss.layer(2)));

    // Damage one table of entry b: its CRC fails, it is baked again with a warning and the entry
    // is repaired.
    {
        std::fstream file(entryB / "penumbra.f16", std::ios::in | std::ios::out | std::ios::binary);
        file.seekp(-64, std::ios::end);
        const char garbage[16] = {'d', 'a', 'm', 'a', 'g', 'e', 'd', '!', 'd', 'a', 'm', 'a', 'g', 'e', 'd', '!'};
        file.write(garbage, sizeof(garbage));
    }
    const ProfileLibrary repaired = ProfileLibrary::forScene(scene, smallDefault(), smallSettings(), options);
    EXPECT_EQ(repaired.stats().cacheHits, 1);
    EXPECT_EQ(repaired.stats().damaged, 1);
    EXPECT_EQ(repaired.stats().baked, 1);
    ASSERT_EQ(repaired.warnings().size(), 1u);
    EXPECT_NE(repaired.warnings()[0].find("profile 'b': damaged cache entry"), std::string::npos)
        << repaired.warnings()[0];
    EXPECT_NE(repaired.warnings()[0].find("penumbra.f16"), std::string::npos) << repaired.warnings()[0];
    EXPECT_NE(repaired.warnings()[0].find("CRC-32"), std::string::npos) << repaired.warnings()[0];
    EXPECT_TRUE(sameTables(repaired.layer(2), miss.layer(2)));
    const ProfileLibrary again = ProfileLibrary::forScene(scene, smallDefault(), smallSettings(), options);
    EXPECT_EQ(again.stats().cacheHits, 2);
    EXPECT_TRUE(again.warnings().empty());

    // An entry holding another profile (as a hash collision would) is not taken for this one.
    fs::remove_all(entryB);
    fs::copy(entryA, entryB);
    const ProfileLibrary swapped = ProfileLibrary::forScene(scene, smallDefault(), smallSettings(), options);
    EXPECT_EQ(swapped.stats().damaged, 1);
    EXPECT_TRUE(sameTables(swapped.layer(2), miss.layer(2)));

    // --no-cache: neither read nor written.
    TempDir unused;
    const ProfileLibrary uncached =
        ProfileLibrary::forScene(scene, smallDefault(), smallSettings(), {false, unused.path()});
    EXPECT_EQ(uncached.stats().baked, 2);
    EXPECT_TRUE(fs::is_empty(unused.path()));
}

TEST(ProfileLibrary, UnwritableCacheFolderWarnsOnceAndBakes) {
    Scene scene;
    for (int i = 0; i < 3; ++i)
        scene.profiles.push_back(
            {fmt::format("p{}", i), DiffusionProfile::burley({0.8, 0.5, 0.4}, {1.0 + i, 0.4, 0.25}), {}});
    TempDir dir;
    // A read-only folder (as root, which may write anyway, a folder below a regular file stands
    // in for it: it can be neither created nor written).
    std::vector<fs::path> folders;
    if (geteuid() != 0) {
        fs::create_directories(dir / "readonly");
        fs::permissions(dir / "readonly", fs::perms::owner_read | fs::perms::owner_exec);
        folders.push_back(dir / "readonly");
    }
    writeText(dir / "file", "not a folder");
    folders.push_back(dir / "file" / "cache");
    for (const fs::path& folder : folders) {
        SCOPED_TRACE(folder.string());
        const ProfileLibrary library = ProfileLibrary::forScene(scene, smallDefault(), smallSettings(), {true, folder});
        EXPECT_EQ(library.stats().baked, 3);
        ASSERT_EQ(library.warnings().size(), 1u);
        EXPECT_NE(library.warnings()[0].find("the profile cache cannot be written"), std::string::npos)
            << library.warnings()[0];
        EXPECT_TRUE(sameTables(library.layer(3), LutSet::bake(*scene.profiles[2].profile, smallSettings())));
    }
    if (geteuid() != 0) fs::permissions(dir / "readonly", fs::perms::owner_all);
}

TEST(ProfileLibrary, CacheFolderFollowsXdg) {
    const char* saved = std::getenv("XDG_CACHE_HOME");
    const std::string restore = saved ? saved : "";
    setenv("XDG_CACHE_HOME", "/somewhere/cache", 1);
    EXPECT_EQ(ProfileCacheOptions{}.resolvedFolder(), fs::path("/somewhere/cache/preskin/luts"));
    setenv("XDG_CACHE_HOME", "relative", 1);  // XDG: relative paths are ignored
    const char* home = std::getenv("HOME");
    if (home) {
        EXPECT_EQ(ProfileCacheOptions{}.resolvedFolder(), fs::path(home) / ".cache/preskin/luts");
    }
    EXPECT_EQ((ProfileCacheOptions{false, {}}.resolvedFolder()), fs::path());
    if (saved)
        setenv("XDG_CACHE_HOME", restore.c_str(), 1);
    else
        unsetenv("XDG_CACHE_HOME");
}

// `preskin bake` writes a folder that loads as a scene profile, and a scene whose material names
// a profile renders through the command line with the cache in a folder of the test's.
TEST(ProfileLibrary, BakeCommandOutputLoadsAsProfile) {
    TempDir dir;
    const ProcessResult bake = runCli({"bake", "--profile", "burley", "--albedo", "0.9,0.6,0.5", "--mfp", "2,1,0.5",
                                       "--size", "16", "--out", (dir / "lips").string()},
                                      dir.path());
    ASSERT_EQ(bake.exitCode, 0) << bake.err;
    const fs::path path =
        writeProfileScene(dir.path(), {{{"type", "lutFolder"}, {"uri", "lips"}}, burleyJson(0.7)}, {{"profile", 0}});
    const Scene scene = Scene::load(path);
    const ProfileLibrary library = ProfileLibrary::forScene(scene, smallDefault(), smallSettings(), {false, {}});
    EXPECT_TRUE(sameTables(
        library.layer(1),
        LutSet::bake(DiffusionProfile::burley({0.9, 0.6, 0.5}, {2.0, 1.0, 0.5}), LutBakeSettings::withSize(16))));

    const ProcessResult render =
        runCli({"render", path.string(), "--width", "32", "--height", "32", "--profile-lut-size", "16", "--cache-dir",
                (dir / "cache").string(), "--out", (dir / "out.png").string(), "--device", testDevice()},
               dir.path());
    EXPECT_EQ(render.exitCode, 0) << render.err;
    EXPECT_TRUE(fs::exists(dir / "out.png"));
    EXPECT_TRUE(fs::exists(profileCacheEntry(dir / "cache", *scene.profiles[1].profile, LutBakeSettings::withSize(16)) /
                           "manifest.json"));
}

}  // namespace
}  // namespace preskin::test
