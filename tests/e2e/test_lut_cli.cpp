// Tests of `preskin bake` as a user runs it: a good bake writes a loadable set; bad input (absurd
// sizes, bad profile files, malformed colours, missing Burley parameters) exits non-zero with one
// "preskin: error: ..." line and writes nothing. `preskin bake-curvature` the same way: the head's
// map and its JSON, the scene written back reading the maps (--scene-out), and bad input refused
// with nothing written.
#include <preskin/CurvatureBake.h>
#include <preskin/LutSet.h>
#include <preskin/Scene.h>

#include "support/Process.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>

namespace preskin::test {
namespace {

namespace fs = std::filesystem;

using CliRun = test::ProcessResult;

class BakeCli : public ::testing::Test {
protected:
    void SetUp() override {
        if (!fs::exists(PRESKIN_CLI_PATH)) GTEST_SKIP() << PRESKIN_CLI_PATH << " is not built";
        std::random_device entropy;
        dir_ = fs::temp_directory_path() / ("preskin_test_bake_cli_" + std::to_string(entropy()));
        fs::create_directories(dir_);
    }
    void TearDown() override {
        std::error_code ec;
        if (!dir_.empty()) fs::remove_all(dir_, ec);
    }

    CliRun bake(const std::vector<std::string>& arguments) const {
        std::vector<std::string> all{std::string("bake")};
        all.insert(all.end(), arguments.begin(), arguments.end());
        return test::runCli(all, dir_);
    }

    // `preskin COMMAND ARGUMENTS --out DIR` for each case: exit 1, one "preskin: error: " line
    // holding the expected text, and no DIR.
    void expectRefused(const std::string& command,
                       const std::vector<std::pair<std::vector<std::string>, std::string>>& cases) const {
        const fs::path out = dir_ / "never";
        for (const auto& [caseArguments, expected] : cases) {
            std::vector<std::string> all = {command};
            all.insert(all.end(), caseArguments.begin(), caseArguments.end());
            all.insert(all.end(), {"--out", out.string()});
            const CliRun run = test::runCli(all, dir_);
            std::ostringstream joined;
            for (const std::string& a : caseArguments) joined << a << ' ';
            const std::string arguments = joined.str();
            EXPECT_EQ(run.exitCode, 1) << arguments;
            EXPECT_EQ(run.err.rfind("preskin: error: ", 0), 0u) << arguments << ": " << run.err;
            EXPECT_NE(run.err.find(expected), std::string::npos) << arguments << ": " << run.err;
            EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << arguments << ": " << run.err;
            EXPECT_FALSE(fs::exists(out)) << arguments;
        }
    }

    fs::path dir_;
};

TEST_F(BakeCli, WritesALoadableSet) {
    const fs::path out = dir_ / "set";
    const CliRun run = bake({"--profile", "deon", "--size", "16", "--preview", "--out", out.string()});
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_NE(run.out.find("baked in"), std::string::npos) << run.out;
    const LutSet loaded = LutSet::load(out);
    EXPECT_EQ(loaded.diffuse().width(), 16);
    EXPECT_TRUE(fs::exists(out / "preview_diffuse.png"));

    const fs::path burley = dir_ / "burley";
    const CliRun run2 = bake({"--profile", "burley", "--albedo", "0.8,0.5,0.3", "--mfp", "2,0.9,0.4", "--size", "16",
                              "--out", burley.string()});
    ASSERT_EQ(run2.exitCode, 0) << run2.err;
    EXPECT_EQ(LutSet::load(burley).profile().kind(), DiffusionProfile::Kind::NormalizedDiffusion);
}

TEST_F(BakeCli, BadInputIsRefusedAndNothingIsWritten) {
    const std::string profiles = std::string(PRESKIN_SOURCE_DIR) + "/tests/data/profiles/";
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases{
        {{"--size", "0"}, "--size: must be an integer in [16, 4096], got '0'"},
        {{"--size", "1e9"}, "--size: must be an integer in [16, 4096], got '1e9'"},
        {{"--size=-5"}, "--size: must be an integer in [16, 4096], got '-5'"},
        {{"--size", "99999999999"}, "--size: must be an integer in [16, 4096]"},
        {{"--profile", profiles + "bad_negative_weight.json"},
         "bad_negative_weight.json: gaussians[1].weights[0]: must be >= 0"},
        {{"--profile", profiles + "bad_nan_variance.json"}, "bad_nan_variance.json: JSON: parse error"},
        {{"--profile", profiles + "bad_zero_albedo.json"}, "zero albedo"},
        {{"--profile", profiles + "bad_missing_variance.json"}, "gaussians[0].varianceMm2: missing"},
        {{"--profile", "burley"}, "--profile burley: needs --albedo"},
        {{"--profile", "burley", "--albedo", "1,2", "--mfp", "1,1,1"},
         "--albedo: expected three comma-separated numbers R,G,B, got '1,2'"},
        {{"--profile", "burley", "--albedo", "0.8,0,0.3", "--mfp", "1,1,1"},
         "burley: albedo[1]: must be in (0, 1], got 0"},
        {{"--profile", "burley", "--albedo", "0.8,0.5,0.3", "--mfp", "1,nan,1"},
         "--mfp: expected three comma-separated numbers"},
        {{"--profile", "deon", "--albedo", "0.5,0.5,0.5"}, "--albedo and --mfp apply only to --profile burley"},
    };
    expectRefused("bake", cases);
}

TEST_F(BakeCli, CurvatureMapOfTheHead) {
    const fs::path out = dir_ / "maps";
    const CliRun run = test::runCli({"bake-curvature", "--size", "128", "--out", out.string()}, dir_);
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_TRUE(fs::exists(out / "skin_curvature.png")) << run.err;
    std::ifstream file(out / "skin_curvature.json");
    const nlohmann::json j = nlohmann::json::parse(file);
    EXPECT_EQ(j["image"], "skin_curvature.png");
    EXPECT_EQ(j["width"], 128);
    EXPECT_GT(j["coveredFraction"].get<double>(), 0.8);
    EXPECT_EQ(j["PRESKIN_materials_skin"]["curvatureSource"], "texture");
    EXPECT_EQ(j["PRESKIN_materials_skin"]["curvatureTextureBias"], 0.5);
    // A head's creases and ears: tens to hundreds of 1/m.
    EXPECT_GT(j["PRESKIN_materials_skin"]["curvatureTextureScalePerM"].get<double>(), 50.0);
}

// The scene `--scene-out` writes loads, and each skin material reads the map baked for it: its
// texels are those bakeCurvatureMaps gives the source scene in-process, with its scale and bias;
// the scene's other resources resolve from the new folder (beside the source and a folder above
// it); the Khronos validator finds no error (where it is installed). A scene whose URIs would
// leave its folder, maps outside its folder and a name other than .gltf are refused with nothing
// written.
TEST_F(BakeCli, CurvatureSceneOutReadsTheMaps) {
    const fs::path head = dir_ / "head";
    fs::copy(fs::path(PRESKIN_SOURCE_DIR) / "samples/assets/head", head, fs::copy_options::recursive);
    const Scene source = Scene::load(head / "head.gltf");
    CurvatureBakeSettings settings;
    settings.size = 64;
    const std::vector<CurvatureMap> expected = bakeCurvatureMaps(source, settings);
    ASSERT_EQ(expected.size(), 1u);
    const std::map<fs::path, fs::path> written{{head / "maps", head / "curved.gltf"},  // beside the source
                                               {dir_ / "maps", dir_ / "above.gltf"}};  // a folder above it
    std::vector<std::string> scenes;
    for (const auto& [maps, scenePath] : written) {
        const CliRun run = test::runCli({"bake-curvature", (head / "head.gltf").string(), "--size", "64", "--out",
                                         maps.string(), "--scene-out", scenePath.string()},
                                        dir_);
        ASSERT_EQ(run.exitCode, 0) << run.err;
        scenes.push_back(scenePath.string());
        const Scene scene = Scene::load(scenePath);
        ASSERT_EQ(scene.materials.size(), source.materials.size());
        ASSERT_EQ(scene.meshes.size(), source.meshes.size());
        EXPECT_EQ(scene.environmentPath.has_value(), source.environmentPath.has_value());
        const Material& m = scene.materials[size_t(expected[0].material)];
        ASSERT_TRUE(m.skin.has_value());
        EXPECT_EQ(m.skin->curvatureSource, CurvatureSource::Texture);
        EXPECT_FLOAT_EQ(m.skin->curvatureTextureScalePerM, expected[0].scalePerM);
        EXPECT_FLOAT_EQ(m.skin->curvatureTextureBias, expected[0].bias);
        ASSERT_TRUE(m.skin->curvatureTexture.valid());
        const Image& image = scene.images[size_t(m.skin->curvatureTexture.image)];
        ASSERT_EQ(image.width, 64u);
        ASSERT_EQ(image.rgba16.size(), size_t(64 * 64 * 4));
        const std::vector<uint16_t> texels = expected[0].encoded();
        size_t differ = 0;
        for (size_t i = 0; i < texels.size(); ++i) differ += image.rgba16[i * 4] != texels[i];
        EXPECT_EQ(differ, 0u) << " of " << texels.size() << " texels";
        // Everything else as the source has it: the base colour's texels, the specular map.
        const Material& s = source.materials[size_t(expected[0].material)];
        EXPECT_EQ(scene.images[size_t(m.baseColor.image)].rgba8, source.images[size_t(s.baseColor.image)].rgba8);
        EXPECT_EQ(m.skin->specularTexture.valid(), s.skin->specularTexture.valid());
    }
    if (std::system("command -v node >/dev/null 2>&1") == 0) {
        std::vector<std::string> args{"node", std::string(PRESKIN_SOURCE_DIR) + "/scripts/validate-gltf.js"};
        args.insert(args.end(), scenes.begin(), scenes.end());
        const test::ProcessResult r = test::runProcess("/usr/bin/env", args, {}, dir_, 300.0);
        if (r.exitCode != 2) {
            ASSERT_EQ(r.exitCode, 0) << r.err;
            std::istringstream lines(r.out);
            int reports = 0;
            for (std::string line; std::getline(lines, line); ++reports)
                EXPECT_EQ(nlohmann::json::parse(line).at("errors"), 0) << line;
            EXPECT_EQ(reports, 2);
        }
    }

    // Refused before anything is baked (expectRefused adds --out DIR/never and checks it is not made).
    const std::string h = (head / "head.gltf").string();
    expectRefused(
        "bake-curvature",
        {{{h, "--scene-out", (dir_ / "elsewhere" / "head.gltf").string()}, "would leave the new scene's folder"},
         {{h, "--scene-out", (head / "curved.glb").string()}, "name it .gltf"},
         {{h, "--scene-out", (head / "inside.gltf").string()}, "lies outside the scene's folder"}});
    EXPECT_FALSE(fs::exists(dir_ / "elsewhere"));
    EXPECT_FALSE(fs::exists(head / "inside.gltf"));
}

TEST_F(BakeCli, BadCurvatureInputIsRefusedAndNothingIsWritten) {
    const std::string plain = std::string(PRESKIN_SOURCE_DIR) + "/samples/assets/tube/tube.gltf";
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases{
        {{"--size", "8"}, "--size: value: 8 is outside [16, 8192]"},
        {{"--size", "0"}, "--size: value: 0 is outside [16, 8192]"},
        {{"--dilation", "5000"}, "dilation: must be in [0, 1024], got 5000"},
        {{"/nonexistent/scene.gltf"}, "/nonexistent/scene.gltf"},
        {{"--skin", "nose"}, "no material named 'nose'"},
        {{plain}, "no skin material is drawn"},
    };
    expectRefused("bake-curvature", cases);
}

}  // namespace
}  // namespace preskin::test
