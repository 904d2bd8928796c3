// Skin at the terminator of closed surfaces with nothing else in the light: a sphere and a torus
// lit from the side. The shadow map shadows each surface's own far side there, which is no cast
// shadow: the diffuse LUT already holds the light scattered past the terminator, so penumbra
// scattering must leave the terminator band (geometric N.L within [-0.1, 0.2], found by tracing
// the analytic surface through each pixel centre) as it is without it, within 1/255, and past
// the terminator the sphere's own shadow must not take away the light the LUT scatters there
// (the image with the shadow map as without it). On a cylinder lit across its axis the rows read
// along the light must bring red in the band closer to the diffusion reference than the mean
// curvature's rows.
#include "support/GpuTest.h"
#include "support/ImageCompare.h"
#include "support/SkinTestSupport.h"
#include "support/TestLights.h"
#include "support/TestScenes.h"

#include <preskin/DiffusionReference.h>
#include <preskin/LutSet.h>
#include <preskin/Renderer.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>

namespace preskin::test {
namespace {

// The first hit of a ray on a surface given by its signed distance (sphere tracing in double
// precision) and the surface's normal there; none when the ray misses.
struct Hit {
    glm::dvec3 position;
    glm::dvec3 normal;
};
std::optional<Hit> traceSdf(const glm::dvec3& origin, const glm::dvec3& direction,
                            const std::function<double(const glm::dvec3&)>& sdf) {
    double t = 0.0;
    for (int i = 0; i < 2000; ++i) {
        const glm::dvec3 p = origin + t * direction;
        const double d = sdf(p);
        if (d < 1e-9) {
            const double e = 1e-7;
            const glm::dvec3 n(sdf(p + glm::dvec3(e, 0, 0)) - sdf(p - glm::dvec3(e, 0, 0)),
                               sdf(p + glm::dvec3(0, e, 0)) - sdf(p - glm::dvec3(0, e, 0)),
                               sdf(p + glm::dvec3(0, 0, e)) - sdf(p - glm::dvec3(0, 0, e)));
            return Hit{p, glm::normalize(n)};
        }
        t += d;
        if (t > 10.0) break;
    }
    return std::nullopt;
}

class SkinTerminator : public GpuTest {
protected:
    static constexpr uint32_t kSize = 128;

    // Specular off: the diffuse light alone.
    RenderedImage render(const Scene& scene, const View& view, RenderSettings settings) {
        settings.specular = false;
        Renderer renderer(context(), scene, Environment::constant(glm::vec3(0.0f)), &LutSet::loadDefault(), settings);
        return renderer.render(view, kSize, kSize, OutputEncoding::DisplaySrgb8);
    }

    // The surface alone as skin, under a shadowed directional light travelling along lightTravel.
    static Scene litSurface(Primitive surface, const glm::vec3& lightTravel) {
        recomputeCurvature(surface);
        surface.material = 0;
        Scene scene = makeScene({{surface, glm::mat4(1.0f)}}, {skinMaterial({0.8f, 0.6f, 0.5f})});
        scene.lights = {shadowedDirectionalLight(lightTravel, 3.0f)};
        return scene;
    }

    // Pixels of the terminator band whose 8-bit channels differ by more than 1 between penumbra
    // on and off, of how many; the largest difference.
    void compareBand(const char* what, const Primitive& surface, const std::function<double(const glm::dvec3&)>& sdf,
                     const glm::vec3& lightTravel, float yawDeg, float pitchDeg) {
        const Scene scene = litSurface(surface, lightTravel);
        const View view = orbitView(scene.worldBounds(), yawDeg, pitchDeg, 0.0f, 1.0f);
        RenderSettings off;
        off.skin.penumbra = false;
        compareWhere(what, "penumbra on and off", render(scene, view, RenderSettings()), render(scene, view, off), sdf,
                     -glm::normalize(glm::dvec3(lightTravel)), view, -0.1, 0.2);
    }

    // Pixels whose geometric N.L lies within [lo, hi] and whose 8-bit channels differ by more than
    // 1 between a and b, of how many; the largest difference.
    void compareWhere(const char* what, const char* pair, const RenderedImage& on, const RenderedImage& off,
                      const std::function<double(const glm::dvec3&)>& sdf, const glm::dvec3& L, const View& view,
                      double lo, double hi) {
        const glm::dmat4 worldFromClip = glm::inverse(glm::dmat4(view.eye().clipFromWorld()));
        size_t band = 0, differing = 0;
        int largest = 0;
        for (uint32_t y = 0; y < kSize; ++y)
            for (uint32_t x = 0; x < kSize; ++x) {
                const glm::dvec2 ndc((x + 0.5) / kSize * 2.0 - 1.0, (y + 0.5) / kSize * 2.0 - 1.0);
                const glm::dvec4 a = worldFromClip * glm::dvec4(ndc, 1.0, 1.0);
                const glm::dvec4 b = worldFromClip * glm::dvec4(ndc, 0.5, 1.0);
                const glm::dvec3 origin = glm::dvec3(a) / a.w;
                const std::optional<Hit> hit = traceSdf(origin, glm::normalize(glm::dvec3(b) / b.w - origin), sdf);
                if (!hit) continue;
                const double NoL = glm::dot(hit->normal, L);
                if (NoL < lo || NoL > hi) continue;
                ++band;
                int d = 0;
                for (int c = 0; c < 3; ++c) {
                    const size_t i = (size_t(y) * kSize + x) * 4 + size_t(c);
                    d = std::max(d, std::abs(int(on.rgba8[i]) - int(off.rgba8[i])));
                }
                largest = std::max(largest, d);
                differing += d > 1 ? 1 : 0;
            }
        std::printf(
            "[ terminator ] %s, %s, N.L in [%.2f, %.2f]: %zu of %zu pixels differ by more than 1/255 "
            "(largest %d/255)\n",
            what, pair, lo, hi, differing, band, largest);
        EXPECT_GT(band, size_t(kSize));
        EXPECT_EQ(differing, 0u) << what << ", " << pair;
    }
};

TEST_F(SkinTerminator, PenumbraChangesNothingAtTheTerminatorOfASphere) {
    for (const double radiusM : {0.005, 0.02}) {
        const Primitive sphere = makeSphere(float(radiusM), 96, 48);
        const auto sdf = [radiusM](const glm::dvec3& p) { return glm::length(p) - radiusM; };
        compareBand(radiusM < 0.01 ? "10 mm sphere" : "40 mm sphere", sphere, sdf, {-1.0f, -0.2f, 0.0f}, 0.0f, 0.0f);
    }
}

TEST_F(SkinTerminator, PenumbraChangesNothingAtTheTerminatorOfATorus) {
    const double majorM = 0.02, minorM = 0.008;
    const Primitive torus = makeTorus(float(majorM), float(minorM), 128, 64);
    const auto sdf = [&](const glm::dvec3& p) {
        return glm::length(glm::dvec2(glm::length(glm::dvec2(p.x, p.z)) - majorM, p.y)) - minorM;
    };
    // Lit along its axis: no part of the ring shadows another.
    compareBand("torus (20 mm, 8 mm tube)", torus, sdf, {0.0f, -1.0f, 0.0f}, 0.0f, 20.0f);
}

// Past the terminator a 40 mm sphere gets the diffuse LUT's light scattered from its lit side,
// which its own shadow in the map must not remove: with the shadow map as without it. Without
// telling the sphere's own shadow from a cast one (preskinCastShadowShare) the map takes that
// light away: 536 of 2,143 pixels there differ, by up to 5/255.
TEST_F(SkinTerminator, OwnShadowKeepsTheLightScatteredPastTheTerminator) {
    const double radiusM = 0.02;
    const auto sdf = [radiusM](const glm::dvec3& p) { return glm::length(p) - radiusM; };
    const glm::vec3 travel(-1.0f, -0.2f, 0.0f);
    const Scene scene = litSurface(makeSphere(float(radiusM), 96, 48), travel);
    const View view = orbitView(scene.worldBounds(), 0.0f, 0.0f, 0.0f, 1.0f);
    RenderSettings shadowed;
    shadowed.skin.transmission = false;  // read from the shadow map; nothing to add on a sphere
    shadowed.skin.opposingLight = false;
    RenderSettings unshadowed = shadowed;
    unshadowed.shadows = false;
    compareWhere("40 mm sphere", "shadow map on and off", render(scene, view, shadowed),
                 render(scene, view, unshadowed), sdf, -glm::normalize(glm::dvec3(travel)), view, -0.4, -0.02);
}

// A skin cylinder of radius 3 mm lit across its axis and seen from the front, the terminator
// running along its middle: a sphere of its mean curvature (half its curvature across) holds
// half the light the profile scatters past a cylinder's terminator, the sphere of its curvature
// across nearly all of it (docs/fidelity.md). With each light's row at the curvature along it
// (kSkinLightCurvature) red in the terminator band is closer to the diffusion reference than with
// the mean curvature's row, and the whole cylinder no farther.
TEST_F(SkinTerminator, RowAlongTheLightBringsACylindersTerminatorCloserToTheReference) {
    const glm::vec3 travel(0.0f, -1.0f, 0.0f);
    const Scene scene = litSurface(makeCylinder(0.003f, 0.06f, 96, 24), travel);
    const View view = orbitView(scene.worldBounds(), 0.0f, 0.0f, 0.025f, 1.0f);
    auto renderWith = [&](bool lightCurvature) {
        RenderSettings settings;
        settings.specular = false;
        settings.skin.lightCurvature = lightCurvature;
        Renderer renderer(context(), scene, Environment::constant(glm::vec3(0.0f)), &LutSet::loadDefault(), settings);
        return renderer.render(view, kSize, kSize, OutputEncoding::LinearFloat);
    };
    const RenderedImage alongLight = renderWith(true), mean = renderWith(false);
    const ReferenceSettings coarse = coarseReferenceSettings();
    const DiffusionReference reference(scene, scene.lights, ShRgb{}, LutSet::loadDefault().profile(), coarse);
    const ReferenceImage truth = reference.render(view.eye(), kSize, kSize);
    // Red's RMSE of each against the reference, in the band and over the whole cylinder.
    double bandAlong = 0.0, bandMean = 0.0, allAlong = 0.0, allMean = 0.0;
    size_t band = 0, all = 0;
    for (size_t i = 0; i < truth.skin.size(); ++i) {
        if (!truth.skin[i]) continue;
        const double want = double(truth.rgba32f[4 * i]);
        const double a = std::pow(double(alongLight.rgba32f[4 * i]) - want, 2.0);
        const double m = std::pow(double(mean.rgba32f[4 * i]) - want, 2.0);
        allAlong += a;
        allMean += m;
        ++all;
        if (!truth.terminatorBand[i]) continue;
        bandAlong += a;
        bandMean += m;
        ++band;
    }
    const double bandRatio = std::sqrt(bandAlong / bandMean), allRatio = std::sqrt(allAlong / allMean);
    std::printf(
        "[ terminator ] 6 mm cylinder lit across (%zu pixels, %zu in the band): red RMSE with the row along "
        "the light / with the mean curvature's, band %.3f, whole %.3f\n",
        all, band, bandRatio, allRatio);
    EXPECT_GT(band, size_t(kSize) * 3);
    EXPECT_LT(bandRatio, 0.8);
    EXPECT_LE(allRatio, 1.0);
}

}  // namespace
}  // namespace preskin::test
