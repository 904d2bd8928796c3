// Tests of the pre-integrated diffuse LUT D(NoL, curvature) (Penner & Borshukov 2011): the
// library's ring integral and the baked, bilinearly sampled table against an independent
// adaptive integration (test_lut_reference.h), the flat limit saturate(NoL), monotonicity in
// NoL, energy bounds, and red >= green >= blue wrap at NoL = 0.
#include "test_lut_reference.h"

#include "skin/RingScatter.h"

#include <preskin/LutSet.h>

#include <gtest/gtest.h>

#include <random>

namespace preskin {
namespace {

struct Point {
    double NoL;
    double curvaturePerMm;
};

// Random points over the whole table: NoL uniform; curvature half uniform on [0, max], half
// log-uniform on [max / 200, max] (the face range).
std::vector<Point> randomPoints(int count, double curvatureMax, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<Point> points;
    for (int i = 0; i < count; ++i) {
        const double NoL = -1.0 + 2.0 * unit(rng);
        const double c = i % 2 == 0 ? curvatureMax * unit(rng) : curvatureMax * std::pow(200.0, -unit(rng));
        points.push_back({NoL, c});
    }
    // Also the hard places: the terminator at tiny and large curvatures.
    for (double c : {curvatureMax * 1e-4, curvatureMax * 3e-3, curvatureMax * 0.05, curvatureMax}) {
        for (double NoL : {-0.003, 0.0, 0.002, 0.011}) points.push_back({NoL, c});
    }
    return points;
}

TEST(LutDiffuse, RingIntegralMatchesIndependentIntegration) {
    for (const DiffusionProfile& profile :
         {DiffusionProfile::deonLuebke(), DiffusionProfile::burley({0.8, 0.5, 0.3}, {2.0, 0.9, 0.4})}) {
        double maxError = 0.0;
        for (const Point& p : randomPoints(24, 1.0, 7)) {
            const glm::dvec3 got = skin::ringScatter(profile, p.curvaturePerMm, p.NoL);
            for (int c = 0; c < 3; ++c) {
                const double want = test::referenceRingScatter(profile, c, p.NoL, p.curvaturePerMm);
                maxError = std::max(maxError, std::abs(got[c] - want));
                ASSERT_NEAR(got[c], want, 1e-6) << profile.name() << " channel " << c << " NoL " << p.NoL << " curvature "
                                                << p.curvaturePerMm;
            }
        }
        RecordProperty(profile.kind() == DiffusionProfile::Kind::SumOfGaussians ? "maxIntegratorErrorDeon" : "maxIntegratorErrorBurley",
                       std::to_string(maxError));
        std::printf("ring integral vs reference (%s): max abs error %.3g\n", profile.name().c_str(), maxError);
    }
}

TEST(LutDiffuse, BakedTableMatchesIndependentIntegration) {
    const LutSet& luts = LutSet::loadDefault();
    double maxError = 0.0;
    Point worst{};
    const std::vector<Point> points = randomPoints(64, luts.settings().curvatureMaxPerMm, 11);
    for (const Point& p : points) {
        const glm::vec3 got = luts.lookupDiffuse(static_cast<float>(p.NoL), static_cast<float>(p.curvaturePerMm));
        for (int c = 0; c < 3; ++c) {
            const double want = test::referenceRingScatter(luts.profile(), c, p.NoL, p.curvaturePerMm);
            const double error = std::abs(static_cast<double>(got[c]) - want);
            if (error > maxError) {
                maxError = error;
                worst = p;
            }
        }
    }
    RecordProperty("maxLookupError", std::to_string(maxError));
    std::printf("diffuse LUT lookup vs reference at %zu points: max abs error %.3g (NoL %.4f, curvature %.4f /mm)\n",
                points.size(), maxError, worst.NoL, worst.curvaturePerMm);
    EXPECT_LE(maxError, 1e-3);
}

TEST(LutDiffuse, FlatLimitIsSaturatedNoL) {
    const LutSet& luts = LutSet::loadDefault();
    const LutTable& table = luts.diffuse();
    EXPECT_EQ(table.y.valueAt(0), 0.0);
    for (int ix = 0; ix < table.width(); ++ix) {
        const double want = std::clamp(table.x.valueAt(ix), 0.0, 1.0);
        const glm::vec3 got = table.texel(ix, 0);
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
    // The physical flat limit, r -> infinity, of the integrator itself.
    for (double n : {-0.5, -0.01, 0.0, 0.01, 0.3, 1.0}) {
        const glm::dvec3 d = skin::ringScatter(luts.profile(), 1e-6, n);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(d[c], std::clamp(n, 0.0, 1.0), 2e-3);
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
                if (ix > 0) {
                    ASSERT_GE(v[c], table.texel(ix - 1, iy)[c]) << "row " << iy << " column " << ix << " channel " << c;
                }
            }
        }
    }
}

TEST(LutDiffuse, WrapAtTerminatorIsRedGreenBlueOrderedAndGrowsWithCurvature) {
    const LutTable& table = LutSet::loadDefault().diffuse();
    const int zero = table.width() / 2;
    ASSERT_EQ(table.x.valueAt(zero), 0.0);
    float previousRed = -1.0f;
    for (int iy = 0; iy < table.height(); ++iy) {
        const glm::vec3 v = table.texel(zero, iy);
        EXPECT_GE(v.r, v.g) << "curvature " << table.y.valueAt(iy);
        EXPECT_GE(v.g, v.b) << "curvature " << table.y.valueAt(iy);
        EXPECT_GE(v.r, previousRed);
        previousRed = v.r;
    }
    const glm::vec3 highest = table.texel(zero, table.height() - 1);
    EXPECT_GT(highest.r, 0.2f);                // a visible red wrap on a 1 mm radius
    EXPECT_GT(highest.r - highest.b, 0.05f);
}

TEST(LutDiffuse, BurleyProfileBakes) {
    const DiffusionProfile profile = DiffusionProfile::burley({0.8, 0.5, 0.3}, {2.0, 0.9, 0.4});
    const LutSet luts = LutSet::bake(profile, LutBakeSettings::withSize(32));
    double maxError = 0.0;
    for (const Point& p : randomPoints(8, 1.0, 5)) {
        const glm::vec3 got = luts.lookupDiffuse(static_cast<float>(p.NoL), static_cast<float>(p.curvaturePerMm));
        for (int c = 0; c < 3; ++c)
            maxError = std::max(maxError, std::abs(static_cast<double>(got[c]) - test::referenceRingScatter(profile, c, p.NoL, p.curvaturePerMm)));
    }
    // A 32x32 table interpolates coarsely; this checks the bake path, not resolution.
    EXPECT_LE(maxError, 2e-2);
}

}  // namespace
}  // namespace preskin
