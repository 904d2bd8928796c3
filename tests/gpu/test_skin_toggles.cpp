// The skin techniques' switches (RenderSettings::skin, the shader's kSkin* specialisation bits):
//  - each one, switched off alone, changes the image of a scene made to show it (pixels changed
//    by more than 2/255 counted);
//  - with all of them off the skin path equals the standard path within 1/255 on every pixel of
//    every scene. For that the skin material gets specularIntensity = 0.04 / 0.028, so its F0 is
//    the standard dielectric's 0.04, and the standard material is a dielectric (metallic 0) with
//    the same base colour, roughness and normal map.
// A skin material's optional inputs (a detail normal map, the curvature source) specialise its
// pipeline: each input, when the material has it, still reaches the image; a specular map packed
// into the base colour's alpha renders as the map read on its own.
// Scenes: a normal-mapped skin sphere (2 cm, scatter scale 0.2: it scatters like a 4 mm one) under a shadowed key light with a
// caster and a structured environment (LUT diffuse, normal prefilter, SH ambient, dual specular);
// a skin plane behind a caster with a wide shadow filter (penumbra); a thin skin slab lit from
// behind (transmission).
#include "support/GpuTest.h"
#include "support/ImageCompare.h"
#include "support/SkinTestSupport.h"
#include "support/TestScenes.h"

#include <preskin/LutSet.h>
#include <preskin/Renderer.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace preskin::test {
namespace {

struct ToggleScene {
    std::string name;
    Scene scene;  // its materials are skin
    Environment environment = Environment::constant(glm::vec3(0.0f));
    RenderSettings settings;
    View view;
};

Material skinMaterial(const glm::vec3& albedo, float roughness, float scatterScale) {
    Material m;
    m.baseColorFactor = glm::vec4(albedo, 1.0f);
    m.metallicFactor = 0.0f;
    m.roughnessFactor = roughness;
    SkinMaterial skin;
    skin.scatterScale = scatterScale;
    m.skin = skin;
    return m;
}

View lookAtView(const glm::vec3& eye, const glm::vec3& target, float yfov, float nearM) {
    return perspectiveView(glm::inverse(glm::lookAt(eye, target, glm::vec3(0.0f, 1.0f, 0.0f))), yfov, 1.0f, nearM,
                           10.0f);
}

ToggleScene sphereScene() {
    ToggleScene s;
    s.name = "sphere";
    Primitive sphere = makeSphere(0.02f, 128, 64);
    sphere.material = 0;
    Material skin = skinMaterial({0.78f, 0.55f, 0.45f}, 0.4f, 0.2f);
    Primitive caster = makeBox(glm::vec3(0.03f, 0.03f, 0.002f));
    Material standard;
    standard.baseColorFactor = glm::vec4(0.4f, 0.4f, 0.45f, 1.0f);
    standard.metallicFactor = 0.0f;
    standard.roughnessFactor = 0.6f;
    caster.material = 1;
    const glm::vec3 toLight = glm::normalize(glm::vec3(1.0f, 0.6f, 0.7f));
    // The caster sits towards the light, shifted sideways so its shadow edge crosses the lit side.
    const glm::vec3 side = glm::normalize(glm::cross(toLight, glm::vec3(0.0f, 1.0f, 0.0f)));
    const glm::mat4 casterFrame =
        glm::inverse(glm::lookAt(0.05f * toLight + 0.027f * side, glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f)));
    s.scene = makeScene({{sphere, glm::mat4(1.0f)}, {caster, casterFrame}}, {skin, standard});
    // Bumps of about 10 texels: the red channel's prefiltered normal (derived mip bias ~3.5) loses them.
    const int normalMap = addNormalMap(s.scene, 128, 64, [](glm::vec2 uv) {
        const float pi = 3.14159265f;
        const float dx = 0.5f * std::cos(2.0f * pi * 12.0f * uv.x) * std::sin(2.0f * pi * 6.0f * uv.y);
        const float dy = 0.5f * std::sin(2.0f * pi * 12.0f * uv.x) * std::cos(2.0f * pi * 6.0f * uv.y);
        return glm::vec3(-dx, -dy, 1.0f);
    });
    s.scene.materials[0].normal.image = normalMap;
    Light key;
    key.type = LightType::Directional;
    key.directionWs = -toLight;
    key.intensity = 2.0f;
    key.castsShadow = true;
    s.scene.lights = {key};
    s.environment = makeEnvironment(64, [](const glm::vec3& d) {
        return glm::vec3(0.4f, 0.34f, 0.3f) * (1.0f + 0.8f * d.y + 0.2f * d.x * d.z) +
            glm::vec3(0.0f, 0.05f, 0.1f) * d.x;
    });
    s.view = lookAtView(glm::vec3(0.0f, 0.01f, 0.1f), glm::vec3(0.0f), 0.5f, 0.01f);
    return s;
}

ToggleScene penumbraScene() {
    ToggleScene s;
    s.name = "penumbra";
    Primitive plane = makeQuad(0.4f, 4);
    plane.material = 0;
    Primitive caster = makeBox(glm::vec3(0.2f, 0.5f, 0.01f));
    caster.material = 0;
    s.scene =
        makeScene({{plane, glm::mat4(1.0f)}, {caster, glm::translate(glm::mat4(1.0f), glm::vec3(0.15f, 0.0f, 0.1f))}},
                  {skinMaterial({0.8f, 0.8f, 0.8f}, 0.7f, 0.5f)});
    Light light;
    light.type = LightType::Directional;
    light.directionWs = glm::normalize(glm::vec3(-1.0f, 0.0f, -1.0f));
    light.intensity = 2.5f;
    light.castsShadow = true;
    s.scene.lights = {light};
    s.environment = Environment::constant(glm::vec3(0.05f));
    s.settings.shadowMapSize = 512;
    s.view = lookAtView(glm::vec3(-0.05f, 0.0f, 0.5f), glm::vec3(-0.05f, 0.0f, 0.0f), 0.06f, 0.05f);
    return s;
}

ToggleScene transmissionScene() {
    ToggleScene s;
    s.name = "transmission";
    Primitive slab = makeBox(glm::vec3(0.08f, 0.08f, 0.003f));
    slab.material = 0;
    s.scene = makeScene({{slab, glm::mat4(1.0f)}}, {skinMaterial({0.8f, 0.6f, 0.5f}, 0.6f, 1.0f)});
    Light light;
    light.type = LightType::Directional;
    light.directionWs = glm::normalize(glm::vec3(0.2f, -0.1f, 1.0f));  // from behind
    light.intensity = 3.0f;
    light.castsShadow = true;
    s.scene.lights = {light};
    s.environment = Environment::constant(glm::vec3(0.02f));
    s.view = lookAtView(glm::vec3(0.0f, 0.0f, 0.2f), glm::vec3(0.0f), 0.6f, 0.01f);
    return s;
}

// The underside of an overhang seen from below, lit across the gap by the floor under it.
ToggleScene overhangToggleScene() {
    ToggleScene s;
    s.name = "overhang";
    s.scene = overhangScene();
    s.view = lookAtView(glm::vec3(-0.01f, 0.0f, -0.06f), glm::vec3(-0.01f, 0.0f, 0.0f), 0.6f, 0.01f);
    return s;
}

constexpr uint32_t kSize = 128;

class SkinToggles : public GpuTest {};

TEST_F(SkinToggles, EachTechniqueChangesTheImage) {
    struct Case {
        const char* name;
        bool SkinFeatures::*feature;
        ToggleScene* scene;
    };
    ToggleScene sphere = sphereScene();
    ToggleScene penumbra = penumbraScene();
    ToggleScene transmission = transmissionScene();
    ToggleScene overhang = overhangToggleScene();
    const std::vector<Case> cases = {{"lutDiffuse", &SkinFeatures::lutDiffuse, &sphere},
                                     {"normalPrefilter", &SkinFeatures::normalPrefilter, &sphere},
                                     {"normalMapLevels", &SkinFeatures::normalMapLevels, &sphere},
                                     {"shAmbient", &SkinFeatures::shAmbient, &sphere},
                                     {"dualSpecular", &SkinFeatures::dualSpecular, &sphere},
                                     {"penumbra", &SkinFeatures::penumbra, &penumbra},
                                     {"widePenumbra", &SkinFeatures::widePenumbra, &penumbra},
                                     {"transmission", &SkinFeatures::transmission, &transmission},
                                     {"opposingLight", &SkinFeatures::opposingLight, &overhang}};
    const LutSet& luts = LutSet::loadDefault();
    for (ToggleScene* s : {&sphere, &penumbra, &transmission, &overhang}) {
        Renderer renderer(context(), s->scene, s->environment, &luts, s->settings);
        const RenderedImage all = renderer.render(s->view, kSize, kSize, OutputEncoding::LinearFloat);
        dumpImage("skin_toggles_" + s->name + "_all", all);
        for (const Case& c : cases) {
            if (c.scene != s) continue;
            RenderSettings settings = s->settings;
            settings.skin.*c.feature = false;
            renderer.setSettings(settings);
            const RenderedImage without = renderer.render(s->view, kSize, kSize, OutputEncoding::LinearFloat);
            dumpImage("skin_toggles_" + s->name + "_no_" + c.name, without);
            const size_t changed = countDifferingPixels(all, without, 2.0);
            std::printf("[ skin     ] switching %-15s off changes %5zu pixels by > 2/255 (largest %.1f/255)\n", c.name,
                        changed, maxSrgbDifference(all, without));
            EXPECT_GE(changed, size_t(kSize * kSize / 100)) << c.name << " off should change at least 1% of the image";
        }
    }
}

// A uniform image of one grey level (red = green = blue = value / 255).
int addUniformImage(Scene& scene, uint8_t value) {
    Image image;
    image.name = "uniform";
    image.width = image.height = 4;
    image.rgba8.assign(4 * 4 * 4, value);
    for (size_t i = 3; i < image.rgba8.size(); i += 4) image.rgba8[i] = 255;
    scene.images.push_back(std::move(image));
    return static_cast<int>(scene.images.size()) - 1;
}

// A 4x4 image whose colour channels hold `value` at 16 bits (rgba8 their rounding, as the loader makes it).
int addUniformImage16(Scene& scene, uint16_t value) {
    const int index = addUniformImage(scene, static_cast<uint8_t>((uint32_t(value) * 255u + 32895u) >> 16));
    Image& image = scene.images[size_t(index)];
    image.rgba16.assign(image.rgba8.size(), value);
    for (size_t i = 3; i < image.rgba16.size(); i += 4) image.rgba16[i] = 65535;
    return index;
}

// `scene` (the sphere scene's, changed) rendered with the sphere scene's environment, settings and view.
RenderedImage renderSphereView(Context& context, const ToggleScene& s, const Scene& scene) {
    Renderer renderer(context, scene, s.environment, &LutSet::loadDefault(), s.settings);
    return renderer.render(s.view, kSize, kSize, OutputEncoding::LinearFloat);
}

TEST_F(SkinToggles, MaterialInputsReachTheImage) {
    const ToggleScene s = sphereScene();
    auto render = [&](const Scene& scene) { return renderSphereView(context(), s, scene); };
    const RenderedImage vertex = render(s.scene);
    // Curvature from a texture: the sphere's own curvature (1 / 2 cm = 50 / m) as a uniform
    // texture renders as the per-vertex curvature does; a texture of 0 (flat skin) does not.
    Scene textured = s.scene;
    SkinMaterial& skin = *textured.materials[0].skin;
    skin.curvatureSource = CurvatureSource::Texture;
    skin.curvatureTextureScalePerM = 50.0f * 255.0f / 200.0f;  // texel 200 / 255 -> 50 / m
    skin.curvatureTexture.image = addUniformImage(textured, 200);
    const RenderedImage fromTexture = render(textured);
    skin.curvatureTexture.image = addUniformImage(textured, 0);
    const RenderedImage flat = render(textured);
    const size_t textureVsVertex = countDifferingPixels(vertex, fromTexture, 2.0);
    const size_t flatVsVertex = countDifferingPixels(vertex, flat, 2.0);
    std::printf(
        "[ skin     ] curvature texture: %zu pixels differ from per-vertex curvature by > 2/255; a flat one: %zu\n",
        textureVsVertex, flatVsVertex);
    EXPECT_LE(textureVsVertex, size_t(kSize * kSize / 200));
    EXPECT_GE(flatVsVertex, size_t(kSize * kSize / 100));
    // A signed map: the bias is the value of zero curvature, so texel 200 with bias 200 / 255 is flat.
    skin.curvatureTexture.image = addUniformImage(textured, 200);
    skin.curvatureTextureBias = 200.0f / 255.0f;
    EXPECT_LE(maxSrgbDifference(render(textured), flat), 1.0);
    // A 16-bit map keeps its precision: with a range so wide that 50 / m is texel 32 of 65535, its
    // 8-bit rounding would be 0 (flat skin); the 16-bit texture renders the sphere's curvature.
    skin.curvatureTextureBias = 0.0f;
    skin.curvatureTextureScalePerM = 50.0f * 65535.0f / 32.0f;
    skin.curvatureTexture.image = addUniformImage16(textured, 32);
    ASSERT_EQ(textured.images.back().rgba8[0], 0);
    const size_t sixteenVsVertex = countDifferingPixels(vertex, render(textured), 2.0);
    std::printf("[ skin     ] 16-bit curvature texture: %zu pixels differ from per-vertex curvature by > 2/255\n",
                sixteenVsVertex);
    EXPECT_LE(sixteenVsVertex, size_t(kSize * kSize / 200));
    // A detail normal map: flat (128, 128, 255) leaves the image as it is, a tilted one changes it.
    Scene detailed = s.scene;
    SkinMaterial& d = *detailed.materials[0].skin;
    d.detailNormalScale = 1.0f;
    d.detailNormalTexture.image = addNormalMap(detailed, 8, 8, [](glm::vec2) { return glm::vec3(0.0f, 0.0f, 1.0f); });
    const RenderedImage flatDetail = render(detailed);
    d.detailNormalTexture.image = addNormalMap(detailed, 8, 8, [](glm::vec2) { return glm::vec3(0.5f, 0.0f, 1.0f); });
    const RenderedImage tiltedDetail = render(detailed);
    const size_t flatDetailChanged = countDifferingPixels(vertex, flatDetail, 2.0);
    const size_t tiltedDetailChanged = countDifferingPixels(vertex, tiltedDetail, 2.0);
    std::printf("[ skin     ] detail normal map: flat changes %zu pixels by > 2/255, tilted %zu\n", flatDetailChanged,
                tiltedDetailChanged);
    EXPECT_LE(flatDetailChanged, size_t(kSize * kSize / 200));
    EXPECT_GE(tiltedDetailChanged, size_t(kSize * kSize / 20));
}

// An image whose texels are colour(u, v) (0..1 per channel, alpha 1).
int addPatternImage(Scene& scene, uint32_t size, const std::function<glm::vec3(float, float)>& colour) {
    Image image;
    image.name = "pattern";
    image.width = image.height = size;
    image.rgba8.resize(size_t(size) * size * 4);
    for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 0; x < size; ++x) {
            const glm::vec3 c = colour((float(x) + 0.5f) / float(size), (float(y) + 0.5f) / float(size));
            uint8_t* t = &image.rgba8[4 * (size_t(y) * size + x)];
            for (int k = 0; k < 3; ++k) t[k] = static_cast<uint8_t>(std::lround(255.0f * std::clamp(c[k], 0.0f, 1.0f)));
            t[3] = 255;
        }
    scene.images.push_back(std::move(image));
    return static_cast<int>(scene.images.size()) - 1;
}

// An opaque skin material's specular map travels in its base colour's unused alpha where both
// share a sampler and a size (GpuScene: one texture read fewer per fragment). Through two
// identical samplers (not packed) the image must be the same within 1/255, and the packed map
// must still reach the image: a map of 0 in its place changes the highlights.
TEST_F(SkinToggles, SpecularMapInTheBaseColourAlphaRendersAsTheMapItself) {
    const ToggleScene s = sphereScene();
    auto render = [&](const Scene& scene) { return renderSphereView(context(), s, scene); };
    const float pi = 3.14159265f;
    Scene scene = s.scene;
    scene.samplers = {Sampler{}, Sampler{}};
    Material& m = scene.materials[0];
    m.baseColor.image = addPatternImage(scene, 64, [&](float u, float v) {
        return glm::vec3(0.8f, 0.55f + 0.2f * std::sin(2.0f * pi * 5.0f * u),
                         0.45f + 0.2f * std::cos(2.0f * pi * 3.0f * v));
    });
    const int pattern = addPatternImage(scene, 64, [&](float u, float v) {
        return glm::vec3(0.5f + 0.5f * std::sin(2.0f * pi * 7.0f * u) * std::sin(2.0f * pi * 4.0f * v));
    });
    m.baseColor.sampler = 0;
    m.baseColorFactor.a = 0.5f;  // unused by an opaque material, and not the specular map's either
    m.skin->specularTexture = SkinTextureRef{pattern, 0};
    const RenderedImage packed = render(scene);
    m.skin->specularTexture.sampler = 1;
    const RenderedImage apart = render(scene);
    dumpImage("skin_specular_packed", packed);
    dumpImage("skin_specular_apart", apart);
    const double packedVsApart = maxSrgbDifference(packed, apart);
    m.skin->specularTexture =
        SkinTextureRef{addPatternImage(scene, 64, [](float, float) { return glm::vec3(0.0f); }), 0};
    const size_t noSpecularChanged = countDifferingPixels(packed, render(scene), 2.0);
    std::printf(
        "[ skin     ] specular map in the base colour's alpha: %.2f/255 from the map read apart; a map of 0 "
        "changes %zu pixels by > 2/255\n",
        packedVsApart, noSpecularChanged);
    EXPECT_LE(packedVsApart, 1.0);
    EXPECT_GE(noSpecularChanged, size_t(kSize * kSize / 50));
}

// The shadow map belongs to the light flagged castsShadow wherever the scene lists it: with an
// unshadowed directional fill light listed first, the image (linear, no ambient) is the sum of
// the images of the two lights alone, for skin and for the standard material, and the key's cast
// shadow darkens part of the plane while the fill lights it.
TEST_F(SkinToggles, ShadowLightIsTheCasterWhereverItIsListed) {
    const LutSet& luts = LutSet::loadDefault();
    for (bool skin : {true, false}) {
        ToggleScene s = penumbraScene();
        s.environment = Environment::constant(glm::vec3(0.0f));
        if (!skin)
            for (Material& m : s.scene.materials) m.skin.reset();
        Light key = s.scene.lights[0];
        Light fill;
        fill.type = LightType::Directional;
        fill.directionWs = glm::normalize(glm::vec3(0.6f, 0.3f, -1.0f));
        fill.intensity = 1.5f;
        auto render = [&](const std::vector<Light>& lights) {
            Scene scene = s.scene;
            scene.lights = lights;
            Renderer renderer(context(), scene, s.environment, &luts, s.settings);
            return renderer.render(s.view, kSize, kSize, OutputEncoding::LinearFloat);
        };
        const RenderedImage both = render({fill, key});
        const RenderedImage fillAlone = render({fill});
        const RenderedImage keyAlone = render({key});
        double worst = 0.0;
        size_t keyShadowed = 0;
        for (size_t p = 0; p < size_t(kSize) * kSize; ++p) {
            for (size_t c = 0; c < 3; ++c) {
                const size_t i = p * 4 + c;
                const double sum = double(fillAlone.rgba32f[i]) + double(keyAlone.rgba32f[i]);
                worst = std::max(worst, std::abs(double(both.rgba32f[i]) - sum) / std::max(sum, 0.05));
            }
            const size_t g = p * 4 + 1;
            if (keyAlone.rgba32f[g] < 0.02f * fillAlone.rgba32f[g] && fillAlone.rgba32f[g] > 0.05f) ++keyShadowed;
        }
        std::printf(
            "[ lights   ] %s: fill + key against the sum of each alone: largest relative difference %.2e; "
            "%zu pixels in the key's shadow and the fill's light\n",
            skin ? "skin" : "standard", worst, keyShadowed);
        EXPECT_LT(worst, 1e-3) << (skin ? "skin" : "standard");
        EXPECT_GE(keyShadowed, size_t(kSize * kSize / 50)) << (skin ? "skin" : "standard");
    }
}

// The diffuse LUT's reads by light (kSkinLutShadowLight, kSkinLutOtherLights): by default (high)
// the shadow light reads the table and every other light gets the fragment's row fit, and
// without a shadow map every light reads the table. On the sphere scene (a scattering radius of
// about 4 mm, where the fit and the table part near the terminator): with its shadowed key light
// alone, turning the shadow light's table off moves the image and adding the other lights' does
// not; with an unshadowed fill light beside it, adding the other lights' table moves it; with the
// key's shadow off (no shadow map), adding it changes nothing and the shadow light's switch
// decides for every light.
TEST_F(SkinToggles, ShadowLightReadsTheDiffuseLutTheOtherLightsItsRowFit) {
    // The largest change of a linear colour value, as a share of the image's brightest value.
    auto largestChange = [](const RenderedImage& a, const RenderedImage& b) {
        double change = 0.0, peak = 0.0;
        for (size_t i = 0; i < a.rgba32f.size(); ++i) {
            if (i % 4 == 3) continue;
            change = std::max(change, std::abs(double(a.rgba32f[i]) - double(b.rgba32f[i])));
            peak = std::max(peak, double(a.rgba32f[i]));
        }
        return change / std::max(peak, 1e-6);
    };
    Light fill;
    fill.type = LightType::Directional;
    fill.directionWs = glm::normalize(glm::vec3(0.7f, -0.2f, -0.7f));
    fill.intensity = 1.0f;
    struct Case {
        const char* name;
        bool castsShadow, withFill, otherLightsMove;
    };
    for (const Case& c : {Case{"shadowed key", true, false, false}, Case{"shadowed key and fill", true, true, true},
                          Case{"unshadowed key", false, false, false}}) {
        ToggleScene s = sphereScene();
        s.scene.lights[0].castsShadow = c.castsShadow;
        if (c.withFill) s.scene.lights.push_back(fill);
        Renderer renderer(context(), s.scene, s.environment, &LutSet::loadDefault(), s.settings);
        auto render = [&](bool shadowLight, bool otherLights) {
            RenderSettings settings = s.settings;
            settings.skin.lutShadowLight = shadowLight;
            settings.skin.lutOtherLights = otherLights;
            renderer.setSettings(settings);
            return renderer.render(s.view, kSize, kSize, OutputEncoding::LinearFloat);
        };
        const RenderedImage high = render(true, false);
        const double shadowLightOff = largestChange(high, render(false, false));
        const double otherLightsOn = largestChange(high, render(true, true));
        std::printf(
            "[ skin     ] %s: the shadow light's table off moves a value by %.4f of the brightest, the other "
            "lights' table on by %.4f\n",
            c.name, shadowLightOff, otherLightsOn);
        EXPECT_GE(shadowLightOff, 0.001) << c.name;
        if (c.otherLightsMove) {
            EXPECT_GE(otherLightsOn, 0.001) << c.name;
        } else {
            EXPECT_EQ(otherLightsOn, 0.0) << c.name;
        }
    }
}

TEST_F(SkinToggles, AllOffEqualsStandardPath) {
    const LutSet& luts = LutSet::loadDefault();
    for (ToggleScene s : {sphereScene(), penumbraScene(), transmissionScene()}) {
        Scene standard = s.scene;
        for (Material& m : s.scene.materials)
            if (m.skin) m.skin->specularIntensity = 0.04f / 0.028f;  // F0 = 0.028 * intensity = 0.04
        for (Material& m : standard.materials) m.skin.reset();
        RenderSettings off = s.settings;
        off.skin = SkinFeatures::none();
        off.fitShadowToSkin = false;  // the same shadow map for both scenes (one has no skin to fit it to)
        Renderer skinRenderer(context(), s.scene, s.environment, &luts, off);
        Renderer standardRenderer(context(), standard, s.environment, &luts, off);
        const RenderedImage skinImage = skinRenderer.render(s.view, kSize, kSize, OutputEncoding::LinearFloat);
        const RenderedImage standardImage = standardRenderer.render(s.view, kSize, kSize, OutputEncoding::LinearFloat);
        dumpImage("skin_all_off_" + s.name, skinImage);
        dumpImage("standard_" + s.name, standardImage);
        // Not vacuous: most of the view shows the scene (differs from the background in the
        // corner by more than 10/255).
        const glm::dvec3 background = pixelLinear(standardImage, 0, 0);
        size_t lit = 0;
        for (uint32_t y = 0; y < kSize; ++y)
            for (uint32_t x = 0; x < kSize; ++x)
                if (srgbDifference(pixelLinear(standardImage, x, y), background) > 10.0) ++lit;
        const double worst = maxSrgbDifference(skinImage, standardImage);
        std::printf("[ skin     ] all techniques off vs standard (%s): worst %.3f/255 over %zu scene pixels\n",
                    s.name.c_str(), worst, lit);
        EXPECT_GT(lit, size_t(kSize * kSize / 4)) << s.name;
        EXPECT_LE(worst, 1.0) << s.name << ": skin with every technique off should equal the standard path";
    }
}

}  // namespace
}  // namespace preskin::test
