// Several diffusion profiles in one scene (LUT array layers, <preskin/ProfileLibrary.h>):
//  - spheres whose materials name different profiles each render exactly as the same scene
//    rendered with that profile alone (a renderer holding only that profile's LUT set), with a
//    shadowed key light and an environment so every table (diffuse, penumbra, SH transfer,
//    transmittance) is read; one profile is a smaller LUT set than the others (padded layer);
//  - the same with 64 profiles in the scene, spheres on the first, middle and last layers;
//  - a profile-weight texture of 0 and of 1 renders as the pure profiles, and an intermediate
//    weight as the CPU skin model with the weighted sum of the two profiles' diffuse lookups;
//  - on the bundled head (normal map, cast shadows, the HDR environment, transmission), a blend
//    of four profiles whose weights are all on one profile renders as that profile named alone,
//    for each of the four: lookups, normal prefiltering, shadow lift and per-vertex terms all
//    follow the blend;
//  - Renderer::setProfileLayer re-uploads one layer: the image follows the new profile.
#include "support/GpuTest.h"
#include "support/ImageCompare.h"
#include "support/SkinTestSupport.h"
#include "support/TestScenes.h"

#include <preskin/Error.h>
#include <preskin/ProfileLibrary.h>
#include <preskin/Renderer.h>

#include <fmt/core.h>
#include <glm/gtc/matrix_transform.hpp>

#include <cstdio>
#include <filesystem>

namespace preskin::test {
namespace {

constexpr double kRadiusM = 0.005;  // curvature 0.2 / mm at scatter scale 1
constexpr uint32_t kSize = 128;

DiffusionProfile burleyProfile(double red, double mfpScale) {
    return DiffusionProfile::burley({red, 0.5, 0.4}, glm::dvec3(1.0, 0.4, 0.25) * mfpScale);
}

Material skinMaterial(int profile) {
    Material m;
    m.baseColorFactor = glm::vec4(0.8f, 0.6f, 0.5f, 1.0f);
    m.metallicFactor = 0.0f;
    m.roughnessFactor = 0.5f;
    SkinMaterial skin;
    skin.profile = profile;
    m.skin = skin;
    return m;
}

// `profiles.size()` spheres in a row, sphere i with material i using profile profiles[i].
Scene sphereRow(const std::vector<int>& profiles) {
    std::vector<std::pair<Primitive, glm::mat4>> parts;
    std::vector<Material> materials;
    const float spacing = 2.4f * float(kRadiusM);
    for (size_t i = 0; i < profiles.size(); ++i) {
        Primitive sphere = makeSphere(float(kRadiusM), 64, 32);
        recomputeCurvature(sphere);
        sphere.material = int(i);
        const float x = (float(i) - 0.5f * float(profiles.size() - 1)) * spacing;
        parts.push_back({sphere, glm::translate(glm::mat4(1.0f), glm::vec3(x, 0.0f, 0.0f))});
        materials.push_back(skinMaterial(profiles[i]));
    }
    Scene scene = makeScene(parts, materials);
    Light key = sphereLight();
    key.castsShadow = true;
    scene.lights = {key};
    return scene;
}

View rowView(size_t count) {
    const float halfWidth = 1.2f * float(kRadiusM) * float(count);
    const glm::mat4 worldFromView = glm::inverse(
        glm::lookAt(glm::vec3(0.0f, 0.0f, 10.0f * halfWidth), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f)));
    return perspectiveView(worldFromView, 0.21f, 1.0f, halfWidth, 20.0f * halfWidth);
}

Environment testEnvironment() {
    return makeEnvironment(
        32, [](const glm::vec3& d) { return glm::vec3(0.3f, 0.25f, 0.2f) * (1.0f + 0.7f * d.y) + 0.1f * d.x; });
}

RenderSettings testSettings() {
    RenderSettings settings;
    settings.shadowMapSize = 512;
    // The wide shadow map's reach follows the widest profile in the scene: pinned, so that a
    // sphere renders the same beside others as alone.
    settings.skinShadowReachMm = 4.0f;
    return settings;
}

// The pixels of column band [x0, x1) of two images: count differing by more than `steps`.
size_t differingInBand(const RenderedImage& a, const RenderedImage& b, uint32_t x0, uint32_t x1, double steps,
                       double& worst) {
    size_t count = 0;
    for (uint32_t y = 0; y < a.height; ++y)
        for (uint32_t x = x0; x < x1; ++x) {
            const double d = srgbDifference(pixelLinear(a, x, y), pixelLinear(b, x, y));
            worst = std::max(worst, d);
            if (d > steps) ++count;
        }
    return count;
}

class SkinProfiles : public GpuTest {
protected:
    // Renders the row with the whole library, and each sphere's profile alone, and compares
    // each sphere's band of columns.
    void expectEachAsAlone(const Scene& scene, const std::vector<int>& profiles, const ProfileLibrary& library,
                           const std::string& name) {
        const View view = rowView(profiles.size());
        const Environment environment = testEnvironment();
        Renderer together(context(), scene, environment, library, testSettings());
        const RenderedImage all = together.render(view, kSize, kSize, OutputEncoding::LinearFloat);
        dumpImage(name, all);
        const auto bandWidth = kSize / uint32_t(profiles.size());
        for (size_t i = 0; i < profiles.size(); ++i) {
            Scene alone = scene;
            for (Material& m : alone.materials) m.skin->profile = -1;
            alone.profiles.clear();
            const LutSet& luts = library.layer(size_t(profiles[i] + 1));
            const RenderedImage reference = Renderer(context(), alone, environment, &luts, testSettings())
                                                .render(view, kSize, kSize, OutputEncoding::LinearFloat);
            // Another profile in its place must change the band, or the comparison proves nothing.
            const LutSet& other = library.layer(size_t(profiles[(i + 1) % profiles.size()] + 1));
            const RenderedImage otherImage = Renderer(context(), alone, environment, &other, testSettings())
                                                 .render(view, kSize, kSize, OutputEncoding::LinearFloat);
            const uint32_t x0 = uint32_t(i) * bandWidth;
            double worst = 0.0, otherWorst = 0.0;
            const size_t differing = differingInBand(all, reference, x0, x0 + bandWidth, 1.0, worst);
            const size_t otherDiffering = differingInBand(all, otherImage, x0, x0 + bandWidth, 2.0, otherWorst);
            std::printf(
                "[ profiles ] %s sphere %zu (profile %d): %zu pixels differ from its profile alone (worst %.2f/255); "
                "%zu from another profile (worst %.2f/255)\n",
                name.c_str(), i, profiles[i], differing, worst, otherDiffering, otherWorst);
            EXPECT_EQ(differing, 0u) << "sphere " << i << " worst " << worst << "/255";
            EXPECT_GT(otherDiffering, size_t(50)) << "sphere " << i << ": the profiles should look different";
        }
    }
};

TEST_F(SkinProfiles, TwoMaterialsEachRenderAsAloneWithTheirProfile) {
    const std::vector<int> profiles = {0, 1};
    Scene scene = sphereRow(profiles);
    scene.profiles = {{"wide", burleyProfile(0.8, 3.0), {}}, {"narrow", burleyProfile(0.9, 0.5), {}}};
    ProfileLibrary library(
        std::make_shared<const LutSet>(LutSet::bake(DiffusionProfile::deonLuebke(), LutBakeSettings::withSize(32))));
    library = ProfileLibrary::forScene(scene, library.layerPointer(0), LutBakeSettings::withSize(32), {false, {}});
    // A smaller set in the second layer: it is padded to the arrays' size.
    library.setLayer(
        2, std::make_shared<const LutSet>(LutSet::bake(*scene.profiles[1].profile, LutBakeSettings::withSize(20))));
    expectEachAsAlone(scene, profiles, library, "profiles_two");
}

TEST_F(SkinProfiles, SixtyFourProfilesInOneScene) {
    const std::vector<int> profiles = {0, 31, 63};
    Scene scene = sphereRow(profiles);
    for (int i = 0; i < 64; ++i)
        scene.profiles.push_back({fmt::format("p{}", i), burleyProfile(0.5 + 0.5 * i / 63.0, 0.3 + 0.05 * i), {}});
    const ProfileLibrary library = ProfileLibrary::forScene(
        scene,
        std::make_shared<const LutSet>(LutSet::bake(DiffusionProfile::deonLuebke(), LutBakeSettings::withSize(16))),
        LutBakeSettings::withSize(16), {false, {}});
    ASSERT_EQ(library.layerCount(), 65u);
    expectEachAsAlone(scene, profiles, library, "profiles_64");
}

// A sphere blending profile A (the material's) with B (blendProfiles[0]) by a constant weight
// texture of `weight` / 255 in red.
Scene blendedSphere(uint8_t weight) {
    Primitive sphere = makeSphere(float(kRadiusM), 256, 128);
    recomputeCurvature(sphere);
    sphere.material = 0;
    Material m = skinMaterial(0);
    Scene scene = makeScene({{sphere, glm::mat4(1.0f)}}, {m});
    Image image;
    image.name = "weights";
    image.width = image.height = 2;
    for (int i = 0; i < 4; ++i) image.rgba8.insert(image.rgba8.end(), {weight, 0, 0, 255});
    scene.images.push_back(image);
    scene.materials[0].skin->blendProfiles = {1};
    scene.materials[0].skin->profileWeightTexture.image = 0;
    scene.profiles = {{"A", burleyProfile(0.8, 3.0), {}}, {"B", DiffusionProfile::deonLuebke(), {}}};
    scene.lights = {sphereLight()};
    return scene;
}

TEST_F(SkinProfiles, WeightTextureBlendsTheLookups) {
    const Scene probe = blendedSphere(0);
    const LutBakeSettings settings = LutBakeSettings::withSize(64);
    const ProfileLibrary library = ProfileLibrary::forScene(
        probe,
        std::make_shared<const LutSet>(LutSet::bake(DiffusionProfile::deonLuebke(), LutBakeSettings::withSize(16))),
        settings, {false, {}});
    const LutSet& a = library.layer(1);
    const LutSet& b = library.layer(2);
    RenderSettings rs;
    rs.shadows = false;
    const View view = sphereView(kRadiusM);
    const Environment dark = Environment::constant(glm::vec3(0.0f));
    auto render = [&](const Scene& scene) {
        return Renderer(context(), scene, dark, library, rs).render(view, kSize, kSize, OutputEncoding::LinearFloat);
    };
    // The pure profiles, without any blend.
    Scene pureA = blendedSphere(0);
    pureA.materials[0].skin->blendProfiles.clear();
    Scene pureB = pureA;
    pureB.materials[0].skin->profile = 1;
    const RenderedImage imageA = render(pureA);
    const RenderedImage imageB = render(pureB);
    EXPECT_EQ(maxSrgbDifference(render(blendedSphere(0)), imageA), 0.0);
    EXPECT_EQ(maxSrgbDifference(render(blendedSphere(255)), imageB), 0.0);

    const RenderedImage half = render(blendedSphere(128));
    dumpImage("profiles_blend_half", half);
    const double w = 128.0 / 255.0;
    const DiffuseLookup blend = [&](double NoL, double c) {
        return (1.0 - w) * glm::dvec3(a.lookupDiffuse(float(NoL), float(c))) +
            w * glm::dvec3(b.lookupDiffuse(float(NoL), float(c)));
    };
    const SkinMaterial& skin = *pureA.materials[0].skin;
    const glm::dvec3 albedo(0.8, 0.6, 0.5);
    const SphereAgreement s = compareWithSkinReference(half, view, kRadiusM, sphereLight(), skin, albedo, 0.5, blend);
    const SphereAgreement pa =
        compareWithSkinReference(half, view, kRadiusM, sphereLight(), skin, albedo, 0.5, lutDiffuse(a));
    const SphereAgreement pb =
        compareWithSkinReference(half, view, kRadiusM, sphereLight(), skin, albedo, 0.5, lutDiffuse(b));
    const SphereAgreement checkA =
        compareWithSkinReference(imageA, view, kRadiusM, sphereLight(), skin, albedo, 0.5, lutDiffuse(a));
    std::printf(
        "[ profiles ] weight 128/255: %zu of %zu interior pixels within 2/255 of the CPU blend (worst %.2f/255); "
        "pure A %zu, pure B %zu within; weight 0 against A's reference: %zu within\n",
        s.within, s.interior, s.worst, pa.within, pb.within, checkA.within);
    ASSERT_GT(s.interior, size_t(kSize * kSize / 4));
    EXPECT_GE(double(s.within), 0.999 * double(s.interior)) << "worst " << s.worst << "/255";
    EXPECT_GE(double(checkA.within), 0.999 * double(checkA.interior));
    EXPECT_LT(double(pa.within), 0.9 * double(pa.interior)) << "A alone should not pass for the blend";
    EXPECT_LT(double(pb.within), 0.9 * double(pb.interior)) << "B alone should not pass for the blend";
}

TEST_F(SkinProfiles, BlendOfOneProfileIsThatProfileOnTheHead) {
    const std::filesystem::path file = std::filesystem::path(PRESKIN_SOURCE_DIR) / "samples/assets/head/head.gltf";
    const Scene head = Scene::load(file);
    ASSERT_TRUE(head.environmentPath.has_value());
    ASSERT_TRUE(head.materials.at(0).skin.has_value());
    ASSERT_TRUE(head.materials[0].normal.valid()) << "the head should have a normal map";
    const Environment environment =
        Environment::load(*head.environmentPath, head.environmentIntensity, head.environmentRotation);
    Scene blended = head;
    blended.profiles = {
        {"d'Eon & Luebke", DiffusionProfile::deonLuebke(), {}},
        {"wide", burleyProfile(0.9, 4.0), {}},
        {"dense", burleyProfile(0.6, 0.6), {}},
        {"broad", DiffusionProfile::sumOfGaussians({{0.5, {0.3, 0.5, 0.7}}, {6.0, {0.7, 0.5, 0.3}}}), {}}};
    blended.materials[0].skin->profile = 0;
    blended.materials[0].skin->blendProfiles = {1, 2, 3};
    blended.materials[0].skin->profileWeightTexture.image = int(blended.images.size());
    blended.images.emplace_back();
    const LutBakeSettings settings = LutBakeSettings::withSize(64);
    const ProfileLibrary library = ProfileLibrary::forScene(
        blended, std::make_shared<const LutSet>(LutSet::bake(DiffusionProfile::deonLuebke(), settings)), settings,
        {false, {}});
    RenderSettings rs;
    // The wide shadow map's blocks follow the widest profile any material uses: the same for both.
    rs.skinShadowReachMm = 12.0f;
    const View view = frameBoundsView(head.worldBounds(), 1.0f);
    constexpr uint32_t kHeadSize = 256;
    auto render = [&](const Scene& scene) {
        return Renderer(context(), scene, environment, library, rs)
            .render(view, kHeadSize, kHeadSize, OutputEncoding::DisplaySrgb8);
    };
    for (int profile = 0; profile < 4; ++profile) {
        Scene weighted = blended;
        Image& weights = weighted.images.back();
        weights.name = fmt::format("weights of profile {}", profile);
        weights.width = weights.height = 4;
        const uint8_t r = profile == 1 ? 255 : 0, g = profile == 2 ? 255 : 0, b = profile == 3 ? 255 : 0;
        for (int i = 0; i < 16; ++i) weights.rgba8.insert(weights.rgba8.end(), {r, g, b, 255});
        Scene pure = blended;
        pure.materials[0].skin->profile = profile;
        pure.materials[0].skin->blendProfiles.clear();
        pure.materials[0].skin->profileWeightTexture = {};
        pure.images.pop_back();
        const RenderedImage blendImage = render(weighted);
        const RenderedImage pureImage = render(pure);
        int worst = 0;
        const size_t beyond = pixelsDifferingBy(blendImage, pureImage, 1, worst);
        std::printf("[ profiles ] head, blend of weight 1 on profile %d against the profile alone: worst %d/255\n",
                    profile, worst);
        EXPECT_EQ(beyond, 0u) << "profile " << profile << ": worst " << worst << "/255";
        if (profile == 1) dumpImage("profiles_blend_head_wide", blendImage);
    }
}

TEST_F(SkinProfiles, SetProfileLayerReuploadsOneLayer) {
    const std::vector<int> profiles = {0, 1};
    Scene scene = sphereRow(profiles);
    scene.profiles = {{"wide", burleyProfile(0.8, 3.0), {}}, {"narrow", burleyProfile(0.9, 0.5), {}}};
    const LutBakeSettings settings = LutBakeSettings::withSize(24);
    ProfileLibrary library = ProfileLibrary::forScene(
        scene, std::make_shared<const LutSet>(LutSet::bake(DiffusionProfile::deonLuebke(), settings)), settings,
        {false, {}});
    const View view = rowView(profiles.size());
    const Environment environment = testEnvironment();
    Renderer renderer(context(), scene, environment, library, testSettings());
    (void)renderer.render(view, kSize, kSize, OutputEncoding::LinearFloat);
    // Profile 1 becomes profile 0's: the scene now renders as if both named profile 0.
    renderer.setProfileLayer(2, library.layer(1));
    const RenderedImage edited = renderer.render(view, kSize, kSize, OutputEncoding::LinearFloat);
    Scene same = scene;
    same.materials[1].skin->profile = 0;
    const RenderedImage expected = Renderer(context(), same, environment, library, testSettings())
                                       .render(view, kSize, kSize, OutputEncoding::LinearFloat);
    EXPECT_EQ(maxSrgbDifference(edited, expected), 0.0);
    EXPECT_THROW(renderer.setProfileLayer(3, library.layer(1)), Error);
    EXPECT_THROW(
        renderer.setProfileLayer(1, LutSet::bake(DiffusionProfile::deonLuebke(), LutBakeSettings::withSize(32))),
        Error);
    // A material naming a profile the renderer has no layer for.
    Scene missing = scene;
    missing.materials[1].skin->profile = 5;
    EXPECT_THROW(Renderer(context(), missing, environment, library, testSettings()), Error);
}

}  // namespace
}  // namespace preskin::test
