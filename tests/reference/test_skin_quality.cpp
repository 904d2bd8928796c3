// The quality tiers (SkinQuality): what each compiles in (shared/skin_features.h), the head under
// each through the tool with the validation layers on (high is the default render, pixel for
// pixel; each lower tier differs from it), a material's own tier from PRESKIN_materials_skin and
// the frame-wide override, and each tier against the diffusion reference on the 10 mm skin
// sphere under a shadowed light: every tier far closer than Lambert, each with its own bound, and
// low's fitted rows for the other lights on spheres under an unshadowed one; the work a tier skips
// outside the forward pass (the wide shadow map's reduction) changes no pixel.
#include "support/GpuTest.h"
#include "support/ImageCompare.h"
#include "support/Process.h"
#include "support/SkinTestSupport.h"
#include "support/TestLights.h"
#include "support/TestScenes.h"
#include "unit/GltfTestFiles.h"

#include <preskin/DiffusionReference.h>
#include <preskin/Environment.h>
#include <preskin/LutSet.h>
#include <preskin/Renderer.h>
#include <preskin/Scene.h>
#include <preskin/View.h>

#include <shared/skin_features.h>

#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

namespace preskin::test {
namespace {

TEST(SkinQuality, TiersCompileInTheirTechniques) {
    const SkinFeatures high = skinQualityFeatures(SkinQuality::High);
    const SkinFeatures medium = skinQualityFeatures(SkinQuality::Medium);
    const SkinFeatures low = skinQualityFeatures(SkinQuality::Low);
    EXPECT_EQ(high, SkinFeatures{});
    // High is every technique but the table for the lights besides the shadow light (an addition).
    EXPECT_EQ(high.mask(), gpu::kSkinAll & ~gpu::kSkinLutOtherLights);
    EXPECT_EQ(high.mask(), gpu::kSkinQualityHigh);
    // Each tier holds the one below it, and the diffuse LUT is in all of them.
    EXPECT_EQ(medium.mask() & low.mask(), low.mask());
    EXPECT_EQ(high.mask() & medium.mask(), medium.mask());
    EXPECT_TRUE(low.lutDiffuse);
    // Low keeps the per-channel geometric normals but reads the normal map once.
    EXPECT_TRUE(low.normalPrefilter);
    EXPECT_FALSE(low.normalMapLevels);
    EXPECT_TRUE(medium.normalMapLevels);
    // Low keeps the penumbra LUT within the shadow filter's reach, without the wide shadow map.
    EXPECT_TRUE(low.penumbra);
    EXPECT_FALSE(low.widePenumbra);
    EXPECT_TRUE(medium.widePenumbra);
    // Low reads the diffuse LUT for no light (the row's fit); medium and high for the shadow light.
    EXPECT_FALSE(low.lutShadowLight);
    EXPECT_TRUE(medium.lutShadowLight);
    EXPECT_FALSE(high.lutOtherLights);
    // The rows along each light where some light reads the table (medium and high).
    EXPECT_FALSE(low.lightCurvature);
    EXPECT_TRUE(medium.lightCurvature);
    // Low filters the shadow map over 6 x 6 texels.
    EXPECT_FALSE(low.fullShadowFilter);
    EXPECT_TRUE(medium.fullShadowFilter);
    EXPECT_NE(medium.mask(), high.mask());
    EXPECT_NE(low.mask(), medium.mask());
}

TEST(SkinQuality, HeadRendersAtEveryTierUnderValidation) {
    TempDir dir;
    std::string error;
    auto render = [&](const std::vector<std::string>& extra, const std::string& name) {
        std::vector<std::string> args = {"render",   "--width",    "96",         "--height",
                                         "96",       "--camera",   "cheek_nose", "--validation",
                                         "--device", testDevice(), "--out",      (dir / name).string()};
        args.insert(args.end(), extra.begin(), extra.end());
        const ProcessResult r = runCli(args, dir.path(), 120.0);
        EXPECT_EQ(r.exitCode, 0) << r.err;
        EXPECT_EQ(r.err.find("Validation"), std::string::npos) << r.err;
        return readPng(dir / name, error);
    };
    const RenderedImage byDefault = render({}, "default.png");
    const RenderedImage high = render({"--skin-quality", "high"}, "high.png");
    int largest = 0;
    EXPECT_EQ(pixelsDifferingBy(byDefault, high, 0, largest), 0u) << "high is today's image";
    for (const char* tier : {"medium", "low"}) {
        const RenderedImage lower = render({"--skin-quality", tier}, std::string(tier) + ".png");
        EXPECT_GT(pixelsDifferingBy(high, lower, 2, largest), 20u) << tier << " leaves techniques out";
    }
}

// Below medium no skin pipeline reads the wide shadow map (penumbra scattering is off), so its
// reduction is not recorded: a low frame is the same, pixel for pixel, whether the map was never
// written or a high frame wrote it just before, and the frame still lists the pass.
class SkinQualityPasses : public GpuTest {};

TEST_F(SkinQualityPasses, LowSkipsTheWideShadowMapAndKeepsItsPixels) {
    const Scene scene = Scene::load(std::string(PRESKIN_SOURCE_DIR) + "/samples/assets/head/head.gltf");
    const LutSet& luts = LutSet::loadDefault();
    const Environment environment = Environment::constant(glm::vec3(0.2f));
    const View view = frameBoundsView(scene.worldBounds(), 1.0f);
    RenderSettings low;
    low.skinQuality = SkinQuality::Low;
    RenderSettings high;
    high.skinQuality = SkinQuality::High;
    Renderer fresh(context(), scene, environment, &luts, low);
    const RenderedImage never = fresh.render(view, 96, 96, OutputEncoding::DisplaySrgb8);
    Renderer used(context(), scene, environment, &luts, high);
    const RenderedImage highFrame = used.render(view, 96, 96, OutputEncoding::DisplaySrgb8);
    used.setSettings(low);
    const RenderedImage afterHigh = used.render(view, 96, 96, OutputEncoding::DisplaySrgb8);
    int largest = 0;
    EXPECT_EQ(pixelsDifferingBy(never, afterHigh, 0, largest), 0u) << "largest difference " << largest;
    EXPECT_GT(pixelsDifferingBy(highFrame, afterHigh, 2, largest), 20u) << "low leaves the wide shadow map out";
    bool listed = false;
    for (const PassTime& p : used.frameStats().passes) listed = listed || p.name == "shadow reduction";
    EXPECT_TRUE(listed);
}

TEST(SkinQuality, MaterialTierFromTheSceneAndTheOverride) {
    TempDir dir;
    GltfBuilder b = triangleScene();
    b.doc["extensionsUsed"] = {"PRESKIN_materials_skin"};
    b.doc["materials"] = nlohmann::json::array({{{"extensions", {{"PRESKIN_materials_skin", {{"quality", "low"}}}}}}});
    b.doc["meshes"][0]["primitives"][0]["material"] = 0;
    const Scene scene = Scene::load(b.writeGltf(dir.path(), "low"));
    ASSERT_TRUE(scene.materials.at(0).skin.has_value());
    EXPECT_EQ(scene.materials[0].skin->quality, SkinQuality::Low);
    b.doc["materials"][0]["extensions"]["PRESKIN_materials_skin"]["quality"] = "best";
    const fs::path bad = b.writeGltf(dir.path(), "bad");
    try {
        (void)Scene::load(bad);
        ADD_FAILURE() << "an unknown tier loaded";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("materials[0].extensions.PRESKIN_materials_skin.quality: 'best' "
                                             "(expected low, medium or high)"),
                  std::string::npos)
            << e.what();
    }
}

class SkinQualityFidelity : public GpuTest {};

// The RMSE of an image against the diffusion reference over the reference's skin pixels.
double referenceError(const ReferenceImage& truth, const RenderedImage& image) {
    double squared = 0.0;
    for (size_t i = 0; i < truth.skin.size(); ++i)
        if (truth.skin[i])
            for (int c = 0; c < 3; ++c)
                squared +=
                    std::pow(double(image.rgba32f[4 * i + size_t(c)]) - double(truth.rgba32f[4 * i + size_t(c)]), 2.0);
    return std::sqrt(squared);
}

// The 10 mm sphere of SkinFidelity.WholeSphereIsFarCloserToTheReferenceThanLambert at each tier.
TEST_F(SkinQualityFidelity, EveryTierIsFarCloserToTheReferenceThanLambertOnTheSphere) {
    constexpr uint32_t kSize = 64;
    Primitive sphere = makeSphere(0.005f, 64, 32);
    recomputeCurvature(sphere);
    sphere.material = 0;
    Scene scene = makeScene({{sphere, glm::mat4(1.0f)}}, {skinMaterial({0.8f, 0.6f, 0.5f})});
    scene.lights = {shadowedDirectionalLight({0.8f, -0.35f, -0.5f}, 3.0f)};
    const View view = orbitView(scene.worldBounds(), 0.0f, 8.0f, 0.0f, 1.0f);
    const DiffusionReference reference(scene, scene.lights, ShRgb{}, LutSet::loadDefault().profile());
    const ReferenceImage truth = reference.render(view.eye(), kSize, kSize);
    auto render = [&](const RenderSettings& settings) {
        Renderer renderer(context(), scene, Environment::constant(glm::vec3(0.0f)), &LutSet::loadDefault(), settings);
        return renderer.render(view, kSize, kSize, OutputEncoding::LinearFloat);
    };
    RenderSettings lambertSettings;
    lambertSettings.specular = false;
    lambertSettings.skin = SkinFeatures::none();
    const RenderedImage lambert = render(lambertSettings);
    auto error = [&](const RenderedImage& image) { return referenceError(truth, image); };
    const double lambertError = error(lambert);
    // Bounds: high as SkinFidelity's 0.3; the lower tiers leave out techniques this sphere barely
    // needs (no cast shadow, no gap), so they stay close.
    for (const auto& [tier, bound] :
         {std::pair{SkinQuality::High, 0.3}, std::pair{SkinQuality::Medium, 0.3}, std::pair{SkinQuality::Low, 0.4}}) {
        RenderSettings settings;
        settings.specular = false;
        settings.skinQuality = tier;
        const double ratio = error(render(settings)) / lambertError;
        std::printf("[ quality  ] 10 mm sphere, tier %d: skin / Lambert RMSE %.3f\n", int(tier), ratio);
        EXPECT_LT(ratio, bound) << int(tier);
    }
}

// Lights other than the shadow light: every tier shades them with the fragment's LUT row fitted by
// a smoothed ramp (preskinDiffuseRowFit), lutOtherLights reads the table; low shades every light so.
// Spheres of 10 and 3 mm under a light
// that casts no shadow, from the side, against the diffusion reference: the fit keeps most of
// what the table gains over Lambert.
TEST_F(SkinQualityFidelity, LowTiersRowFitIsFarCloserToTheReferenceThanLambert) {
    constexpr uint32_t kSize = 64;
    for (const float radiusM : {0.005f, 0.0015f}) {
        Primitive sphere = makeSphere(radiusM, 64, 32);
        recomputeCurvature(sphere);
        sphere.material = 0;
        Scene scene = makeScene({{sphere, glm::mat4(1.0f)}}, {skinMaterial({0.8f, 0.6f, 0.5f})});
        Light light = shadowedDirectionalLight({0.9f, -0.2f, -0.3f}, 3.0f);
        light.castsShadow = false;
        scene.lights = {light};
        const View view = orbitView(scene.worldBounds(), 0.0f, 8.0f, 0.0f, 1.0f);
        const DiffusionReference reference(scene, scene.lights, ShRgb{}, LutSet::loadDefault().profile());
        const ReferenceImage truth = reference.render(view.eye(), kSize, kSize);
        auto error = [&](const RenderSettings& base, std::optional<SkinQuality> tier) {
            RenderSettings settings = base;
            settings.specular = false;
            settings.skinQuality = tier;
            Renderer renderer(context(), scene, Environment::constant(glm::vec3(0.0f)), &LutSet::loadDefault(),
                              settings);
            return referenceError(truth, renderer.render(view, kSize, kSize, OutputEncoding::LinearFloat));
        };
        RenderSettings lambertSettings;
        lambertSettings.skin = SkinFeatures::none();
        const double lambert = error(lambertSettings, std::nullopt);
        // Without a shadow map high reads the table for every light (Renderer: no shadow light to
        // tell the key by); low shades every light by the fit.
        const double high = error(RenderSettings{}, SkinQuality::High) / lambert;
        const double low = error(RenderSettings{}, SkinQuality::Low) / lambert;
        std::printf("[ quality  ] %.1f mm sphere, unshadowed light: skin / Lambert RMSE high %.3f, low %.3f\n",
                    double(radiusM) * 2000.0, high, low);
        EXPECT_LT(high, 0.3);
        EXPECT_LT(low, 0.25);
    }
}

}  // namespace
}  // namespace preskin::test
