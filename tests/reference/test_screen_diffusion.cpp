// The screen-space separable baseline (RenderSettings::diffusion ScreenSpace, render/ScreenDiffusion.h)
// against what it must do:
//  - a flat, uniformly lit skin plane, tilted to the view, leaves the blur unchanged: the same
//    image as the forward pass's unblurred Lambert skin (the kernel is normalised);
//  - a straight cast-shadow edge (a sharp one: a fine shadow map, a narrow filter) on a skin plane matches the ray-traced diffusion reference
//    (DiffusionReference: the profile convolved with the visibility step) within 5 % of the lit
//    level in red, where unblurred Lambert is off by more;
//  - taps across a depth discontinuity do not bleed: a lit skin plate 30 mm above a black skin
//    plane leaves the plane black next to it, and keeps its own edge as bright as its middle;
//    the same plate 0.5 mm above the plane (a continuous surface to the blur) does bleed;
//  - stereo with MSAA 4x: each eye equals the mono frame of that eye, under the validation
//    layers, and the frame reports the baseline's 2 passes and 7 targets with their bytes.
#include "support/GpuTest.h"
#include "support/ImageCompare.h"
#include "support/SkinTestSupport.h"
#include "support/TestScenes.h"

#include <preskin/DiffusionReference.h>
#include <preskin/Error.h>
#include <preskin/LutSet.h>
#include <preskin/Renderer.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace preskin::test {
namespace {

RenderSettings screenSettings() {
    RenderSettings s;
    s.diffusion = Diffusion::ScreenSpace;
    return s;
}

// What the baseline's forward pass shades skin with, drawn by the pre-integrated path: Lambert,
// one normal, plain shadow, Lambert SH; the skin's transmission and dual specular kept.
RenderSettings unblurredSettings() {
    RenderSettings s;
    s.skin = SkinFeatures::none();
    s.skin.transmission = true;
    s.skin.dualSpecular = true;
    return s;
}

using ScreenDiffusion = GpuTest;

TEST_F(ScreenDiffusion, FlatUniformlyLitPlaneIsUnchangedByTheBlur) {
    Primitive plane = makeQuad(0.4f, 4);
    plane.material = 0;
    Scene scene = makeScene({{plane, glm::mat4(1.0f)}}, {skinMaterial(glm::vec3(0.8f, 0.6f, 0.5f))});
    Light light;
    light.type = LightType::Directional;
    light.directionWs = glm::normalize(glm::vec3(0.3f, 0.2f, -1.0f));
    light.intensity = 2.0f;
    scene.lights = {light};
    // 40 mm of the plane from 0.25 m, tilted 40 degrees: depth varies across the view.
    const glm::mat4 worldFromView =
        glm::inverse(glm::lookAt(glm::vec3(0.0f, -0.16f, 0.19f), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f)));
    const View view = perspectiveView(worldFromView, 2.0f * std::atan(0.02f / 0.25f), 1.0f, 0.05f, 2.0f);
    const Environment environment = Environment::constant(glm::vec3(0.1f));
    Renderer renderer(context(), scene, environment, &LutSet::loadDefault(), screenSettings());
    const RenderedImage blurred = renderer.render(view, 96, 96, OutputEncoding::LinearFloat);
    renderer.setSettings(unblurredSettings());
    const RenderedImage plain = renderer.render(view, 96, 96, OutputEncoding::LinearFloat);
    double worst = 0.0;
    for (uint32_t y = 0; y < 96; ++y)
        for (uint32_t x = 0; x < 96; ++x) {
            const glm::dvec3 a = pixelLinear(blurred, x, y), b = pixelLinear(plain, x, y);
            for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(a[c] - b[c]) / std::max(b[c], 1e-3));
        }
    std::printf("[ screen   ] flat plane: largest relative change by the blur %.2e\n", worst);
    EXPECT_LT(worst, 2e-3) << "the blur changed a uniformly lit plane (half-float targets round to 5e-4)";
}

// The SkinPenumbra reference edge (straightEdgeScene) drawn by the baseline.
TEST_F(ScreenDiffusion, StraightShadowEdgeMatchesTheDiffusionReferenceInRed) {
    const StraightEdgeScene edge = straightEdgeScene(0.4f);
    RenderSettings settings = screenSettings();
    settings.specular = false;
    // A sharp edge (what the blur is measured on, not the shadow filter): 0.1 mm texels, sigma 0.5 texel.
    settings.shadowMapSize = 4096;
    settings.shadowSoftnessTexels = 0.5f;
    const Environment dark = Environment::constant(glm::vec3(0.0f));
    Renderer renderer(context(), edge.scene, dark, &LutSet::loadDefault(), settings);
    const RenderedImage screen = renderer.render(edge.view, edge.width, edge.height, OutputEncoding::LinearFloat);
    RenderSettings plainSettings = unblurredSettings();
    plainSettings.specular = false;
    plainSettings.shadowMapSize = settings.shadowMapSize;
    plainSettings.shadowSoftnessTexels = settings.shadowSoftnessTexels;
    renderer.setSettings(plainSettings);
    const RenderedImage plain = renderer.render(edge.view, edge.width, edge.height, OutputEncoding::LinearFloat);
    const DiffusionReference reference(edge.scene, edge.scene.lights, dark.radianceSh(),
                                       LutSet::loadDefault().profile());
    const ReferenceImage truth = reference.render(edge.view.eye(), edge.width, edge.height);
    dumpImage("screen_diffusion_edge", screen);
    const glm::dvec3 worst = largestColumnDifference(screen, truth);
    const glm::dvec3 worstPlain = largestColumnDifference(plain, truth);
    std::printf(
        "[ screen   ] straight edge against the reference: largest difference / lit level R %.3f G %.3f B %.3f "
        "(unblurred Lambert R %.3f G %.3f B %.3f)\n",
        worst.r, worst.g, worst.b, worstPlain.r, worstPlain.g, worstPlain.b);
    EXPECT_LT(worst.r, 0.05);
    EXPECT_GT(worstPlain.r, 0.05) << "the check should tell the blur apart from no blur";
}

// A lit skin plate above a black skin plane, seen from above; `heightM` apart.
struct Discontinuity {
    double planeNearEdge = 0.0;   // brightest red of the plane within 3 mm of the plate's edge
    double plateEdgeRatio = 0.0;  // red of the plate within 1 mm of its edge over its middle's
};

Discontinuity renderDiscontinuity(Context& context, float heightM) {
    Primitive plane = makeQuad(0.2f, 2);
    plane.material = 0;
    Primitive plate = makeQuad(0.2f, 2);
    plate.material = 1;
    // The plate covers x > 0 (its left edge at x = 0, mid-view).
    Scene scene =
        makeScene({{plane, glm::mat4(1.0f)}, {plate, glm::translate(glm::mat4(1.0f), glm::vec3(0.1f, 0.0f, heightM))}},
                  {skinMaterial(glm::vec3(0.0f)), skinMaterial(glm::vec3(0.9f, 0.7f, 0.6f))});
    Light light;
    light.type = LightType::Directional;
    light.directionWs = glm::vec3(0.0f, 0.0f, -1.0f);
    light.intensity = 3.0f;
    scene.lights = {light};
    RenderSettings settings = screenSettings();
    settings.specular = false;
    settings.shadows = false;
    Renderer renderer(context, scene, Environment::constant(glm::vec3(0.0f)), &LutSet::loadDefault(), settings);
    // 24 mm across in 128 pixels, orthographic from above: x = 0 at the image's centre.
    Camera camera;
    camera.orthographic = true;
    camera.xmag = camera.ymag = 0.012f;
    camera.znear = 0.01f;
    camera.zfar = 1.0f;
    camera.worldFromView =
        glm::inverse(glm::lookAt(glm::vec3(0.0f, 0.0f, 0.3f), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f)));
    const View view = cameraView(camera, 1.0f, Bounds{});
    const uint32_t size = 128;
    const RenderedImage image = renderer.render(view, size, size, OutputEncoding::LinearFloat);
    dumpImage(heightM > 0.01f ? "screen_diffusion_step" : "screen_diffusion_ledge", image);
    const double pixelMm = 24.0 / size;
    Discontinuity d;
    double middle = 0.0, edge = 0.0;
    int middleCount = 0, edgeCount = 0;
    for (uint32_t y = 16; y < size - 16; ++y)
        for (uint32_t x = 0; x < size; ++x) {
            const double xMm = (x + 0.5) * pixelMm - 12.0;
            const double red = pixelLinear(image, x, y).r;
            if (xMm < -0.5 && xMm > -3.0) d.planeNearEdge = std::max(d.planeNearEdge, red);
            if (xMm > 0.5 && xMm < 1.0) edge += red, ++edgeCount;
            if (xMm > 8.0) middle += red, ++middleCount;
        }
    d.plateEdgeRatio = (edge / edgeCount) / (middle / middleCount);
    return d;
}

TEST_F(ScreenDiffusion, TapsAcrossADepthDiscontinuityDoNotBleed) {
    const Discontinuity step = renderDiscontinuity(context(), 0.03f);
    const Discontinuity ledge = renderDiscontinuity(context(), 0.0005f);
    std::printf(
        "[ screen   ] 30 mm step: plane next to the plate %.4f, plate's edge / middle %.3f; 0.5 mm ledge: %.4f, "
        "%.3f\n",
        step.planeNearEdge, step.plateEdgeRatio, ledge.planeNearEdge, ledge.plateEdgeRatio);
    EXPECT_LT(step.planeNearEdge, 1e-4) << "light bled from the plate onto the plane 30 mm below";
    EXPECT_NEAR(step.plateEdgeRatio, 1.0, 0.01) << "the plate's edge took in the plane below";
    EXPECT_GT(ledge.planeNearEdge, 0.01)
        << "across a 0.5 mm ledge the blur should carry light, or the check means little";
    EXPECT_LT(ledge.plateEdgeRatio, 0.95);
}

TEST_F(ScreenDiffusion, StereoWithMsaaIsEachEyesMonoFrame) {
    RenderSettings settings = screenSettings();
    settings.msaaSamples = 4;
    const StereoAgainstMono result = stereoAgainstMono(context(), settings);
    for (uint32_t e = 0; e < 2; ++e) {
        std::printf("[ screen   ] stereo MSAA 4x, eye %u against its mono frame: %.3f/255\n", e, result.worst[e]);
        EXPECT_LE(result.worst[e], 1.0) << "eye " << e;
    }
    const FrameStats& stats = result.stereoStats;
    EXPECT_EQ(stats.diffusionPasses, 2u);
    EXPECT_EQ(stats.diffusionTargets, 7u);  // scene, diffuse, surface, intermediate; 3 multisampled
    // 8 bytes per texel (RGBA16F, RG32F) for each, times 4 samples for the multisampled ones.
    const uint64_t layer = uint64_t(96) * 96 * 2;
    EXPECT_EQ(stats.diffusionTargetBytes, layer * 8 * 4 + layer * 8 * 4 * 3);
    RenderSettings odd = settings;
    odd.screenDiffusionTaps = 16;
    Renderer renderer(context(), makeScene({{makeQuad(0.1f, 2), glm::mat4(1.0f)}}, {}),
                      Environment::constant(glm::vec3(0.0f)), &LutSet::loadDefault(), settings);
    EXPECT_THROW(renderer.setSettings(odd), Error);
}

}  // namespace
}  // namespace preskin::test
