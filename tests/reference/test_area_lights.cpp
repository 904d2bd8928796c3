// Lights with a size (PRESKIN_lights_area) rendered on the GPU against independent integrals:
//  - a Lambert plane under a rectangle that the plane cuts (so every point sees it clipped by its
//    horizon), a disc, a sphere light straddling the horizon and a tube, against the diffusion
//    reference's irradiance of each shape (reference/src/AreaLightIrradiance.h: the clipped
//    polygon by Lambert's formula, the disc as a 256-gon, the sphere's cap ring by ring, the
//    capsule's surface), whose polygon formula is checked here against the closed-form form
//    factor of a rectangle parallel to the receiver;
//  - skin under a sphere light of vanishing size equals skin under a point light;
//  - inside a sphere light every direction is lit: a skin sphere there is uniformly bright;
//  - the skin spheres under a sphere light and a rectangle are closer to the diffusion reference
//    than Lambert.
#include "support/GpuTest.h"
#include "support/ImageCompare.h"
#include "support/SkinTestSupport.h"
#include "support/TestScenes.h"

#include "AreaLightIrradiance.h"

#include <preskin/DiffusionReference.h>
#include <preskin/LightRecord.h>
#include <preskin/LightScatter.h>
#include <preskin/LutSet.h>
#include <preskin/Renderer.h>

#include <glm/gtc/matrix_transform.hpp>

#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace preskin::test {
namespace {

constexpr double kPi = std::numbers::pi;

// The closed-form form factor from a differential area to a parallel rectangle a x b at height c
// with one corner above it (Howell's catalogue, configuration B-3), times pi: the integral of
// cos over the rectangle's solid angle.
double cornerRectangleCosineIntegral(double a, double b, double c) {
    const double x = a / c, y = b / c;
    const double f = (x / std::sqrt(1.0 + x * x) * std::atan(y / std::sqrt(1.0 + x * x)) +
                      y / std::sqrt(1.0 + y * y) * std::atan(x / std::sqrt(1.0 + y * y))) /
        (2.0 * kPi);
    return kPi * f;
}

TEST(AreaLightIrradiance, PolygonFormulaMatchesTheClosedFormRectangle) {
    for (const glm::dvec3 abc : {glm::dvec3(1.0, 1.0, 1.0), glm::dvec3(0.3, 2.0, 0.5), glm::dvec3(4.0, 0.1, 0.7)}) {
        const glm::dvec3 corners[4] = {
            {0.0, 0.0, abc.z}, {abc.x, 0.0, abc.z}, {abc.x, abc.y, abc.z}, {0.0, abc.y, abc.z}};
        const double polygon = reference::polygonCosineIntegral(corners, 4, glm::dvec3(0.0), glm::dvec3(0, 0, 1));
        EXPECT_NEAR(polygon, cornerRectangleCosineIntegral(abc.x, abc.y, abc.z), 1e-12);
    }
    // Below the horizon nothing, half below half.
    const glm::dvec3 below[4] = {{-1, -1, -0.5}, {1, -1, -0.5}, {1, 1, -0.5}, {-1, 1, -0.5}};
    EXPECT_EQ(reference::polygonCosineIntegral(below, 4, glm::dvec3(0.0), glm::dvec3(0, 0, 1)), 0.0);
    const glm::dvec3 wall[4] = {{-1, 1, -1}, {1, 1, -1}, {1, 1, 1}, {-1, 1, 1}};
    const double upper = reference::polygonCosineIntegral(wall, 4, glm::dvec3(0.0), glm::dvec3(0, 0, 1));
    const glm::dvec3 upperWall[4] = {{-1, 1, 0}, {1, 1, 0}, {1, 1, 1}, {-1, 1, 1}};
    EXPECT_NEAR(upper, reference::polygonCosineIntegral(upperWall, 4, glm::dvec3(0.0), glm::dvec3(0, 0, 1)), 1e-12);
    EXPECT_GT(upper, 0.0);
}

class AreaLights : public GpuTest {
protected:
    static constexpr uint32_t kSize = 96;

    // A white Lambert plane (z = 0, facing +Z, 2 m wide) seen from 1.6 m above, lit by `light`
    // alone: the largest difference from the reference irradiance's radiance, relative to the
    // image's largest radiance.
    // The plane (0.8 grey, roughness `roughness`) under `light` alone, seen from 1.6 m above.
    RenderedImage renderPlane(const Light& light, bool specular, float roughness = 1.0f) {
        Material material;
        material.baseColorFactor = glm::vec4(0.8f, 0.8f, 0.8f, 1.0f);
        material.metallicFactor = 0.0f;
        material.roughnessFactor = roughness;
        Primitive plane = makeQuad(2.0f, 8);
        plane.material = 0;
        Scene scene = makeScene({{plane, glm::mat4(1.0f)}}, {material});
        scene.lights = {light};
        RenderSettings settings;
        settings.specular = specular;
        settings.shadows = false;
        Renderer renderer(context(), scene, Environment::constant(glm::vec3(0.0f)), nullptr, settings);
        return renderer.render(planeView(), kSize, kSize, OutputEncoding::LinearFloat);
    }

    static View planeView() {
        const glm::mat4 worldFromView =
            glm::inverse(glm::lookAt(glm::vec3(0.0f, 0.0f, 1.6f), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f)));
        return perspectiveView(worldFromView, 0.7f, 1.0f, 0.1f, 10.0f);
    }

    double planeError(const Light& light, const char* name) {
        const RenderedImage image = renderPlane(light, false);
        const View view = planeView();
        dumpImage(std::string("area_light_plane_") + name, image);

        const glm::dmat4 worldFromClip = glm::inverse(glm::dmat4(view.eye().clipFromWorld()));
        double largest = 0.0, worst = 0.0;
        glm::dvec3 worstAt(0.0), worstWant(0.0), worstGot(0.0);
        for (uint32_t y = 0; y < kSize; ++y)
            for (uint32_t x = 0; x < kSize; ++x) {
                const glm::dvec2 ndc((x + 0.5) / kSize * 2.0 - 1.0, (y + 0.5) / kSize * 2.0 - 1.0);
                const glm::dvec4 a = worldFromClip * glm::dvec4(ndc, 1.0, 1.0);
                const glm::dvec4 b = worldFromClip * glm::dvec4(ndc, 0.5, 1.0);
                const glm::dvec3 o = glm::dvec3(a) / a.w, d = glm::dvec3(b) / b.w - o;
                const glm::dvec3 p = o - d * (o.z / d.z);
                const glm::dvec3 want = 0.8 / kPi * reference::areaLightIrradiance(light, p, glm::dvec3(0.0, 0.0, 1.0));
                const glm::dvec3 got = pixelLinear(image, x, y);
                largest = std::max(largest, want.g);
                if (std::abs(got.g - want.g) > worst) {
                    worst = std::abs(got.g - want.g);
                    worstAt = p;
                    worstWant = want;
                    worstGot = got;
                }
            }
        std::printf(
            "[ area lights ] Lambert plane under a %s: largest difference %.2e of the largest radiance %.3f "
            "(at %.3f, %.3f: %.5f, reference %.5f)\n",
            name, worst / largest, largest, worstAt.x, worstAt.y, worstGot.g, worstWant.g);
        EXPECT_GT(largest, 0.01);
        return worst / largest;
    }
};

Light areaLight(LightType type, const glm::vec3& position, const glm::vec3& direction, float intensity) {
    Light l;
    l.type = type;
    l.positionWs = position;
    l.directionWs = glm::normalize(direction);
    l.intensity = intensity;
    return l;
}

TEST_F(AreaLights, RectangleCutByThePlaneMatchesTheClippedPolygon) {
    Light light = areaLight(LightType::Rectangle, {0.2f, 0.1f, 0.08f}, {0.2f, -0.6f, -1.0f}, 2.0f);
    light.axisWs = glm::vec3(1.0f, 0.0f, 0.5f);  // one long side dips below the plane
    light.width = 0.6f;
    light.height = 0.3f;
    EXPECT_LT(planeError(light, "rectangle"), 1e-3);
}

TEST_F(AreaLights, DiscFacingThePlaneMatchesTheReference) {
    Light light = areaLight(LightType::Disc, {-0.1f, 0.15f, 0.2f}, {0.0f, 0.0f, -1.0f}, 2.0f);
    light.radius = 0.15f;
    EXPECT_LT(planeError(light, "disc"), 1e-3);
}

TEST_F(AreaLights, SphereLightAcrossTheHorizonMatchesTheReference) {
    Light light = areaLight(LightType::Sphere, {0.1f, -0.2f, 0.15f}, {0.0f, 0.0f, -1.0f}, 2.0f);
    light.radius = 0.1f;
    EXPECT_LT(planeError(light, "sphere"), 1e-3);
}

// A tube is the sphere cap of its vector form factor, found as a rectangle facing the point with
// a half sphere at each end: an approximation, measured here.
TEST_F(AreaLights, TubeOverThePlaneIsCloseToTheReference) {
    Light light = areaLight(LightType::Tube, {0.0f, 0.1f, 0.25f}, {0.0f, 0.0f, -1.0f}, 2.0f);
    light.axisWs = glm::vec3(1.0f, 0.3f, 0.2f);
    light.radius = 0.03f;
    light.length = 0.8f;
    EXPECT_LT(planeError(light, "tube"), 0.03);
}

// The area-light size floor (preskin/lights.glsl): a rectangle or disc far smaller than its
// distance keeps its power (a point light with its cosine falloff), where the edges' form factors
// in single precision lost it (1e-30 m and 1e-20 m gave black, 1e-10 m most of the light gone).
// Each tiny light against the same light at a size the form factors resolve (a few millimetres at
// 0.2 to 1 m, where the difference between the two is below 1e-4): every pixel within 1 % of the
// largest radiance (2 % for the line of light, near its own plane), and the image's energy within 1 %.
class TinyAreaLights : public AreaLights {
protected:
    void expectSamePower(const Light& tiny, const Light& resolved, const char* name, double pixelBound = 0.01) {
        const RenderedImage a = renderPlane(tiny, true, 0.5f), b = renderPlane(resolved, true, 0.5f);
        dumpImage(std::string("area_light_tiny_") + name, a);
        double sumA = 0.0, sumB = 0.0, largest = 0.0, worst = 0.0;
        for (size_t i = 0; i < a.rgba32f.size(); i += 4) {
            ASSERT_TRUE(std::isfinite(a.rgba32f[i + 1]));
            sumA += double(a.rgba32f[i + 1]);
            sumB += double(b.rgba32f[i + 1]);
            largest = std::max(largest, double(b.rgba32f[i + 1]));
            worst = std::max(worst, std::abs(double(a.rgba32f[i + 1]) - double(b.rgba32f[i + 1])));
        }
        std::printf("[ area lights ] tiny %s: energy %.6f against %.6f (%.4f), largest pixel difference %.2e of %.4f\n",
                    name, sumA, sumB, sumA / sumB, worst / largest, largest);
        EXPECT_GT(sumB, 0.0);
        EXPECT_NEAR(sumA / sumB, 1.0, 0.01) << name;
        EXPECT_LT(worst / largest, pixelBound) << name;
    }
};

TEST_F(TinyAreaLights, RectanglesAndDiscsFarSmallerThanTheirDistanceKeepTheirPower) {
    Light rectangle = areaLight(LightType::Rectangle, {0.1f, -0.1f, 0.3f}, {0.3f, 0.2f, -1.0f}, 0.05f);
    rectangle.width = rectangle.height = 1e-30f;
    Light rectangleResolved = rectangle;
    rectangleResolved.width = rectangleResolved.height = 0.003f;
    expectSamePower(rectangle, rectangleResolved, "rectangle 1e-30 m");

    Light thin = rectangle;  // a line of light: one side tiny, the other not
    thin.width = 1e-10f;
    thin.height = 0.3f;
    Light thinResolved = thin;
    thinResolved.width = 0.002f;
    expectSamePower(thin, thinResolved, "rectangle 1e-10 m by 0.3 m", 0.02);

    Light disc = areaLight(LightType::Disc, {-0.1f, 0.1f, 0.25f}, {-0.2f, 0.1f, -1.0f}, 0.05f);
    disc.radius = 1e-20f;
    Light discResolved = disc;
    discResolved.radius = 0.0015f;
    expectSamePower(disc, discResolved, "disc 1e-20 m");
}

// Specular: a plane of roughness 0.4 reflecting a rectangle, metal (F0 1, where the linearly
// transformed cosine alone is measured) and a black dielectric (F0 0.04, no diffuse: Schlick's
// Fresnel taken at the light's representative direction adds its error), against the GGX BRDF
// (preskin/brdf.glsl: height-correlated Smith, Schlick Fresnel) integrated over the rectangle by
// the midpoint rule, per pixel.
double rectangleSpecularError(Context& context, double F0) {
    Material material;
    material.baseColorFactor = F0 >= 1.0 ? glm::vec4(1.0f) : glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    material.metallicFactor = F0 >= 1.0 ? 1.0f : 0.0f;
    material.roughnessFactor = 0.4f;
    Primitive plane = makeQuad(2.0f, 8);
    plane.material = 0;
    Scene scene = makeScene({{plane, glm::mat4(1.0f)}}, {material});
    Light light = areaLight(LightType::Rectangle, {0.0f, 0.35f, 0.3f}, {0.0f, -0.5f, -1.0f}, 2.0f);
    light.width = 0.5f;
    light.height = 0.25f;
    scene.lights = {light};
    RenderSettings settings;
    settings.shadows = false;
    Renderer renderer(context, scene, Environment::constant(glm::vec3(0.0f)), nullptr, settings);
    const glm::vec3 eye(0.0f, -0.7f, 0.6f);
    const View view =
        perspectiveView(glm::inverse(glm::lookAt(eye, glm::vec3(0.0f, 0.0f, 0.0f), glm::vec3(0.0f, 0.0f, 1.0f))), 0.9f,
                        1.0f, 0.05f, 10.0f);
    const uint32_t size = 48;
    const RenderedImage image = renderer.render(view, size, size, OutputEncoding::LinearFloat);
    dumpImage(F0 >= 1.0 ? "area_light_rectangle_metal" : "area_light_rectangle_dielectric", image);

    const double alpha = 0.4 * 0.4, a2 = alpha * alpha;
    const AreaLightAxes axes = areaLightAxes(light);
    const glm::dvec3 c(light.positionWs), u = glm::dvec3(axes.width) * 0.25, v = glm::dvec3(axes.height) * 0.125;
    const double radiance = 2.0 / (0.5 * 0.25);
    const glm::dmat4 worldFromClip = glm::inverse(glm::dmat4(view.eye().clipFromWorld()));
    double largest = 0.0, worst = 0.0;
    for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 0; x < size; ++x) {
            const glm::dvec2 ndc((x + 0.5) / size * 2.0 - 1.0, (y + 0.5) / size * 2.0 - 1.0);
            const glm::dvec4 a = worldFromClip * glm::dvec4(ndc, 1.0, 1.0),
                             b = worldFromClip * glm::dvec4(ndc, 0.5, 1.0);
            const glm::dvec3 o = glm::dvec3(a) / a.w, d = glm::dvec3(b) / b.w - o;
            if (d.z >= 0.0) continue;
            const glm::dvec3 p = o - d * (o.z / d.z);
            if (std::abs(p.x) > 0.9 || std::abs(p.y) > 0.9) continue;
            const glm::dvec3 V = glm::normalize(glm::dvec3(eye) - p);
            double sum = 0.0;
            const int steps = 64;
            for (int i = 0; i < steps; ++i)
                for (int j = 0; j < steps; ++j) {
                    const glm::dvec3 q =
                        c + u * ((i + 0.5) / steps * 2.0 - 1.0) + v * ((j + 0.5) / steps * 2.0 - 1.0) - p;
                    const double d2 = glm::dot(q, q);
                    const glm::dvec3 L = q / std::sqrt(d2);
                    const double cosLight = -glm::dot(glm::dvec3(axes.normal), L);
                    if (L.z <= 0.0 || cosLight <= 0.0) continue;
                    const glm::dvec3 H = glm::normalize(L + V);
                    const double dd = H.z * H.z * (a2 - 1.0) + 1.0;
                    const double D = a2 / (kPi * dd * dd);
                    const double vis = 0.5 /
                        (L.z * std::sqrt(V.z * V.z * (1.0 - a2) + a2) + V.z * std::sqrt(L.z * L.z * (1.0 - a2) + a2));
                    const double F = F0 + (1.0 - F0) * std::pow(1.0 - std::clamp(glm::dot(V, H), 0.0, 1.0), 5.0);
                    sum += D * vis * F * L.z * cosLight / d2;
                }
            const double want = sum * radiance * (4.0 * 0.25 * 0.125) / (steps * steps);
            largest = std::max(largest, want);
            worst = std::max(worst, std::abs(pixelLinear(image, x, y).g - want));
        }
    std::printf(
        "[ area lights ] GGX (roughness 0.4, F0 %.2f) reflecting a rectangle: largest difference %.4f of the "
        "largest radiance %.3f\n",
        F0, worst / largest, largest);
    EXPECT_GT(largest, 0.1);
    return worst / largest;
}

TEST_F(AreaLights, RectangleSpecularMatchesTheGgxIntegral) {
    EXPECT_LT(rectangleSpecularError(context(), 1.0), 0.05);
    EXPECT_LT(rectangleSpecularError(context(), 0.04), 0.10);
}

// 65,536 lights at a constant density (scatterLights, 4 lights per point), every one an area light
// of the four shapes in turn, around a skin sphere: rendered under the validation layers (any
// message fails the test), no cluster list overflows, and every pixel finite.
TEST_F(AreaLights, SixtyFiveThousandAreaLightsRenderWithoutOverflow) {
    Primitive sphere = makeSphere(0.3f, 64, 32);
    recomputeCurvature(sphere);
    sphere.material = 0;
    Scene scene = makeScene({{sphere, glm::mat4(1.0f)}}, {skinMaterial({0.8f, 0.6f, 0.5f})});
    std::vector<Light> lights = scatterLights(scene.worldBounds(), 65536, 1, 4.0f);
    for (size_t i = 0; i < lights.size(); ++i) {
        Light& l = lights[i];
        const float r = std::max(l.range, 1e-3f);
        l.type = std::array{LightType::Sphere, LightType::Tube, LightType::Rectangle, LightType::Disc}[i % 4];
        l.directionWs = glm::vec3(0.0f, 0.0f, -1.0f);
        l.radius = 0.05f * r;
        l.length = 0.3f * r;
        l.width = 0.2f * r;
        l.height = 0.1f * r;
    }
    scene.lights = lights;
    RenderSettings settings;
    settings.shadows = false;
    Renderer renderer(context(), scene, Environment::constant(glm::vec3(0.0f)), &LutSet::loadDefault(), settings);
    const View view = perspectiveView(
        glm::inverse(glm::lookAt(glm::vec3(0.0f, 0.0f, 1.2f), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f))), 0.7f,
        1.0f, 0.1f, 10.0f);
    // Froxels of 16 px: at this size each holds fewer lights than its list's cap (at 320 px one would overflow).
    const RenderedImage image = renderer.render(view, 640, 640, OutputEncoding::LinearFloat);
    dumpImage("area_lights_65536", image);
    EXPECT_EQ(renderer.frameStats().clusterOverflows, 0u);
    double sum = 0.0;
    for (const float v : image.rgba32f) {
        ASSERT_TRUE(std::isfinite(v));
        sum += double(v);
    }
    EXPECT_GT(sum, 0.0);
}

class SkinAreaLights : public GpuTest {
protected:
    void SetUp() override {
        GpuTest::SetUp();
        Primitive sphere = makeSphere(0.005f, 64, 32);
        recomputeCurvature(sphere);
        sphere.material = 0;
        scene_ = makeScene({{sphere, glm::mat4(1.0f)}}, {skinMaterial({0.8f, 0.6f, 0.5f})});
        view_ = orbitView(scene_.worldBounds(), 0.0f, 8.0f, 0.0f, 1.0f);
    }

    RenderedImage render(const Light& light, bool skin, bool specular) {
        scene_.lights = {light};
        RenderSettings settings;
        settings.specular = specular;
        settings.shadows = false;
        if (!skin) settings.skin = SkinFeatures::none();
        Renderer renderer(context(), scene_, Environment::constant(glm::vec3(0.0f)), &LutSet::loadDefault(), settings);
        return renderer.render(view_, kSize, kSize, OutputEncoding::LinearFloat);
    }

    static constexpr uint32_t kSize = 64;
    Scene scene_;
    View view_;
};

TEST_F(SkinAreaLights, VanishingSphereLightEqualsAPointLight) {
    const glm::vec3 position = glm::vec3(-0.5f, 0.6f, 0.65f);
    Light point = areaLight(LightType::Point, position, {0.0f, 0.0f, -1.0f}, 3.0f);
    Light sphere = point;
    sphere.type = LightType::Sphere;
    sphere.radius = 0.0005f;  // half a millimetre at a metre: still the cap path (cos sigma < 1 in single precision)
    const RenderedImage a = render(point, true, true), b = render(sphere, true, true);
    dumpImage("area_light_vanishing_sphere", b);
    dumpImage("area_light_vanishing_point", a);
    EXPECT_LE(maxSrgbDifference(a, b), 1.0);
    EXPECT_GT(maxSrgbDifference(a, render(point, false, true)), 3.0) << "skin differs from Lambert here";
}

TEST_F(SkinAreaLights, InsideASphereLightTheSkinIsUniformlyLit) {
    Light light = areaLight(LightType::Sphere, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}, 1.0f);
    light.radius = 10.0f;
    const double radiance = 1.0 / (kPi * 100.0);  // candela over the projected area
    for (const bool skin : {false, true}) {
        const RenderedImage image = render(light, skin, false);
        const auto hits = traceSphere(view_, kSize, kSize, glm::dvec3(0.0), 0.005);
        double worst = 0.0;
        int pixels = 0;
        for (uint32_t y = 0; y < kSize; ++y)
            for (uint32_t x = 0; x < kSize; ++x) {
                if (!hits[size_t(y) * kSize + x].interior) continue;
                const glm::dvec3 got = pixelLinear(image, x, y);
                const glm::dvec3 want = glm::dvec3(0.8, 0.6, 0.5) * radiance;
                for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(got[c] / want[c] - 1.0));
                ++pixels;
            }
        std::printf("[ area lights ] %s sphere inside a sphere light: largest deviation from albedo x radiance %.4f\n",
                    skin ? "skin" : "Lambert", worst);
        EXPECT_GT(pixels, 1000);
        EXPECT_LT(worst, skin ? 0.02 : 1e-4);
    }
}

double skinOverLambert(const ReferenceImage& truth, const RenderedImage& skin, const RenderedImage& lambert) {
    double s = 0.0, l = 0.0;
    for (size_t i = 0; i < truth.skin.size(); ++i) {
        if (!truth.skin[i]) continue;
        for (size_t c = 0; c < 3; ++c) {
            const double want = double(truth.rgba32f[4 * i + c]);
            s += std::pow(double(skin.rgba32f[4 * i + c]) - want, 2.0);
            l += std::pow(double(lambert.rgba32f[4 * i + c]) - want, 2.0);
        }
    }
    return std::sqrt(s / l);
}

TEST_F(SkinAreaLights, SkinIsCloserToTheReferenceThanLambertUnderSphereAndRectangleLights) {
    const glm::vec3 towards = glm::normalize(glm::vec3(-0.5f, 0.6f, 0.65f));
    Light sphere = areaLight(LightType::Sphere, towards, -towards, 3.0f);
    sphere.radius = 0.1f;
    Light rectangle = areaLight(LightType::Rectangle, towards, -towards, 3.0f);
    rectangle.width = 1.0f;
    rectangle.height = 0.5f;
    for (const Light& light : {sphere, rectangle}) {
        const RenderedImage skin = render(light, true, false), lambert = render(light, false, false);
        const DiffusionReference reference(scene_, scene_.lights, ShRgb{}, LutSet::loadDefault().profile());
        const double ratio = skinOverLambert(reference.render(view_.eye(), kSize, kSize), skin, lambert);
        std::printf("[ area lights ] 10 mm skin sphere under a %s: skin / Lambert RMSE %.3f\n",
                    light.type == LightType::Sphere ? "sphere light" : "rectangle", ratio);
        EXPECT_LT(ratio, 0.5);
    }
}

}  // namespace
}  // namespace preskin::test
