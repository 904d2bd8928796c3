// The texture-space baseline (RenderSettings::diffusion TextureSpace, render/TextureDiffusion.h)
// against what it must do:
//  - the profile's Gaussians: a sum-of-Gaussians profile keeps its own; a fitted one (Burley)
//    reproduces the profile's edge response within 1 % (independent: DiffusionProfile::edgeResponse);
//  - a straight cast-shadow edge on a UV-mapped skin plane (irradiance blurred in UV) matches the
//    ray-traced diffusion reference within 5 % of the lit level in red;
//  - a sphere lit from the side shows no line along its UV seam (u = 0 and 1 meet) beyond 5/255,
//    from every side;
//  - stereo with MSAA 4x: each eye equals the mono frame of that eye (no specular, so the
//    irradiance, lit as eye 0 sees it, is the same for both), under the validation layers, and
//    the frame reports its passes and textures;
//  - textures beyond 2 GB are refused with an error naming the setting, before anything is drawn.
#include "support/GpuTest.h"
#include "support/ImageCompare.h"
#include "support/SkinTestSupport.h"
#include "support/TestScenes.h"

#include "skin/GaussianFit.h"

#include <preskin/DiffusionReference.h>
#include <preskin/Error.h>
#include <preskin/LutSet.h>
#include <preskin/Renderer.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace preskin::test {
namespace {

RenderSettings textureSettings() {
    RenderSettings s;
    s.diffusion = Diffusion::TextureSpace;
    return s;
}

TEST(GaussianFit, OwnTermsOrAFitThatKeepsTheEdgeResponse) {
    const DiffusionProfile deon = DiffusionProfile::deonLuebke();
    const std::vector<GaussianTerm> own = normalizedGaussians(deon);
    ASSERT_EQ(own.size(), deon.gaussians().size());
    const DiffusionProfile burley = DiffusionProfile::burley(glm::dvec3(0.8, 0.5, 0.3), glm::dvec3(3.0, 1.5, 0.8));
    const std::vector<GaussianTerm> fit = normalizedGaussians(burley);
    glm::dvec3 sum(0.0);
    for (const GaussianTerm& t : fit) sum += t.weight;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c], 1.0, 1e-9);
    double worst = 0.0;
    for (double x = -10.0; x <= 10.0; x += 0.05) {
        glm::dvec3 edge(0.0);  // a sum of Gaussians' edge response: Phi(x / sigma) per term
        for (const GaussianTerm& t : fit) edge += t.weight * 0.5 * std::erfc(-x / std::sqrt(2.0 * t.varianceMm2));
        const glm::dvec3 want = burley.edgeResponse(x);
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(edge[c] - want[c]));
    }
    std::printf("[ texture  ] Burley's profile as %zu Gaussians: edge response within %.4f\n", fit.size(), worst);
    EXPECT_LT(worst, 0.01);
}

using TextureDiffusion = GpuTest;

TEST_F(TextureDiffusion, StraightShadowEdgeMatchesTheDiffusionReferenceInRed) {
    // A 0.1 m skin plane (1024 texels: 0.1 mm each) under the plate whose shadow edge crosses it.
    const StraightEdgeScene edge = straightEdgeScene(0.1f);
    RenderSettings settings = textureSettings();
    settings.specular = false;
    settings.shadowMapSize = 4096;  // a sharp edge: what the blur is measured on
    settings.shadowSoftnessTexels = 0.5f;
    const Environment dark = Environment::constant(glm::vec3(0.0f));
    Renderer renderer(context(), edge.scene, dark, &LutSet::loadDefault(), settings);
    const RenderedImage texture = renderer.render(edge.view, edge.width, edge.height, OutputEncoding::LinearFloat);
    const FrameStats stats = renderer.frameStats();
    const DiffusionReference reference(edge.scene, edge.scene.lights, dark.radianceSh(),
                                       LutSet::loadDefault().profile());
    const ReferenceImage truth = reference.render(edge.view.eye(), edge.width, edge.height);
    dumpImage("texture_diffusion_edge", texture);
    const glm::dvec3 worst = largestColumnDifference(texture, truth);
    std::printf(
        "[ texture  ] straight edge against the reference: largest difference / lit level R %.3f G %.3f B %.3f\n",
        worst.r, worst.g, worst.b);
    EXPECT_LT(worst.r, 0.05);
    // One skin draw, d'Eon's six Gaussians: the irradiance pass and two passes per Gaussian.
    EXPECT_EQ(stats.diffusionPasses, 1u + 2u * 6u);
    EXPECT_EQ(stats.diffusionTargets, 5u);
    EXPECT_EQ(stats.diffusionTargetBytes, uint64_t(1024) * 1024 * (4 * 8 + 4));
}

TEST_F(TextureDiffusion, NoLineAlongTheUvSeam) {
    // A 40 mm sphere whose UV seam (u = 0 and 1 meet) runs down its +Z side, seen from +Z under a
    // light from the side and above (the irradiance changes across the seam, where each side's
    // blur sees only its own side of the UV layout), against the same sphere turned half a turn
    // about Y (its tessellation maps onto itself, the seam now on the far side): what differs is
    // the seam's doing.
    const View view = perspectiveView(
        glm::inverse(glm::lookAt(glm::vec3(0.0f, 0.0f, 0.12f), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f))), 0.45f,
        1.0f, 0.01f, 1.0f);
    RenderSettings settings = textureSettings();
    settings.specular = false;
    settings.shadows = false;
    Light light;
    light.type = LightType::Directional;
    light.directionWs = glm::normalize(glm::vec3(-1.0f, -0.6f, -0.8f));
    light.intensity = 2.0f;
    std::vector<RenderedImage> images;
    for (float turn : {0.0f, 3.14159265f}) {
        Primitive sphere = makeSphere(0.02f, 96, 48);
        sphere.material = 0;
        Scene scene = makeScene({{sphere, glm::rotate(glm::mat4(1.0f), turn, glm::vec3(0.0f, 1.0f, 0.0f))}},
                                {skinMaterial(glm::vec3(0.8f, 0.6f, 0.5f))});
        scene.lights = {light};
        Renderer renderer(context(), scene, Environment::constant(glm::vec3(0.1f)), &LutSet::loadDefault(), settings);
        images.push_back(renderer.render(view, 128, 128, OutputEncoding::LinearFloat));
    }
    dumpImage("texture_diffusion_seam_front", images[0]);
    dumpImage("texture_diffusion_seam_back", images[1]);
    const std::vector<SphereHit> hits = traceSphere(view, 128, 128, glm::dvec3(0.0), 0.02);
    double worst = 0.0, seamFree = 0.0;
    for (uint32_t y = 0; y < 128; ++y)
        for (uint32_t x = 0; x < 128; ++x) {
            if (!hits[y * 128 + x].interior) continue;
            const double d = srgbDifference(pixelLinear(images[0], x, y), pixelLinear(images[1], x, y));
            worst = std::max(worst, d);
            if (x < 48 || x > 80) seamFree = std::max(seamFree, d);  // columns away from the seam
        }
    std::printf(
        "[ texture  ] seam facing the view against the seam behind: largest difference %.2f/255 (%.2f away "
        "from the seam)\n",
        worst, seamFree);
    EXPECT_LE(worst, 5.0);
}

TEST_F(TextureDiffusion, StereoWithMsaaIsEachEyesMonoFrame) {
    RenderSettings settings = textureSettings();
    settings.msaaSamples = 4;
    settings.specular = false;
    settings.textureDiffusionSize = 256;
    const StereoAgainstMono result = stereoAgainstMono(context(), settings);
    for (uint32_t e = 0; e < 2; ++e) {
        std::printf("[ texture  ] stereo MSAA 4x, eye %u against its mono frame: %.3f/255\n", e, result.worst[e]);
        EXPECT_LE(result.worst[e], 1.0) << "eye " << e;
    }
}

TEST_F(TextureDiffusion, TexturesBeyondTwoGigabytesAreRefusedNamingTheSetting) {
    Primitive sphere = makeSphere(0.04f, 16, 8);
    sphere.material = 0;
    const Scene scene = makeScene({{sphere, glm::mat4(1.0f)}}, {skinMaterial(glm::vec3(0.8f, 0.6f, 0.5f))});
    RenderSettings settings = textureSettings();
    settings.textureDiffusionSize = 8192;  // 36 bytes a texel: 2.25 GiB for the one skin draw
    Renderer renderer(context(), scene, Environment::constant(glm::vec3(0.1f)), &LutSet::loadDefault(), settings);
    const View view = sphereView(0.04);
    try {
        renderer.render(view, 32, 32, OutputEncoding::LinearFloat);
        ADD_FAILURE() << "an 8192-texel irradiance texture was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("textureDiffusionSize 8192"), std::string::npos) << e.what();
    }
    settings.textureDiffusionSize = 64;  // the renderer still draws afterwards
    renderer.setSettings(settings);
    EXPECT_EQ(renderer.render(view, 32, 32, OutputEncoding::LinearFloat).rgba32f.size(), size_t(32 * 32 * 4));
}

}  // namespace
}  // namespace preskin::test
