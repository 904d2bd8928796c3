// The diffusion reference (DiffusionReference) against analytic cases:
//  - a flat plane under a directional light and uniform ambient equals Lambert (the profile
//    integrates to one over the plane) within 1e-3, for d'Eon's Gaussians and for Burley, at
//    scatter scales 1 and 2;
//  - a sphere converges to the exact sphere integral as its mesh is refined. The exact value
//    (derived in docs/reference.md) is the 1D integral over the angle psi between x and y of
//    a^2 Rn(2 a sin(psi / 2)) sin(psi) Phi(theta, psi), where Phi is the closed-form azimuthal
//    integral of the clamped cosine, evaluated here by adaptive Simpson quadrature (test-side);
//  - results are bitwise identical on 1 and 2 threads and from run to run;
//  - the terminator band is where the sphere's analytic normal turns from the light (its cosine
//    within [-0.1, 0.2]), and a cast shadow within the clearance takes it away.
#include "reference/test_lut_reference.h"
#include "support/SkinTestSupport.h"
#include "support/TestLights.h"
#include "support/TestScenes.h"

#include <preskin/DiffusionReference.h>
#include <preskin/Environment.h>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdio>
#include <cstring>

namespace preskin::test {
namespace {

// Azimuthal integral of the clamped cosine: int_0^2pi max(A + B cos(phi), 0) dphi, B >= 0.
double azimuthalClampedCosine(double A, double B) {
    if (A >= B) return 2.0 * kPi * A;
    if (A <= -B) return 0.0;
    const double phi0 = std::acos(-A / B);
    return 2.0 * (A * phi0 + B * std::sin(phi0));
}

// Exact int_S Rn(|x - y|) max(n_y . L, 0) dA(y) on a sphere of radius a (profile mm) at a point
// whose normal makes the angle theta with L, for one channel.
double exactSphereIntegral(const DiffusionProfile& profile, int channel, double radiusMm, double theta) {
    const double albedo = profile.albedo()[channel];
    auto integrand = [&](double psi) {
        const double A = std::cos(theta) * std::cos(psi), B = std::sin(theta) * std::sin(psi);
        const double chord = 2.0 * radiusMm * std::sin(0.5 * psi);
        return radiusMm * radiusMm * profile.R(std::max(chord, 1e-12))[channel] / albedo * std::sin(psi) *
            azimuthalClampedCosine(A, std::max(B, 0.0));
    };
    const double k1 = std::abs(0.5 * kPi - theta);
    const double k2 = std::min(0.5 * kPi + theta, 1.5 * kPi - theta);
    double sum = integrateGradedTowardsStart(integrand, 0.0, std::max(k1, 1e-9), 1e-12);
    if (k2 > k1) sum += adaptiveSimpson(integrand, k1, k2, 1e-12, 8);
    if (kPi > k2) sum += adaptiveSimpson(integrand, k2, kPi, 1e-12, 8);
    return sum;
}

TEST(DiffusionReference, ExactSphereIntegralHasTheFlatLimit) {
    // The test's own exact integral must give Lambert's cos(theta) for a sphere much larger than
    // the profile (and the normalised profile's total 1 at theta = 0 minus curvature effects).
    const DiffusionProfile profile = DiffusionProfile::deonLuebke();
    for (double theta : {0.0, 0.5, 1.0, 1.4}) {
        const double value = exactSphereIntegral(profile, 0, 1e5, theta);
        EXPECT_NEAR(value, std::cos(theta), 1e-4) << theta;
    }
}

struct PlaneCase {
    const char* name;
    bool burley;
    float scatterScale;
};

class DiffusionReferencePlane : public ::testing::TestWithParam<PlaneCase> {};

TEST_P(DiffusionReferencePlane, EqualsLambertWithin1e3) {
    const PlaneCase& c = GetParam();
    const DiffusionProfile profile =
        c.burley ? DiffusionProfile::burley({0.8, 0.6, 0.5}, {3.0, 1.2, 0.6}) : DiffusionProfile::deonLuebke();
    const glm::vec3 albedo(0.7f, 0.5f, 0.4f);
    // A 0.2 m square (far beyond the 1e-4 reach of either profile at these scales), coarse.
    Primitive plane = makeQuad(0.2f, 4);
    plane.material = 0;
    Scene scene = makeScene({{plane, glm::mat4(1.0f)}}, {skinMaterial(albedo, c.scatterScale)});
    const Light light = shadowedDirectionalLight(glm::vec3(0.6f, -0.3f, -0.74f), 2.0f);
    const glm::vec3 ambient(0.3f, 0.25f, 0.2f);
    const Environment env = Environment::constant(ambient);
    const DiffusionReference reference(scene, {light}, env.radianceSh(), profile);
    const glm::dvec3 L = -glm::normalize(glm::dvec3(light.directionWs));
    // Lambert: E = intensity N.L + pi * ambient radiance (SH of a constant, Lambert bands).
    const glm::dvec3 E = glm::dvec3(double(light.intensity) * L.z) +
        glm::dvec3(env.radianceSh().c[0]) * (0.282095 * 3.14159265358979323846);
    const glm::dvec3 lambert = glm::dvec3(albedo) / 3.14159265358979323846 * E;
    for (const glm::dvec2 at : {glm::dvec2(0.0, 0.0), glm::dvec2(0.013, -0.021), glm::dvec2(-0.03, 0.007)}) {
        const auto sample = reference.trace(glm::dvec3(at, 0.5), glm::dvec3(0.0, 0.0, -1.0));
        ASSERT_TRUE(sample.has_value());
        EXPECT_TRUE(sample->skin);
        for (int ch = 0; ch < 3; ++ch)
            EXPECT_NEAR(sample->radiance[ch] / lambert[ch], 1.0, 1e-3) << c.name << " channel " << ch;
    }
}

INSTANTIATE_TEST_SUITE_P(Profiles, DiffusionReferencePlane,
                         ::testing::Values(PlaneCase{"deon", false, 1.0f}, PlaneCase{"deon_scale2", false, 2.0f},
                                           PlaneCase{"burley", true, 1.0f}),
                         [](const auto& param) { return std::string(param.param.name); });

// Relative error (to the lit pole's value, 1) of the reference on a UV sphere mesh of the given
// resolution, the largest over points spread from the lit side across the terminator.
double sphereError(const DiffusionProfile& profile, double radiusM, uint32_t segments,
                   const ReferenceSettings& settings, int channel, bool print) {
    Primitive sphere = makeSphere(float(radiusM), segments, segments / 2);
    sphere.material = 0;
    recomputeCurvature(sphere);
    Scene scene = makeScene({{sphere, glm::mat4(1.0f)}}, {skinMaterial(glm::vec3(1.0f), 1.0f)});
    const glm::dvec3 L = glm::normalize(glm::dvec3(-0.3, 0.8, 0.52));
    const Light light = shadowedDirectionalLight(-glm::vec3(L), 1.0f);
    const DiffusionReference reference(scene, {light}, ShRgb{}, profile, settings);
    // A direction perpendicular to L: points at angle theta from L lie in the plane (L, u),
    // turned a little about L so they avoid the mesh's symmetry planes.
    const glm::dvec3 u0 = glm::normalize(glm::cross(L, glm::dvec3(0.0, 0.0, 1.0)));
    const glm::dvec3 u = glm::normalize(u0 * std::cos(0.3) + glm::cross(L, u0) * std::sin(0.3));
    double worst = 0.0;
    for (double thetaDeg : {0.0, 45.0, 80.0, 90.0, 100.0, 115.0, 135.0}) {
        const double t = glm::radians(thetaDeg);
        const glm::dvec3 n = L * std::cos(t) + u * std::sin(t);
        const auto sample = reference.trace(n * (3.0 * radiusM), -n);
        if (!sample) return 1e9;
        const double theta = std::acos(std::clamp(glm::dot(glm::normalize(sample->positionWs), L), -1.0, 1.0));
        const double exact = exactSphereIntegral(profile, channel, radiusM * 1000.0, theta);
        const double got = sample->radiance[channel] * 3.14159265358979323846;
        worst = std::max(worst, std::abs(got - exact));
        if (print)
            std::printf("[ sphere   ] %u segments, theta %5.1f deg: reference %.6f exact %.6f (error %+.2e)\n",
                        segments, glm::degrees(theta), got, exact, got - exact);
    }
    return worst;
}

TEST(DiffusionReference, SphereConvergesToTheExactIntegral) {
    const DiffusionProfile profile = DiffusionProfile::deonLuebke();
    const ReferenceSettings settings;
    // Red (the widest channel) on a sphere of 10 mm diameter: every point integrates over the
    // whole sphere, including the dark side.
    std::vector<double> errors;
    for (uint32_t segments : {16u, 32u, 64u}) {
        const double e = sphereError(profile, 0.005, segments, settings, 0, true);
        std::printf("[ sphere   ] %u segments: largest error %.3e\n", segments, e);
        errors.push_back(e);
    }
    // Second order in the mesh spacing: about 4x per halving; at 64 segments (0.5 mm edges)
    // within 1e-3 of the lit pole's value.
    EXPECT_LT(errors[1], 0.5 * errors[0]);
    EXPECT_LT(errors[2], 0.5 * errors[1]);
    EXPECT_LT(errors[2], 1e-3);
}

// A traced uniform environment over an unoccluded skin plane: the irradiance is pi L exactly,
// and the reference equals Lambert (albedo L).
TEST(DiffusionReference, TracedUniformEnvironmentOnAPlaneIsLambertsIrradiance) {
    const glm::vec3 albedo(0.7f, 0.5f, 0.4f), radiance(0.3f, 0.25f, 0.2f);
    Primitive plane = makeQuad(0.2f, 4);
    plane.material = 0;
    const Scene scene = makeScene({{plane, glm::mat4(1.0f)}}, {skinMaterial(albedo, 1.0f)});
    const Environment env = Environment::constant(radiance);
    ReferenceSettings settings;
    settings.environmentSamples = 64;
    const DiffusionReference reference(scene, {}, env, DiffusionProfile::deonLuebke(), settings);
    for (const glm::dvec2 at : {glm::dvec2(0.0, 0.0), glm::dvec2(0.013, -0.021)}) {
        const auto sample = reference.trace(glm::dvec3(at, 0.5), glm::dvec3(0.0, 0.0, -1.0));
        ASSERT_TRUE(sample.has_value());
        for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(sample->radiance[ch] / double(albedo[ch] * radiance[ch]), 1.0, 1e-3);
    }
}

// On a convex sphere nothing occludes the environment, so for an environment of bands 0 and 1
// alone (which L2 SH holds exactly) the traced reference must approach the SH one as the mesh is
// refined (the traced irradiance is found per vertex and interpolated).
TEST(DiffusionReference, TracedEnvironmentOnASphereConvergesAsTheMeshIsRefined) {
    const Environment env = makeEnvironment(
        64, [](const glm::vec3& d) { return glm::vec3(0.3f, 0.25f, 0.2f) * (1.0f + 0.7f * d.y) + 0.1f * d.x; });
    std::vector<double> errors;
    for (uint32_t segments : {12u, 24u, 48u}) {
        Primitive sphere = makeSphere(0.005f, segments, segments / 2);
        sphere.material = 0;
        recomputeCurvature(sphere);
        const Scene scene = makeScene({{sphere, glm::mat4(1.0f)}}, {skinMaterial(glm::vec3(1.0f), 1.0f)});
        ReferenceSettings traced;
        traced.environmentSamples = 1024;
        const DiffusionReference withRays(scene, {}, env, DiffusionProfile::deonLuebke(), traced);
        const DiffusionReference withSh(scene, {}, env, DiffusionProfile::deonLuebke());
        double worst = 0.0;
        for (const glm::dvec3 n : {glm::dvec3(0.0, 1.0, 0.0), glm::normalize(glm::dvec3(0.7, 0.2, 0.3)),
                                   glm::normalize(glm::dvec3(-0.2, -0.9, 0.4))}) {
            const auto a = withRays.trace(n * 0.02, -n), b = withSh.trace(n * 0.02, -n);
            ASSERT_TRUE(a && b);
            for (int ch = 0; ch < 3; ++ch) worst = std::max(worst, std::abs(a->radiance[ch] / b->radiance[ch] - 1.0));
        }
        std::printf("[ ambient  ] %u segments: traced against SH, largest relative difference %.4f\n", segments, worst);
        errors.push_back(worst);
    }
    EXPECT_LT(errors[2], errors[0]);
    EXPECT_LT(errors[2], 0.01);
}

TEST(DiffusionReference, RenderIsBitwiseReproducibleAndThreadIndependent) {
    const DiffusionProfile profile = DiffusionProfile::deonLuebke();
    Primitive sphere = makeSphere(0.01f, 24, 12);
    sphere.material = 0;
    recomputeCurvature(sphere);
    Primitive floor = makeQuad(0.04f, 2);
    floor.material = 0;
    Scene scene = makeScene({{sphere, glm::mat4(1.0f)},
                             {floor,
                              glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, -0.012f, 0.0f)), -1.5707963f,
                                          glm::vec3(1.0f, 0.0f, 0.0f))}},
                            {skinMaterial(glm::vec3(0.8f, 0.6f, 0.5f), 1.0f)});
    const Light light = shadowedDirectionalLight(glm::vec3(0.4f, -1.0f, -0.3f), 2.0f);
    const Environment env = Environment::constant(glm::vec3(0.1f));
    // Determinism does not depend on the accuracy: keep the test fast.
    const ReferenceSettings coarse = coarseReferenceSettings();
    const DiffusionReference reference(scene, {light}, env.radianceSh(), profile, coarse);
    const View view = orbitView(scene.worldBounds(), 20.0f, 25.0f, 0.0f, 1.0f);
    auto renderWith = [&](int threads) {
        tbb::global_control control(tbb::global_control::max_allowed_parallelism, size_t(threads));
        return reference.render(view.eye(), 32, 32);
    };
    const ReferenceImage one = renderWith(1);
    const ReferenceImage two = renderWith(2);
    const ReferenceImage again = renderWith(2);
    ASSERT_EQ(one.rgba32f.size(), two.rgba32f.size());
    EXPECT_EQ(std::memcmp(one.rgba32f.data(), two.rgba32f.data(), one.rgba32f.size() * sizeof(float)), 0);
    EXPECT_EQ(std::memcmp(two.rgba32f.data(), again.rgba32f.data(), two.rgba32f.size() * sizeof(float)), 0);
    EXPECT_EQ(one.nearShadowEdge, two.nearShadowEdge);
    EXPECT_EQ(one.curvaturePerMm, two.curvaturePerMm);
    size_t covered = 0, edge = 0;
    for (size_t i = 0; i < one.skin.size(); ++i) {
        covered += one.skin[i];
        edge += one.nearShadowEdge[i];
    }
    EXPECT_GT(covered, 200u);
    EXPECT_GT(edge, 0u) << "the sphere's shadow on the floor has an edge";
    EXPECT_LT(edge, covered / 2);
}

// The band of a 10 mm skin sphere lit from the side, against the sphere's analytic normals
// through the same pixel centres (pixels within 0.03 of the band's bounds may go either way: the
// mesh's interpolated normals); then with a box casting a shadow on the sphere, which lies within
// the 12 mm clearance of every point: no band.
TEST(DiffusionReference, TerminatorBandIsWhereTheSphereTurnsFromTheLightAwayFromCastShadows) {
    const DiffusionProfile profile = DiffusionProfile::deonLuebke();
    const double radiusM = 0.005;
    Primitive sphere = makeSphere(float(radiusM), 48, 24);
    sphere.material = 0;
    recomputeCurvature(sphere);
    const ReferenceSettings coarse = coarseReferenceSettings();
    const Light light = shadowedDirectionalLight(glm::vec3(-1.0f, 0.0f, 0.0f), 2.0f);
    const glm::dvec3 L(1.0, 0.0, 0.0);
    const Scene lone = makeScene({{sphere, glm::mat4(1.0f)}}, {skinMaterial(glm::vec3(0.8f, 0.6f, 0.5f), 1.0f)});
    const View view = orbitView(lone.worldBounds(), 0.0f, 0.0f, 0.0f, 1.0f);
    constexpr uint32_t kSize = 40;
    const ReferenceImage image =
        DiffusionReference(lone, {light}, ShRgb{}, profile, coarse).render(view.eye(), kSize, kSize);
    const auto hits = traceSphere(view, kSize, kSize, glm::dvec3(0.0), radiusM);
    size_t band = 0, wrong = 0;
    for (size_t i = 0; i < hits.size(); ++i) {
        if (!hits[i].interior) continue;
        const double NoL = glm::dot(glm::normalize(hits[i].positionWs), L);
        const bool inside = NoL >= kTerminatorBandNoL[0] && NoL <= kTerminatorBandNoL[1];
        const bool nearBound =
            std::abs(NoL - kTerminatorBandNoL[0]) < 0.03 || std::abs(NoL - kTerminatorBandNoL[1]) < 0.03;
        band += image.terminatorBand[i];
        if ((image.terminatorBand[i] != 0) != inside && !nearBound) ++wrong;
    }
    std::printf("[ reference] terminator band: %zu pixels, %zu misplaced\n", band, wrong);
    EXPECT_GT(band, 40u);
    EXPECT_EQ(wrong, 0u);

    // A box above the sphere's lit side shadows part of it.
    Primitive box = makeBox(glm::vec3(0.004f, 0.002f, 0.012f));
    box.material = 1;
    Scene shadowed =
        makeScene({{sphere, glm::mat4(1.0f)}, {box, glm::translate(glm::mat4(1.0f), glm::vec3(0.009f, 0.004f, 0.0f))}},
                  {skinMaterial(glm::vec3(0.8f, 0.6f, 0.5f), 1.0f), Material{}});
    const ReferenceImage withShadow =
        DiffusionReference(shadowed, {light}, ShRgb{}, profile, coarse).render(view.eye(), kSize, kSize);
    size_t shadowedBand = 0;
    for (uint8_t b : withShadow.terminatorBand) shadowedBand += b;
    EXPECT_EQ(shadowedBand, 0u);
}

}  // namespace
}  // namespace preskin::test
