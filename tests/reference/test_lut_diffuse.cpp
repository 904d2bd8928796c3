// Tests of the pre-integrated diffuse LUT D(NoL, curvature) over the sphere of the signed
// curvature (SphereScatter.h, after Penner & Borshukov 2011): the library's integrator and the
// baked, bilinearly sampled table against an independent surface integration
// (test_lut_reference.h), convex and concave; the flat limit saturate(NoL); monotonicity in NoL;
// energy bounds; red >= green >= blue wrap at NoL = 0 on convex skin, none on concave skin;
// closed forms of one Gaussian on a small sphere, inside and out, with the patch's shadow.
#include "reference/test_lut_reference.h"

#include "skin/SphereScatter.h"

#include <preskin/LutSet.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

namespace preskin::test {
namespace {

struct Point {
    double NoL;
    double curvaturePerMm;
};

// Random points over the whole table: NoL uniform; |curvature| half uniform on [0, max], half
// log-uniform on [max / 200, max] (the face range); every third one concave.
std::vector<Point> randomPoints(int count, double curvatureMax, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<Point> points;
    for (int i = 0; i < count; ++i) {
        const double NoL = -1.0 + 2.0 * unit(rng);
        const double c = i % 2 == 0 ? curvatureMax * unit(rng) : curvatureMax * std::pow(200.0, -unit(rng));
        points.push_back({NoL, i % 3 == 2 ? -c : c});
    }
    // Also the hard places: the terminator at tiny and large curvatures, and grazing light on a
    // concave patch (its rim).
    for (double c : {curvatureMax * 1e-4, curvatureMax * 3e-3, curvatureMax * 0.05, curvatureMax}) {
        for (double NoL : {-0.003, 0.0, 0.002, 0.011}) points.push_back({NoL, c});
        for (double NoL : {0.01, 0.1, 0.3}) points.push_back({NoL, -c});
    }
    return points;
}

TEST(LutDiffuse, SphereIntegralMatchesIndependentIntegration) {
    for (const DiffusionProfile& profile :
         {DiffusionProfile::deonLuebke(), DiffusionProfile::burley({0.8, 0.5, 0.3}, {2.0, 0.9, 0.4})}) {
        const double patchMm = profile.maxWidthMm();
        double maxError = 0.0;
        for (const Point& p : randomPoints(6, 1.0, 7)) {
            const glm::dvec3 got = skin::sphereScatter(profile, p.curvaturePerMm, patchMm, p.NoL);
            for (int c = 0; c < 3; ++c) {
                const double want = test::referenceSphereScatter(profile, c, p.NoL, p.curvaturePerMm, patchMm);
                maxError = std::max(maxError, std::abs(got[c] - want));
                ASSERT_NEAR(got[c], want, 2e-4)
                    << profile.name() << " channel " << c << " NoL " << p.NoL << " curvature " << p.curvaturePerMm;
            }
        }
        RecordProperty(profile.kind() == DiffusionProfile::Kind::SumOfGaussians ? "maxIntegratorErrorDeon"
                                                                                : "maxIntegratorErrorBurley",
                       std::to_string(maxError));
        std::printf("sphere integral vs reference (%s): max abs error %.3g\n", profile.name().c_str(), maxError);
    }
}

TEST(LutDiffuse, BakedTableMatchesIndependentIntegration) {
    const LutSet& luts = LutSet::loadDefault();
    double maxError[2] = {0.0, 0.0};  // convex, concave
    Point worst[2]{};
    const std::vector<Point> points = randomPoints(30, luts.settings().curvatureMaxPerMm, 11);
    for (const Point& p : points) {
        const glm::vec3 got = luts.lookupDiffuse(static_cast<float>(p.NoL), static_cast<float>(p.curvaturePerMm));
        const int side = p.curvaturePerMm < 0.0 ? 1 : 0;
        for (int c = 0; c < 3; ++c) {
            const double want =
                test::referenceSphereScatter(luts.profile(), c, p.NoL, p.curvaturePerMm, luts.localPatchMm());
            const double error = std::abs(static_cast<double>(got[c]) - want);
            if (error > maxError[side]) {
                maxError[side] = error;
                worst[side] = p;
            }
        }
    }
    RecordProperty("maxLookupError", std::to_string(maxError[0]));
    RecordProperty("maxLookupErrorConcave", std::to_string(maxError[1]));
    for (int side = 0; side < 2; ++side)
        std::printf(
            "diffuse LUT lookup vs reference at %zu points, %s: max abs error %.3g (NoL %.4f, curvature %.4f /mm)\n",
            points.size(), side ? "concave" : "convex", maxError[side], worst[side].NoL, worst[side].curvaturePerMm);
    EXPECT_LE(maxError[0], 1e-3);
    // The concave half has a kink where the patch's rim starts to shadow the point itself
    // (NoL = sin(rho |k| / 2)); bilinear interpolation rounds it off.
    EXPECT_LE(maxError[1], 6e-3);
}

TEST(LutDiffuse, FlatLimitIsSaturatedNoL) {
    const LutSet& luts = LutSet::loadDefault();
    const LutTable& table = luts.diffuse();
    const int flat = table.height() / 2;
    EXPECT_EQ(table.y.valueAt(flat), 0.0);
    for (int ix = 0; ix < table.width(); ++ix) {
        const double want = std::clamp(table.x.valueAt(ix), 0.0, 1.0);
        const glm::vec3 got = table.texel(ix, flat);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want, 2e-3) << "NoL " << table.x.valueAt(ix);
    }
    // Between texels too: the NoL axis has a texel centre at 0, so the lookup is exact up to half rounding.
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> nol(-1.0f, 1.0f);
    for (int i = 0; i < 200; ++i) {
        const float n = nol(rng);
        const glm::vec3 got = luts.lookupDiffuse(n, 0.0f);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], std::clamp(n, 0.0f, 1.0f), 2e-3) << "NoL " << n;
    }
    // The physical flat limit, r -> infinity, of the integrator itself, from either side.
    for (double k : {1e-6, -1e-6})
        for (double n : {-0.5, -0.01, 0.0, 0.01, 0.3, 1.0}) {
            const glm::dvec3 d = skin::sphereScatter(luts.profile(), k, luts.localPatchMm(), n);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(d[c], std::clamp(n, 0.0, 1.0), 2e-3) << "curvature " << k;
        }
}

TEST(LutDiffuse, MonotoneInNoLAndBounded) {
    const LutTable& table = LutSet::loadDefault().diffuse();
    for (int iy = 0; iy < table.height(); ++iy) {
        for (int ix = 0; ix < table.width(); ++ix) {
            const glm::vec3 v = table.texel(ix, iy);
            for (int c = 0; c < 3; ++c) {
                ASSERT_GE(v[c], 0.0f);
                ASSERT_LE(v[c], 1.0f);
                // Monotone on convex skin; a concave patch's rim need not shadow less as the
                // light rises over the point's own normal.
                if (ix > 0 && iy >= table.height() / 2) {
                    ASSERT_GE(v[c], table.texel(ix - 1, iy)[c]) << "row " << iy << " column " << ix << " channel " << c;
                }
            }
        }
    }
}

TEST(LutDiffuse, WrapAtTerminatorIsRedGreenBlueOrderedAndGrowsWithCurvature) {
    const LutTable& table = LutSet::loadDefault().diffuse();
    const int zero = table.width() / 2;
    const int flat = table.height() / 2;
    ASSERT_EQ(table.x.valueAt(zero), 0.0);
    float previousRed = -1.0f;
    for (int iy = flat; iy < table.height(); ++iy) {  // convex rows
        const glm::vec3 v = table.texel(zero, iy);
        EXPECT_GE(v.r, v.g) << "curvature " << table.y.valueAt(iy);
        EXPECT_GE(v.g, v.b) << "curvature " << table.y.valueAt(iy);
        EXPECT_GE(v.r, previousRed);
        previousRed = v.r;
    }
    const glm::vec3 highest = table.texel(zero, table.height() - 1);
    EXPECT_GT(highest.r, 0.1f);  // a visible red wrap on a 1 mm radius
    EXPECT_GT(highest.r - highest.b, 0.05f);
}

TEST(LutDiffuse, ConcaveSkinShadowsItselfWhereConvexSkinWrapsLight) {
    const LutSet& luts = LutSet::loadDefault();
    // A 5 mm radius, either side: past the terminator concave skin gets less light than convex
    // skin (only from beyond its patch); under grazing light its rim darkens it below the convex
    // sphere; light from above the patch is hardly changed.
    for (float NoL : {-0.2f, -0.05f, 0.0f}) {
        const glm::vec3 concave = luts.lookupDiffuse(NoL, -0.2f), convex = luts.lookupDiffuse(NoL, 0.2f);
        EXPECT_LT(concave.r, 0.8f * convex.r) << "NoL " << NoL;
    }
    for (float NoL : {0.05f, 0.15f}) {
        const glm::vec3 concave = luts.lookupDiffuse(NoL, -0.2f), convex = luts.lookupDiffuse(NoL, 0.2f);
        for (int c = 0; c < 3; ++c) EXPECT_LT(concave[c], convex[c]) << "NoL " << NoL;
    }
    const glm::vec3 overhead = luts.lookupDiffuse(1.0f, -0.2f), overheadConvex = luts.lookupDiffuse(1.0f, 0.2f);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(overhead[c], overheadConvex[c], 0.02f);
    // With a vanishing patch the concave integral is the convex one (the same surface integral
    // without the self-shadowing).
    for (double NoL : {-0.1, 0.2, 0.7})
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(skin::sphereScatter(luts.profile(), -0.2, 0.0, NoL)[c],
                        skin::sphereScatter(luts.profile(), 0.2, 0.0, NoL)[c], 1e-4);
}

// One Gaussian of variance v on a sphere of radius a, light along the normal (NoL = +-1): with
// u = cos(psi) the kernel is exp(kappa u), kappa = a^2 / v, and a neighbour's irradiance is +-u,
// so D = int e^(kappa u) (+-u) du over the lit and visible u, divided by int_-1^1 e^(kappa u) du.
// Inside the sphere the patch of arc radius Psi around the point hides the neighbours whose ray
// to the light leaves the sphere on it (the ray from y along L leaves at y - 2 (y . L) L): with
// the light along the normal, u < -cos(Psi); against it, u < -cos(Psi) as well, where the facing
// neighbours (u < 0) lie on the far side and their rays cross the cavity towards the point.
TEST(LutDiffuse, ConcaveHalfMatchesClosedFormsOfOneGaussian) {
    const double v = 1.0, a = 2.0, kappa = a * a / v;
    const DiffusionProfile profile = DiffusionProfile::sumOfGaussians({{v, glm::dvec3(1.0)}}, "one Gaussian");
    ASSERT_GE(profile.reachMm(1e-4), 2.0 * a) << "the whole sphere must be within the profile's reach";
    const auto F = [&](double u) { return std::exp(kappa * u) * (u / kappa - 1.0 / (kappa * kappa)); };
    const double norm = (std::exp(kappa) - std::exp(-kappa)) / kappa;
    const auto facing = [&](double lo, double hi) { return (F(hi) - F(lo)) / norm; };     // int e^(k u) u du
    const auto opposite = [&](double lo, double hi) { return -(F(hi) - F(lo)) / norm; };  // int e^(k u) (-u) du
    struct Case {
        double curvaturePerMm, patchRadians, NoL, want;
        const char* what;
    };
    const double wide = 0.75 * std::numbers::pi, narrow = std::numbers::pi / 3.0;
    const std::vector<Case> cases{
        {1.0 / a, wide, 1.0, facing(0.0, 1.0), "convex, light along the normal"},
        {1.0 / a, wide, -1.0, opposite(-1.0, 0.0), "convex, light from behind"},
        {-1.0 / a, narrow, 1.0, facing(0.0, 1.0), "concave, patch too small to shadow"},
        {-1.0 / a, wide, 1.0, facing(-std::cos(wide), 1.0), "concave, the patch shadows the far neighbours"},
        {-1.0 / a, narrow, -1.0, opposite(-std::cos(narrow), 0.0),
         "concave, light from behind: the neighbours whose rays miss the patch"},
    };
    for (const Case& c : cases) {
        const glm::dvec3 got = skin::sphereScatter(profile, c.curvaturePerMm, c.patchRadians * a, c.NoL);
        std::printf("%s: %.6f (closed form %.6f)\n", c.what, got.r, c.want);
        // The step where the patch's shadow begins falls inside a quadrature panel (error about 3e-6).
        for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(got[ch], c.want, 1e-4) << c.what;
    }
    // The concave cases differ from the convex ones by far more than the tolerance.
    EXPECT_GT(facing(0.0, 1.0) - facing(-std::cos(wide), 1.0), 0.1);
    EXPECT_GT(opposite(-1.0, 0.0) - opposite(-std::cos(narrow), 0.0), 1e-3);
}

TEST(LutDiffuse, BurleyProfileBakes) {
    const DiffusionProfile profile = DiffusionProfile::burley({0.8, 0.5, 0.3}, {2.0, 0.9, 0.4});
    const LutSet luts = LutSet::bake(profile, LutBakeSettings::withSize(32));
    double maxError = 0.0;
    for (const Point& p : randomPoints(8, 1.0, 5)) {
        const glm::vec3 got = luts.lookupDiffuse(static_cast<float>(p.NoL), static_cast<float>(p.curvaturePerMm));
        for (int c = 0; c < 3; ++c)
            maxError = std::max(
                maxError,
                std::abs(static_cast<double>(got[c]) -
                         test::referenceSphereScatter(profile, c, p.NoL, p.curvaturePerMm, luts.localPatchMm())));
    }
    // A 32x32 table interpolates coarsely (the concave half's rim most); this checks the bake
    // path, not resolution.
    EXPECT_LE(maxError, 3e-2);
}

}  // namespace
}  // namespace preskin::test
