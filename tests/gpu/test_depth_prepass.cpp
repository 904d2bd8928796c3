// The forward pass's depth prepass (RenderSettings::depthPrepass): the opaque draws' depth first,
// then the shading draws pass the depth test only where their surface is the one seen. Were the
// prepass's depth not bit for bit the shading draws' (its pipeline has no fragment stage and is
// compiled apart), surfaces would fail their own depth test and leave holes or show what lies
// behind them. So, with it and without it:
//  - the same image, value for value (linear float), on the bundled head (its lids, nose, lips
//    and ears hide parts of itself), skin and standard, mono and stereo, and on a scene of skin
//    spheres drawn far to near with an alpha-masked and a blended quad in front (masked and
//    blended draws take no part in the prepass);
//  - under MSAA 4x the golden tolerance (at most 0.1% of pixels more than 5/255 apart): a pixel
//    that another part of the surface partly hides is shaded at the centroid of its samples, which
//    lavapipe takes over the samples that pass the depth test.
// Validation layers are on (GpuTest).
#include "support/GpuTest.h"
#include "support/ImageCompare.h"
#include "support/TestScenes.h"

#include <preskin/Environment.h>
#include <preskin/LutSet.h>
#include <preskin/Renderer.h>
#include <preskin/Scene.h>
#include <preskin/View.h>

#include <glm/gtc/matrix_transform.hpp>

#include <string>

namespace preskin::test {
namespace {

class DepthPrepass : public GpuTest {};

// Renders `scene` with and without the prepass and expects the same linear values.
void expectSameImage(Context& context, const Scene& scene, const LutSet* luts, RenderSettings settings,
                     const View& view, uint32_t width, uint32_t height, const std::string& what) {
    const Environment ambient = Environment::constant(glm::vec3(0.15f));
    settings.depthPrepass = true;
    Renderer renderer(context, scene, ambient, luts, settings);
    const RenderedImage with = renderer.render(view, width, height, OutputEncoding::LinearFloat);
    settings.depthPrepass = false;
    renderer.setSettings(settings);
    const RenderedImage without = renderer.render(view, width, height, OutputEncoding::LinearFloat);
    ASSERT_EQ(with.rgba32f.size(), without.rgba32f.size()) << what;
    size_t differing = 0;
    size_t lit = 0;
    for (size_t i = 0; i < with.rgba32f.size(); ++i) {
        if (with.rgba32f[i] != without.rgba32f[i]) ++differing;
        if (i % 4 == 0 && with.rgba32f[i] > 0.02f) ++lit;
    }
    EXPECT_EQ(differing, 0u) << what << ": values differ with the depth prepass";
    EXPECT_GT(lit, with.rgba32f.size() / 4 / 10) << what << ": the scene should cover a good part of the image";
}

TEST_F(DepthPrepass, TheHeadLooksTheSameWithAndWithoutIt) {
    const Scene scene = Scene::load(std::string(PRESKIN_SOURCE_DIR) + "/samples/assets/head/head.gltf");
    const LutSet& luts = LutSet::loadDefault();
    const View mono = frameBoundsView(scene.worldBounds(), 96.0f / 112.0f);
    RenderSettings skin;
    expectSameImage(context(), scene, &luts, skin, mono, 96, 112, "head, skin");
    RenderSettings standard;
    standard.skin = SkinFeatures::none();
    expectSameImage(context(), scene, &luts, standard, mono, 96, 112, "head, standard");
    const View side = orbitView(scene.worldBounds(), 80.0f, 10.0f, 0.0f, 1.0f);
    expectSameImage(context(), scene, &luts, skin, side, 96, 96, "head from the side, skin");
    const View stereo = stereoFromMono(frameBoundsView(scene.worldBounds(), 64.0f / 72.0f), 0.063f);
    expectSameImage(context(), scene, &luts, skin, stereo, 64, 72, "head, stereo, skin");
}

TEST_F(DepthPrepass, FarSurfacesDrawnFirstAndMaskedAndBlendedOnesLookTheSame) {
    Material masked;
    masked.baseColorFactor = glm::vec4(0.2f, 0.6f, 0.3f, 1.0f);
    masked.alphaMode = AlphaMode::Mask;
    Material blended;
    blended.baseColorFactor = glm::vec4(0.3f, 0.3f, 0.9f, 0.5f);
    blended.alphaMode = AlphaMode::Blend;
    // Four skin spheres in a row going towards the camera, drawn far to near (each hides part of
    // the one before), then the masked and the blended quad across them.
    std::vector<std::pair<Primitive, glm::mat4>> parts;
    for (int i = 0; i < 4; ++i)
        parts.push_back({makeSphere(0.03f, 32, 16),
                         glm::translate(glm::mat4(1.0f), glm::vec3(0.02f * float(i), 0.0f, 0.025f * float(i)))});
    Primitive maskedQuad = makeQuad(0.05f, 2);
    maskedQuad.material = 1;
    Primitive blendedQuad = makeQuad(0.05f, 2);
    blendedQuad.material = 2;
    parts.push_back({maskedQuad, glm::translate(glm::mat4(1.0f), glm::vec3(-0.03f, 0.02f, 0.09f))});
    parts.push_back({blendedQuad, glm::translate(glm::mat4(1.0f), glm::vec3(0.06f, -0.02f, 0.1f))});
    Scene scene = makeScene(parts, {skinMaterial(glm::vec3(0.8f, 0.55f, 0.45f)), masked, blended});
    Light light;
    light.type = LightType::Directional;
    light.directionWs = glm::normalize(glm::vec3(-0.5f, -0.3f, -1.0f));
    light.intensity = 3.0f;
    scene.lights = {light};
    const glm::mat4 worldFromView = glm::inverse(
        glm::lookAt(glm::vec3(0.03f, 0.0f, 0.4f), glm::vec3(0.03f, 0.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f)));
    const View view = perspectiveView(worldFromView, 0.6f, 1.0f, 0.05f, 5.0f);
    const LutSet& luts = LutSet::loadDefault();
    expectSameImage(context(), scene, &luts, RenderSettings{}, view, 80, 80, "spheres far to near");
}

TEST_F(DepthPrepass, UnderMsaaTheHeadIsWithinTheGoldenTolerance) {
    const Scene scene = Scene::load(std::string(PRESKIN_SOURCE_DIR) + "/samples/assets/head/head.gltf");
    const LutSet& luts = LutSet::loadDefault();
    const Environment ambient = Environment::constant(glm::vec3(0.15f));
    const View view = frameBoundsView(scene.worldBounds(), 1.0f);
    RenderSettings settings;
    settings.msaaSamples = 4;
    Renderer renderer(context(), scene, ambient, &luts, settings);
    const RenderedImage with = renderer.render(view, 128, 128, OutputEncoding::DisplaySrgb8);
    settings.depthPrepass = false;
    renderer.setSettings(settings);
    const RenderedImage without = renderer.render(view, 128, 128, OutputEncoding::DisplaySrgb8);
    int largest = 0;
    const size_t over = pixelsDifferingBy(with, without, 5, largest);
    EXPECT_LE(over, size_t(128 * 128 / 1000)) << "largest difference " << largest << "/255";
}

}  // namespace
}  // namespace preskin::test
