// Stereo (multiview) and MSAA rendering:
//  - each eye of a stereo frame equals the mono frame of that eye (golden tolerance: <= 5/255 per
//    channel except on <= 0.1% of pixels), standard and skin materials, MSAA 1x and 4x, with a
//    shadowed key light, an alpha-masked material and clustered point and spot lights, among them
//    lights on a wall just inside every eye's frustum edges (inner and outer); those lights are
//    shown to light pixels of both eyes, so a grid that lost them would fail the comparison;
//  - MSAA 4x against 1x, mono and stereo: on a flat emissive sphere's silhouette (from an
//    analytic ray trace of the sphere) most pixels take values between the sphere's and the
//    background's, which 1x never does; fully covered pixels equal the 1x image within 1/255;
//    an alpha-masked disc's edge gets intermediate coverage (alpha-to-coverage) under MSAA only;
//  - a view with more eyes than the device draws, and sample counts it does not offer, are
//    refused with preskin::Error.
// Validation layers are on (GpuTest): viewMask agreement, attachment layers and the resolve are
// checked by them on every frame here.
#include "support/GpuTest.h"
#include "support/ImageCompare.h"
#include "support/SkinTestSupport.h"
#include "support/TestLights.h"
#include "support/TestScenes.h"

#include "render/MultiviewProbe.h"

#include <preskin/Error.h>
#include <preskin/LutSet.h>
#include <preskin/Renderer.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace preskin::test {
namespace {

constexpr uint32_t kWidth = 80;
constexpr uint32_t kHeight = 88;
constexpr float kWallZ = -1.2f;

// Per-pixel largest channel difference (RGB) between two one-eye 8-bit images.
std::vector<int> pixelDifferences(const RenderedImage& a, const RenderedImage& b) {
    std::vector<int> d(size_t(a.width) * a.height, 255);
    if (a.rgba8.size() != b.rgba8.size()) return d;
    for (size_t i = 0; i < d.size(); ++i) {
        int m = 0;
        for (int c = 0; c < 3; ++c) m = std::max(m, std::abs(int(a.rgba8[i * 4 + c]) - int(b.rgba8[i * 4 + c])));
        d[i] = m;
    }
    return d;
}

size_t countAbove(const std::vector<int>& d, int steps) {
    return size_t(std::count_if(d.begin(), d.end(), [&](int v) { return v > steps; }));
}

// The golden tolerance: at most 0.1% of pixels more than 5/255 apart in any channel.
void expectWithinGoldenTolerance(const RenderedImage& a, const RenderedImage& b, const std::string& what) {
    const std::vector<int> d = pixelDifferences(a, b);
    EXPECT_LE(countAbove(d, 5), d.size() / 1000) << what;
}

Material material(const glm::vec3& albedo, float roughness) {
    Material m;
    m.baseColorFactor = glm::vec4(albedo, 1.0f);
    m.metallicFactor = 0.0f;
    m.roughnessFactor = roughness;
    return m;
}

// A 64x64 texture whose alpha falls off radially (1 at the centre, 0 at the rim).
int addRadialAlpha(Scene& scene) {
    Image image;
    image.name = "radial alpha";
    image.width = image.height = 64;
    for (uint32_t y = 0; y < 64; ++y)
        for (uint32_t x = 0; x < 64; ++x) {
            const float r = glm::length(glm::vec2(float(x) + 0.5f, float(y) + 0.5f) / 32.0f - 1.0f);
            const uint8_t alpha = uint8_t(std::clamp(1.0f - r, 0.0f, 1.0f) * 255.0f + 0.5f);
            image.rgba8.insert(image.rgba8.end(), {255, 255, 255, alpha});
        }
    scene.images.push_back(image);
    return int(scene.images.size()) - 1;
}

// Room: a back wall, a floor reaching behind the viewer (both single quads of two triangles, so
// every eye has to clip them), a sphere and an alpha-masked disc in front of the wall.
Scene roomScene() {
    Material masked = material({0.9f, 0.8f, 0.3f}, 0.5f);
    masked.alphaMode = AlphaMode::Mask;
    masked.alphaCutoff = 0.5f;
    masked.doubleSided = true;
    Scene scene =
        makeScene({{makeQuad(6.0f, 1), glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, kWallZ))},
                   {makeQuad(6.0f, 1),
                    glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, -0.6f, 1.8f)) *
                        glm::rotate(glm::mat4(1.0f), -1.5708f, glm::vec3(1, 0, 0))},
                   {makeSphere(0.22f, 48, 24), glm::translate(glm::mat4(1.0f), glm::vec3(0.08f, -0.2f, -0.7f))},
                   {makeQuad(0.4f, 1), glm::translate(glm::mat4(1.0f), glm::vec3(-0.35f, 0.15f, -0.9f))}},
                  {material({0.7f, 0.7f, 0.72f}, 0.6f), material({0.5f, 0.45f, 0.4f}, 0.8f),
                   material({0.8f, 0.55f, 0.45f}, 0.4f), masked});
    for (size_t i = 0; i < scene.meshes.size(); ++i) scene.meshes[i].primitives[0].material = int(i);
    scene.materials[3].baseColor.image = addRadialAlpha(scene);
    for (Mesh& mesh : scene.meshes)
        for (Primitive& p : mesh.primitives) recomputeCurvature(p);
    return scene;
}

View roomView() {
    const glm::mat4 head = glm::inverse(
        glm::lookAt(glm::vec3(0.0f, 0.05f, 0.25f), glm::vec3(0.0f, -0.05f, -1.0f), glm::vec3(0.0f, 1.0f, 0.0f)));
    // HMD-like angles: the inner (nasal) side narrower than the outer one.
    return stereoView(head, 0.064f, FovAngles{-0.62f, 0.5f, 0.55f, -0.6f}, FovAngles{-0.5f, 0.62f, 0.55f, -0.6f}, 0.05f,
                      10.0f);
}

// The direction of eye pixel (px, py)'s ray (pixel edges at integers).
glm::vec3 pixelRay(const Eye& eye, float px, float py) {
    const glm::mat4 worldFromClip = glm::inverse(eye.clipFromWorld());
    glm::vec4 p = worldFromClip * glm::vec4(px / kWidth * 2.0f - 1.0f, py / kHeight * 2.0f - 1.0f, 0.5f, 1.0f);
    return glm::normalize(glm::vec3(p) / p.w - eye.positionWs);
}

// Bright lights 2 cm off the wall or floor (whichever the ray meets first) just inside each
// eye's four frustum edges.
std::vector<Light> edgeLights(const View& view) {
    std::vector<Light> lights;
    for (const Eye& eye : view.eyes)
        for (int edge = 0; edge < 4; ++edge) {
            const float px = edge == 0 ? 1.5f : edge == 1 ? kWidth - 1.5f : 0.6f * kWidth;
            const float py = edge == 2 ? 1.5f : edge == 3 ? kHeight - 1.5f : 0.4f * kHeight;
            const glm::vec3 dir = pixelRay(eye, px, py);
            const float toWall = (kWallZ - eye.positionWs.z) / dir.z;
            const float toFloor = dir.y < 0.0f ? (-0.6f - eye.positionWs.y) / dir.y : 1e9f;
            const glm::vec3 offset = toFloor < toWall ? glm::vec3(0.0f, 0.02f, 0.0f) : glm::vec3(0.0f, 0.0f, 0.02f);
            const glm::vec3 p = eye.positionWs + dir * std::min(toWall, toFloor) + offset;
            lights.push_back(pointLight(p, 0.14f, glm::vec3(1.0f, 0.3f, 0.2f), 0.6f));
        }
    return lights;
}

std::vector<Light> roomLights(const View& view, bool withEdgeLights) {
    std::vector<Light> lights(1);
    lights[0].type = LightType::Directional;
    lights[0].directionWs = glm::normalize(glm::vec3(0.4f, -0.7f, -0.5f));
    lights[0].intensity = 2.0f;
    lights[0].castsShadow = true;
    std::mt19937 rng(7);
    for (int i = 0; i < 40; ++i) {
        const glm::vec3 p(uniform(rng, -1.2f, 1.2f), uniform(rng, -0.55f, 1.0f), uniform(rng, -1.15f, 0.1f));
        const glm::vec3 color(uniform(rng, 0.2f, 1.0f), uniform(rng, 0.2f, 1.0f), uniform(rng, 0.2f, 1.0f));
        if (i % 3 == 2)
            lights.push_back(
                spotLight(p, randomDirection(rng), uniform(rng, 0.3f, 1.0f), uniform(rng, 0.2f, 0.8f), 0.8f));
        else
            lights.push_back(pointLight(p, uniform(rng, 0.15f, 0.5f), color, 0.3f));
    }
    if (withEdgeLights) {
        const std::vector<Light> edge = edgeLights(view);
        lights.insert(lights.end(), edge.begin(), edge.end());
    }
    return lights;
}

// A flat emissive sphere on the dark background, no lights.
Scene emissiveSphere(float radiusM) {
    Material m = material(glm::vec3(0.0f), 1.0f);
    m.emissiveFactor = glm::vec3(0.6f, 0.8f, 0.7f);
    Scene scene = makeScene({{makeSphere(radiusM, 96, 48), glm::mat4(1.0f)}}, {m});
    scene.meshes[0].primitives[0].material = 0;
    return scene;
}

class Stereo : public GpuTest {};

TEST_F(Stereo, EachEyeEqualsItsMonoFrame) {
    const LutSet luts = LutSet::load(std::string(PRESKIN_SOURCE_DIR) + "/luts");
    const View view = roomView();
    for (bool skin : {false, true}) {
        Scene scene = roomScene();
        if (skin) scene.makeSkin("all");
        for (uint32_t samples : {1u, 4u}) {
            RenderSettings settings;
            settings.msaaSamples = samples;
            // The shadow map covers the whole scene in both: fitted to the skin in view, its texels
            // would depend on which eyes see the skin (both in stereo, one in mono).
            settings.fitShadowToSkin = false;
            Renderer renderer(context(), scene, Environment::constant(glm::vec3(0.08f)), &luts, settings);
            renderer.setLights(roomLights(view, true));
            const RenderedImage stereo = renderer.render(view, kWidth, kHeight, OutputEncoding::DisplaySrgb8);
            ASSERT_EQ(stereo.eyes, 2u);
            dumpImage(std::string("stereo_") + (skin ? "skin" : "standard") + "_msaa" + std::to_string(samples),
                      sideBySide(stereo));
            for (uint32_t e = 0; e < 2; ++e) {
                const RenderedImage mono =
                    renderer.render(View(view.eyes[e]), kWidth, kHeight, OutputEncoding::DisplaySrgb8);
                dumpImage(std::string("mono_") + (skin ? "skin" : "standard") + "_msaa" + std::to_string(samples) +
                              "_eye" + std::to_string(e),
                          mono);
                expectWithinGoldenTolerance(eyeImage(stereo, e), mono,
                                            std::string(skin ? "skin" : "standard") + ", MSAA " +
                                                std::to_string(samples) + ", eye " + std::to_string(e));
            }
        }
    }
}

// Multiview itself (EyeDrawing::Multiview forced): every eye equals its mono frame on geometry
// every eye sees whole (nothing to clip), where this driver's multiview is sound too.
TEST_F(Stereo, MultiviewEyesEqualMonoFrames) {
    const Scene scene = emissiveSphere(0.3f);
    const View view =
        stereoView(glm::inverse(glm::lookAt(glm::vec3(0.0f, 0.1f, 1.5f), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f))),
                   0.064f, FovAngles{-0.62f, 0.5f, 0.55f, -0.6f}, FovAngles{-0.5f, 0.62f, 0.55f, -0.6f}, 0.05f, 10.0f);
    for (uint32_t samples : {1u, 4u}) {
        RenderSettings settings;
        settings.msaaSamples = samples;
        settings.eyeDrawing = EyeDrawing::Multiview;
        Renderer renderer(context(), scene, Environment::constant(glm::vec3(0.1f)), nullptr, settings);
        renderer.setLights(roomLights(view, false));
        const RenderedImage stereo = renderer.render(view, kWidth, kHeight, OutputEncoding::DisplaySrgb8);
        EXPECT_EQ(renderer.frameStats().eyeDrawing, EyeDrawing::Multiview);
        for (uint32_t e = 0; e < 2; ++e)
            expectWithinGoldenTolerance(
                eyeImage(stereo, e), renderer.render(View(view.eyes[e]), kWidth, kHeight, OutputEncoding::DisplaySrgb8),
                "multiview, MSAA " + std::to_string(samples) + ", eye " + std::to_string(e));
    }
}

// The multiview clipping probe agrees with what multiview draws on this device: with clipped
// geometry (the room's wall and floor), multiview's eyes equal their mono frames exactly when the
// probe passed; Auto then uses multiview, otherwise instanced layers.
TEST_F(Stereo, MultiviewProbeMatchesTheDevice) {
    const View view = roomView();
    const Scene scene = roomScene();
    RenderSettings settings;
    settings.eyeDrawing = EyeDrawing::Multiview;
    Renderer renderer(context(), scene, Environment::constant(glm::vec3(0.08f)), nullptr, settings);
    renderer.setLights(roomLights(view, true));
    const RenderedImage stereo = renderer.render(view, kWidth, kHeight, OutputEncoding::DisplaySrgb8);
    dumpImage("stereo_multiview_room", sideBySide(stereo));
    size_t differing = 0;
    for (uint32_t e = 0; e < 2; ++e)
        differing += countAbove(
            pixelDifferences(eyeImage(stereo, e),
                             renderer.render(View(view.eyes[e]), kWidth, kHeight, OutputEncoding::DisplaySrgb8)),
            0);
    const bool sound = multiviewClipsEveryView(ContextAccess::core(context()));
    EXPECT_EQ(differing == 0, sound) << differing << " pixels differ; probe: multiview "
                                     << (sound ? "sound" : "unsound");
    renderer.setSettings(RenderSettings{});
    renderer.render(view, 16, 16, OutputEncoding::DisplaySrgb8);
    const bool layered = ContextAccess::core(context()).shaderOutputLayer() && !sound;
    EXPECT_EQ(renderer.frameStats().eyeDrawing, layered ? EyeDrawing::InstancedLayers : EyeDrawing::Multiview);
}

TEST_F(Stereo, EdgeLightsLightBothEyes) {
    const View view = roomView();
    const Scene scene = roomScene();
    Renderer renderer(context(), scene, Environment::constant(glm::vec3(0.08f)), nullptr);
    renderer.setLights(roomLights(view, true));
    const RenderedImage with = renderer.render(view, kWidth, kHeight, OutputEncoding::DisplaySrgb8);
    renderer.setLights(roomLights(view, false));
    const RenderedImage without = renderer.render(view, kWidth, kHeight, OutputEncoding::DisplaySrgb8);
    for (uint32_t e = 0; e < 2; ++e) {
        const std::vector<int> d = pixelDifferences(eyeImage(with, e), eyeImage(without, e));
        // Every edge of the eye has a lit patch: count lit pixels per border band.
        size_t bands[4] = {0, 0, 0, 0};
        for (uint32_t y = 0; y < kHeight; ++y)
            for (uint32_t x = 0; x < kWidth; ++x) {
                if (d[size_t(y) * kWidth + x] <= 10) continue;
                if (x < 6) ++bands[0];
                if (x + 6 >= kWidth) ++bands[1];
                if (y < 6) ++bands[2];
                if (y + 6 >= kHeight) ++bands[3];
            }
        for (int b = 0; b < 4; ++b) EXPECT_GT(bands[b], 3u) << "eye " << e << ", edge " << b;
    }
}

TEST_F(Stereo, Msaa4BlendsSilhouettesAndKeepsInteriors) {
    const float radius = 0.3f;
    const Scene scene = emissiveSphere(radius);
    const View mono = perspectiveView(
        glm::inverse(glm::lookAt(glm::vec3(0.0f, 0.0f, 1.2f), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f))), 0.7f,
        float(kWidth) / float(kHeight), 0.1f, 10.0f);
    const View stereo = stereoFromMono(mono, 0.064f);
    for (const View* view : {&mono, &stereo}) {
        RenderSettings one;
        RenderSettings four;
        four.msaaSamples = 4;
        Renderer r1(context(), scene, Environment::constant(glm::vec3(0.0f)), nullptr, one);
        Renderer r4(context(), scene, Environment::constant(glm::vec3(0.0f)), nullptr, four);
        r1.setLights({});
        r4.setLights({});
        const RenderedImage i1 = r1.render(*view, kWidth, kHeight, OutputEncoding::DisplaySrgb8);
        const RenderedImage i4 = r4.render(*view, kWidth, kHeight, OutputEncoding::DisplaySrgb8);
        for (uint32_t e = 0; e < view->eyeCount(); ++e) {
            const RenderedImage a = eyeImage(i1, e);
            const RenderedImage b = eyeImage(i4, e);
            const std::vector<SphereHit> hits =
                traceSphere(View(view->eyes[e]), kWidth, kHeight, glm::dvec3(0.0), radius);
            const int background = a.rgba8[1];  // the top-left corner misses the sphere
            ASSERT_FALSE(hits[0].interior);
            int sphere = -1;
            size_t interior = 0, interiorOff = 0, silhouette = 0, blended4 = 0, blended1 = 0;
            for (uint32_t y = 0; y < kHeight; ++y)
                for (uint32_t x = 0; x < kWidth; ++x) {
                    const size_t i = size_t(y) * kWidth + x;
                    if (hits[i].interior) {
                        sphere = a.rgba8[i * 4 + 1];
                        ++interior;
                        if (std::abs(int(a.rgba8[i * 4 + 1]) - int(b.rgba8[i * 4 + 1])) > 1) ++interiorOff;
                    }
                }
            ASSERT_GT(interior, 500u);
            ASSERT_GT(sphere, background + 50);
            auto between = [&](int v) { return v > background + 8 && v < sphere - 8; };
            const Eye& eye = view->eyes[e];
            auto hitsSphere = [&](float px, float py) {  // does the ray through (px, py) meet the sphere?
                const glm::vec3 d = pixelRay(eye, px, py);
                const float along = glm::dot(d, eye.positionWs);
                return along * along - (glm::dot(eye.positionWs, eye.positionWs) - radius * radius) > 0.0f;
            };
            for (uint32_t y = 0; y < kHeight; ++y)
                for (uint32_t x = 0; x < kWidth; ++x) {
                    // A silhouette pixel: the sphere's edge crosses it well inside (the rays through
                    // points a quarter pixel in from its corners disagree).
                    int corners = 0;
                    for (int c = 0; c < 4; ++c)
                        corners +=
                            hitsSphere(float(x) + ((c & 1) ? 0.75f : 0.25f), float(y) + ((c & 2) ? 0.75f : 0.25f));
                    if (corners == 0 || corners == 4) continue;
                    ++silhouette;
                    const size_t i = size_t(y) * kWidth + x;
                    if (between(b.rgba8[i * 4 + 1])) ++blended4;
                    if (between(a.rgba8[i * 4 + 1])) ++blended1;
                }
            const std::string what = (view->eyeCount() > 1 ? "stereo eye " : "mono eye ") + std::to_string(e);
            EXPECT_EQ(interiorOff, 0u) << what;
            EXPECT_GT(silhouette, 60u) << what;
            EXPECT_EQ(blended1, 0u) << what;
            EXPECT_GT(blended4, silhouette * 8 / 10) << what << ": " << blended4 << " of " << silhouette;
        }
    }
}

TEST_F(Stereo, AlphaMaskUsesCoverageUnderMsaa) {
    Material disc = material(glm::vec3(0.0f), 1.0f);
    disc.emissiveFactor = glm::vec3(0.9f);
    disc.alphaMode = AlphaMode::Mask;
    Scene scene = makeScene({{makeQuad(1.0f, 1), glm::mat4(1.0f)}}, {disc});
    scene.meshes[0].primitives[0].material = 0;
    scene.materials[0].baseColor.image = addRadialAlpha(scene);
    const View view = perspectiveView(
        glm::inverse(glm::lookAt(glm::vec3(0.0f, 0.0f, 1.0f), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f))), 0.9f,
        float(kWidth) / float(kHeight), 0.1f, 10.0f);
    size_t blended[2] = {0, 0};
    int full = 0;
    for (uint32_t samples : {1u, 4u}) {
        RenderSettings settings;
        settings.msaaSamples = samples;
        Renderer renderer(context(), scene, Environment::constant(glm::vec3(0.0f)), nullptr, settings);
        renderer.setLights({});
        const RenderedImage image = renderer.render(view, kWidth, kHeight, OutputEncoding::DisplaySrgb8);
        const int background = image.rgba8[1];
        full = std::max<int>(full, image.rgba8[(size_t(kHeight / 2) * kWidth + kWidth / 2) * 4 + 1]);
        for (size_t i = 0; i < size_t(kWidth) * kHeight; ++i) {
            const int v = image.rgba8[i * 4 + 1];
            if (v > background + 8 && v < full - 8) ++blended[samples == 4];
            EXPECT_EQ(image.rgba8[i * 4 + 3], 255) << "alpha of pixel " << i << " with " << samples << " samples";
        }
    }
    EXPECT_EQ(blended[0], 0u);   // discard: every pixel is disc or background
    EXPECT_GT(blended[1], 60u);  // coverage: the disc's rim is blended
}

TEST_F(Stereo, RefusesWhatTheDeviceCannotDraw) {
    const Scene scene = emissiveSphere(0.3f);
    Renderer renderer(context(), scene, Environment::constant(glm::vec3(0.0f)), nullptr);
    const View mono = perspectiveView(glm::mat4(1.0f), 0.7f, 1.0f, 0.1f, 10.0f);
    View tooMany;
    tooMany.eyes.assign(renderer.maxEyes() + 1, mono.eye());
    EXPECT_THROW(renderer.render(tooMany, 16, 16, OutputEncoding::DisplaySrgb8), Error);
    EXPECT_THROW(renderer.render(View{}, 16, 16, OutputEncoding::DisplaySrgb8), Error);
    const std::vector<uint32_t> counts = renderer.msaaSampleCounts();
    ASSERT_FALSE(counts.empty());
    EXPECT_EQ(counts.front(), 1u);
    for (uint32_t n : {3u, 16u, 64u, 0u}) {
        if (std::find(counts.begin(), counts.end(), n) != counts.end()) continue;
        RenderSettings settings;
        settings.msaaSamples = n;
        renderer.setSettings(settings);
        EXPECT_THROW(renderer.render(mono, 16, 16, OutputEncoding::DisplaySrgb8), Error) << n << " samples";
    }
    // Six eyes, as many as lavapipe's multiview offers, render each like its mono frame.
    View six;
    for (int i = 0; i < int(std::min(renderer.maxEyes(), kMaxEyes)); ++i)
        six.eyes.push_back(perspectiveView(glm::inverse(glm::lookAt(glm::vec3(0.2f * float(i) - 0.5f, 0.0f, 1.2f),
                                                                    glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f))),
                                           0.7f, 1.0f, 0.1f, 10.0f)
                               .eye());
    renderer.setSettings(RenderSettings{});
    const RenderedImage all = renderer.render(six, 24, 24, OutputEncoding::DisplaySrgb8);
    for (uint32_t e = 0; e < six.eyeCount(); ++e)
        expectWithinGoldenTolerance(eyeImage(all, e),
                                    renderer.render(View(six.eyes[e]), 24, 24, OutputEncoding::DisplaySrgb8),
                                    "eye " + std::to_string(e) + " of " + std::to_string(six.eyeCount()));
}

}  // namespace
}  // namespace preskin::test
