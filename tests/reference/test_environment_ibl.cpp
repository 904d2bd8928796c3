// Image-based lighting against independent computations:
//  - the split-sum DFG table against a brute-force quadrature over the light's hemisphere;
//  - a white furnace: metallic white spheres (F0 = 1) of roughness 0.1 .. 1 in a uniform
//    environment reflect the environment times the directional albedo A + B of their GGX lobe at
//    each pixel's NoV (found here by intersecting the pixel's ray with the sphere);
//  - a glossy metal sphere reflects the sky in its reflection direction, turned with the
//    environment's rotation;
//  - the background: each pixel, in each eye of a stereo view and with MSAA, shows the
//    environment's radiance in its direction (an analytic sky, turned by the environment's
//    rotation), linear and tone-mapped; a transparent background writes alpha 0.
#include "support/GpuTest.h"
#include "support/TestScenes.h"

#include <preskin/Renderer.h>

#include "env/Dfg.h"
#include "render/GpuEnvironment.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace preskin::test {
namespace {

// GGX with height-correlated Smith visibility, written out here (Walter et al. 2007; Heitz 2014).
double ggxD(double NoH, double alpha) {
    const double a2 = alpha * alpha;
    const double d = NoH * NoH * (a2 - 1.0) + 1.0;
    return a2 / (M_PI * d * d);
}
double smithV(double NoL, double NoV, double alpha) {
    const double a2 = alpha * alpha;
    return 0.5 / (NoL * std::sqrt(NoV * NoV * (1.0 - a2) + a2) + NoV * std::sqrt(NoL * NoL * (1.0 - a2) + a2));
}

// A and B by the midpoint rule over the light direction (theta, phi), no importance sampling.
glm::dvec2 dfgQuadrature(double NoV, double roughness) {
    const double alpha = std::max(roughness * roughness, 1e-3);
    const glm::dvec3 V(std::sqrt(1.0 - NoV * NoV), 0.0, NoV);
    const int nTheta = 1500, nPhi = 1500;
    glm::dvec2 sum(0.0);
    for (int i = 0; i < nTheta; ++i) {
        const double theta = (i + 0.5) / nTheta * 0.5 * M_PI;
        for (int j = 0; j < nPhi; ++j) {
            const double phi = (j + 0.5) / nPhi * 2.0 * M_PI;
            const glm::dvec3 L(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
            const glm::dvec3 H = glm::normalize(L + V);
            const double f = ggxD(H.z, alpha) * smithV(L.z, NoV, alpha) * L.z;
            const double fc = std::pow(1.0 - glm::dot(V, H), 5.0);
            const double dOmega = std::sin(theta) * (0.5 * M_PI / nTheta) * (2.0 * M_PI / nPhi);
            sum += glm::dvec2((1.0 - fc) * f, fc * f) * dOmega;
        }
    }
    return sum;
}

TEST(Dfg, TableMatchesAnIndependentQuadrature) {
    for (double NoV : {0.15, 0.5, 0.95})
        for (double roughness : {0.3, 0.6, 1.0}) {
            const glm::dvec2 expected = dfgQuadrature(NoV, roughness);
            const glm::vec2 ab = env::dfgIntegral(float(NoV), float(roughness));
            EXPECT_NEAR(double(ab.x), expected.x, 1e-3) << "NoV " << NoV << " roughness " << roughness;
            EXPECT_NEAR(double(ab.y), expected.y, 1e-3) << "NoV " << NoV << " roughness " << roughness;
        }
    // Entry (i, j) holds NoV i / (size - 1), roughness j / (size - 1).
    const std::vector<glm::vec2> table = env::dfgTable(8, 64, 8);
    const glm::vec2 entry = env::dfgIntegral(5.0f / 7.0f, 2.0f / 7.0f, 64, 8);
    EXPECT_EQ(table[2 * 8 + 5], entry);
}

class EnvironmentIbl : public GpuTest {};

View frontView(float yfov, uint32_t width, uint32_t height, const glm::vec3& eye = {0.0f, 0.0f, 1.0f}) {
    return perspectiveView(glm::inverse(glm::lookAt(eye, glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f))), yfov,
                           float(width) / float(height), 0.01f, 10.0f);
}

// The world ray through the centre of pixel (x, y) of an eye.
void pixelRay(const Eye& eye, uint32_t x, uint32_t y, uint32_t width, uint32_t height, glm::vec3& origin,
              glm::vec3& direction) {
    const glm::mat4 worldFromClip = glm::inverse(eye.clipFromWorld());
    const glm::vec2 ndc((float(x) + 0.5f) / float(width) * 2.0f - 1.0f,
                        (float(y) + 0.5f) / float(height) * 2.0f - 1.0f);
    const glm::vec4 nearWs = worldFromClip * glm::vec4(ndc, 1.0f, 1.0f);
    const glm::vec4 farWs = worldFromClip * glm::vec4(ndc, 0.5f, 1.0f);
    origin = glm::vec3(nearWs) / nearWs.w;
    direction = glm::normalize(glm::vec3(farWs) / farWs.w - origin);
}

// Where pixel (x, y)'s ray meets the sphere of `radius` at the origin: its normal (the
// tessellated sphere's normals are the exact ones) and the ray's direction; false on a miss.
bool sphereHit(const Eye& eye, uint32_t x, uint32_t y, uint32_t size, float radius, glm::vec3& n, glm::vec3& d) {
    glm::vec3 o;
    pixelRay(eye, x, y, size, size, o, d);
    const float b = glm::dot(o, d), c = glm::dot(o, o) - radius * radius, disc = b * b - c;
    if (disc <= 0.0f) return false;
    n = glm::normalize(o + d * (-b - std::sqrt(disc)));
    return true;
}

// A white metal sphere (F0 = 1: it reflects the environment times A + B) at the origin.
Scene metalSphere(float radius, float roughness, uint32_t segments) {
    Primitive sphere = makeSphere(radius, segments, segments / 2);
    sphere.material = 0;
    Material metal;
    metal.baseColorFactor = glm::vec4(1.0f);
    metal.metallicFactor = 1.0f;
    metal.roughnessFactor = roughness;
    return makeScene({{sphere, glm::mat4(1.0f)}}, {metal});
}

TEST_F(EnvironmentIbl, ConstantEnvironmentPrefiltersToItselfAtEveryLevel) {
    const glm::vec3 radiance(0.5f, 1.0f, 2.0f);
    EquirectImage image;
    image.width = 256;
    image.height = 128;
    for (uint32_t i = 0; i < image.width * image.height; ++i)
        image.rgb.insert(image.rgb.end(), {radiance.r, radiance.g, radiance.b});
    GpuEnvironment maps(ContextAccess::core(context()));
    for (const Environment& environment : {Environment::fromImage(image, 0.3f), Environment::constant(radiance)}) {
        maps.set(environment, EquirectImage{});
        EXPECT_GE(maps.maxLevel(), environment.image().width > 0 ? 3.0f : 0.0f);
        const std::vector<glm::vec4> texels = maps.readPrefiltered();
        ASSERT_FALSE(texels.empty());
        for (size_t i = 0; i < texels.size(); ++i)
            for (int c = 0; c < 3; ++c)
                ASSERT_NEAR(texels[i][c], radiance[c], 2e-3f * radiance[c]) << "texel " << i << " channel " << c;
    }
}

TEST_F(EnvironmentIbl, WhiteFurnaceReflectsTheDirectionalAlbedo) {
    const glm::vec3 radiance(0.8f, 1.0f, 1.25f);
    const Environment environment = Environment::constant(radiance);
    const float radius = 0.1f;
    const uint32_t size = 64;
    for (float roughness : {0.1f, 0.4f, 0.7f, 1.0f}) {
        const Scene scene = metalSphere(radius, roughness, 96);
        RenderSettings settings;
        settings.environmentLights = 0;
        Renderer renderer(context(), scene, environment, static_cast<const LutSet*>(nullptr), settings);
        const View view = frontView(0.25f, size, size);
        const RenderedImage image = renderer.render(view, size, size, OutputEncoding::LinearFloat);
        int checked = 0;
        for (uint32_t y = 0; y < size; y += 3)
            for (uint32_t x = 0; x < size; x += 3) {
                glm::vec3 n, d;
                if (!sphereHit(view.eyes[0], x, y, size, radius, n, d)) continue;
                const float NoV = glm::dot(n, -d);
                if (NoV < 0.3f) continue;  // the silhouette: facets and the table's steep edge
                const glm::vec2 ab = env::dfgIntegral(NoV, roughness, 2048, 32);
                const float* p = &image.rgba32f[(size_t(y) * size + x) * 4];
                for (int ch = 0; ch < 3; ++ch)
                    EXPECT_NEAR(p[ch], radiance[ch] * (ab.x + ab.y), 0.01f * radiance[ch] * (ab.x + ab.y))
                        << "roughness " << roughness << " pixel " << x << "," << y << " NoV " << NoV;
                ++checked;
            }
        EXPECT_GT(checked, 50);
    }
}

// A smooth sky (no edges: bilinear and mip filtering leave it alone), in the image's own directions.
glm::vec3 sky(const glm::vec3& d) { return glm::vec3(0.35f + 0.2f * d.x, 0.4f + 0.25f * d.y, 0.45f + 0.2f * d.z); }

Environment skyEnvironment(float rotationY) {
    EquirectImage image;
    image.width = 512;
    image.height = 256;
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x) {
            const glm::vec3 l = sky(EquirectImage::directionAt((float(x) + 0.5f) / float(image.width),
                                                               (float(y) + 0.5f) / float(image.height)));
            image.rgb.insert(image.rgb.end(), {l.r, l.g, l.b});
        }
    return Environment::fromImage(std::move(image), rotationY);
}

// Khronos PBR Neutral where every channel lies in [0.08, 0.76): the colour less 0.04. Then sRGB.
float displayValue(float linear) {
    const float t = linear - 0.04f;
    return t <= 0.0031308f ? 12.92f * t : 1.055f * std::pow(t, 1.0f / 2.4f) - 0.055f;
}

TEST_F(EnvironmentIbl, BackgroundShowsTheEnvironmentInEveryEye) {
    const float rotationY = 0.6f;
    const Environment environment = skyEnvironment(rotationY);
    Primitive sphere = makeSphere(0.02f, 32, 16);
    sphere.material = 0;
    Material grey;
    const Scene scene = makeScene({{sphere, glm::translate(glm::mat4(1.0f), glm::vec3(0.3f, 0.3f, 0.0f))}}, {grey});
    const uint32_t width = 48, height = 40;
    const View view =
        stereoView(glm::inverse(glm::lookAt(glm::vec3(0.0f, 0.0f, 1.0f), glm::vec3(0.3f, 0.2f, 0.0f),
                                            glm::vec3(0.0f, 1.0f, 0.0f))),
                   0.064f, FovAngles{-0.6f, 0.5f, 0.45f, -0.5f}, FovAngles{-0.5f, 0.6f, 0.45f, -0.5f}, 0.01f, 10.0f);
    for (uint32_t msaa : {1u, 4u}) {
        RenderSettings settings;
        settings.background.mode = BackgroundMode::Environment;
        settings.msaaSamples = msaa;
        settings.environmentLights = 0;
        Renderer renderer(context(), scene, environment, static_cast<const LutSet*>(nullptr), settings);
        const RenderedImage linear = renderer.render(view, width, height, OutputEncoding::LinearFloat);
        const RenderedImage display = renderer.render(view, width, height, OutputEncoding::DisplaySrgb8);
        ASSERT_EQ(linear.eyes, 2u);
        int checked = 0;
        for (uint32_t e = 0; e < 2; ++e)
            for (uint32_t y = 0; y < height; ++y)
                for (uint32_t x = 0; x < width; ++x) {
                    glm::vec3 o, d;
                    pixelRay(view.eyes[e], x, y, width, height, o, d);
                    const glm::vec3 toSphere = glm::vec3(0.3f, 0.3f, 0.0f) - o;
                    if (glm::length(glm::cross(toSphere, d)) < 0.03f) continue;  // near the sphere
                    const glm::vec3 expected = sky(rotateY(d, -rotationY));
                    const size_t i = (size_t(e) * width * height + size_t(y) * width + x) * 4;
                    for (int ch = 0; ch < 3; ++ch) {
                        EXPECT_NEAR(linear.rgba32f[i + size_t(ch)], expected[ch], 0.004f)
                            << "msaa " << msaa << " eye " << e << " pixel " << x << "," << y;
                        EXPECT_NEAR(float(display.rgba8[i + size_t(ch)]), 255.0f * displayValue(expected[ch]), 1.0f)
                            << "msaa " << msaa << " eye " << e << " pixel " << x << "," << y;
                    }
                    EXPECT_EQ(display.rgba8[i + 3], 255);
                    ++checked;
                }
        EXPECT_GT(checked, 2 * int(width * height) * 3 / 4);
    }
}

TEST_F(EnvironmentIbl, ReflectionTurnsWithTheEnvironment) {
    // A glossy white metal sphere reflects the sky in each pixel's reflection direction, turned by
    // the environment's rotation, times the directional albedo A + B.
    const float radius = 0.1f, roughness = 0.05f;
    const uint32_t size = 64;
    const Scene scene = metalSphere(radius, roughness, 128);
    const View view = frontView(0.25f, size, size);
    for (float rotationY : {0.0f, 1.1f, -2.4f}) {
        RenderSettings settings;
        settings.environmentLights = 0;
        Renderer renderer(context(), scene, skyEnvironment(rotationY), static_cast<const LutSet*>(nullptr), settings);
        const RenderedImage image = renderer.render(view, size, size, OutputEncoding::LinearFloat);
        int checked = 0;
        for (uint32_t y = 0; y < size; y += 2)
            for (uint32_t x = 0; x < size; x += 2) {
                glm::vec3 n, d;
                if (!sphereHit(view.eyes[0], x, y, size, radius, n, d)) continue;
                const float NoV = glm::dot(n, -d);
                if (NoV < 0.5f) continue;
                const glm::vec3 r = glm::reflect(d, n);
                const glm::vec2 ab = env::dfgIntegral(NoV, roughness, 2048, 32);
                const glm::vec3 expected = sky(rotateY(r, -rotationY)) * (ab.x + ab.y);
                const float* p = &image.rgba32f[(size_t(y) * size + x) * 4];
                for (int ch = 0; ch < 3; ++ch)
                    EXPECT_NEAR(p[ch], expected[ch], 0.03f * expected[ch])
                        << "rotation " << rotationY << " pixel " << x << "," << y;
                ++checked;
            }
        EXPECT_GT(checked, 100);
    }
}

TEST_F(EnvironmentIbl, ExtractedLightsComeAfterTheScenesOwn) {
    // The sky with a sun: a bright disc towards +Y+Z.
    EquirectImage image;
    image.width = 256;
    image.height = 128;
    const glm::vec3 sun = glm::normalize(glm::vec3(0.0f, 1.0f, 1.0f));
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x) {
            const glm::vec3 d = EquirectImage::directionAt((float(x) + 0.5f) / float(image.width),
                                                           (float(y) + 0.5f) / float(image.height));
            const glm::vec3 l = sky(d) + (glm::dot(d, sun) > 0.999f ? glm::vec3(500.0f) : glm::vec3(0.0f));
            image.rgb.insert(image.rgb.end(), {l.r, l.g, l.b});
        }
    const Environment environment = Environment::fromImage(image);
    Primitive sphere = makeSphere(0.1f, 32, 16);
    sphere.material = 0;
    Scene scene = makeScene({{sphere, glm::mat4(1.0f)}}, {Material{}});
    // No lights of its own: one light from the environment by default, towards the sun.
    Renderer lightless(context(), scene, environment, static_cast<const LutSet*>(nullptr));
    ASSERT_EQ(lightless.environmentLights().size(), 1u);
    EXPECT_GT(glm::dot(-lightless.environmentLights()[0].directionWs, sun), 0.999f);
    // With a light of its own: none by default; asked for, they come after the scene's lights.
    Light key;
    key.castsShadow = true;
    scene.lights.push_back(key);
    Renderer lit(context(), scene, environment, static_cast<const LutSet*>(nullptr));
    EXPECT_TRUE(lit.environmentLights().empty());
    RenderSettings settings;
    settings.environmentLights = 2;
    lit.setSettings(settings);
    EXPECT_EQ(lit.environmentLights().size(), 1u);  // the sky holds one concentration only
    EXPECT_EQ(lit.lights().size(), 1u);             // the host's lights stay as they were set
    settings.environmentLights = 0;
    lit.setSettings(settings);
    EXPECT_TRUE(lit.environmentLights().empty());
}

TEST_F(EnvironmentIbl, TransparentBackgroundWritesAlphaZero) {
    Primitive sphere = makeSphere(0.1f, 32, 16);
    sphere.material = 0;
    const Scene scene = makeScene({{sphere, glm::mat4(1.0f)}}, {Material{}});
    RenderSettings settings;
    settings.background.mode = BackgroundMode::Transparent;
    Renderer renderer(context(), scene, skyEnvironment(0.0f), static_cast<const LutSet*>(nullptr), settings);
    const uint32_t size = 32;
    const RenderedImage image = renderer.render(frontView(0.5f, size, size), size, size, OutputEncoding::DisplaySrgb8);
    EXPECT_EQ(image.rgba8[3], 0);                                               // a corner: background
    EXPECT_EQ(image.rgba8[(size_t(size / 2) * size + size / 2) * 4 + 3], 255);  // the centre: the sphere
    settings.background = {BackgroundMode::Color, glm::vec3(1.0f, 0.0f, 0.0f)};
    renderer.setSettings(settings);
    const RenderedImage red = renderer.render(frontView(0.5f, size, size), size, size, OutputEncoding::DisplaySrgb8);
    EXPECT_EQ(red.rgba8[0], 255);
    EXPECT_EQ(red.rgba8[1], 0);
    EXPECT_EQ(red.rgba8[3], 255);
}

}  // namespace
}  // namespace preskin::test
