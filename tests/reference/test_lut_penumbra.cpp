// Tests of the penumbra LUT P(shadow, filter width): fully lit gives 1 and deep shadow 0 for
// every filter width; values rise monotonically with the shadow value; red reaches furthest into
// the shadow (and stays darkest on the lit side); the filter only places the edge: where it is
// wider than the profile green and blue come out sharper than the filtered shadow, and red
// scatters into its dark side; texels and lookups match an independent computation (test-side
// quantile, and the hard edge seen through a numerically integrated line profile).
#include "reference/test_lut_reference.h"

#include <preskin/LutSet.h>

#include <gtest/gtest.h>

#include <random>

namespace preskin::test {
namespace {

// Phi^-1 by bisection (test-side).
double quantile(double p) {
    double lo = -40.0, hi = 40.0;
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        (0.5 * std::erfc(-mid / std::sqrt(2.0)) < p ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

double phi(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }

// Response of one channel to a hard edge at x (lit for u > 0): the line profile integrated over
// (-inf, x] / albedo, as 1/2 plus or minus its integral between 0 and |x| (P is even), graded
// towards u = 0.
double hardEdge(const DiffusionProfile& p, int c, double x) {
    if (x == 0.0) return 0.5;
    const double half = test::integrateGradedTowardsStart([&](double u) { return test::referenceLineProfile(p, c, u); },
                                                          0.0, std::abs(x), 1e-12) /
        p.albedo()[c];
    return x > 0.0 ? 0.5 + half : 0.5 - half;
}

// The documented model: the edge at x = sigma Phi^-1(s), its hard-edge response renormalised to
// |x| <= 3 sigma.
double referencePenumbra(const DiffusionProfile& p, int c, double shadow, double sigmaMm) {
    const double q = quantile(shadow);
    if (q <= -3.0) return 0.0;
    if (q >= 3.0) return 1.0;
    const double lo = hardEdge(p, c, -3.0 * sigmaMm);
    const double hi = hardEdge(p, c, 3.0 * sigmaMm);
    return (hardEdge(p, c, sigmaMm * q) - lo) / (hi - lo);
}

TEST(LutPenumbra, LitIsOneAndDeepShadowIsZero) {
    const LutSet& luts = LutSet::loadDefault();
    const LutTable& table = luts.penumbra();
    for (int iy = 0; iy < table.height(); ++iy) {
        EXPECT_EQ(table.texel(0, iy), glm::vec3(0.0f)) << "row " << iy;
        EXPECT_EQ(table.texel(table.width() - 1, iy), glm::vec3(1.0f)) << "row " << iy;
    }
    for (float sigma : {0.0f, 0.1f, 1.0f, 5.0f, 50.0f, 1e6f}) {
        EXPECT_EQ(luts.lookupPenumbra(0.0f, sigma), glm::vec3(0.0f));
        EXPECT_EQ(luts.lookupPenumbra(1.0f, sigma), glm::vec3(1.0f));
        // Deep shadow far from the edge: the filter reads 0 there.
        EXPECT_EQ(luts.lookupPenumbra(-0.5f, sigma), glm::vec3(0.0f));
    }
}

TEST(LutPenumbra, MonotoneInShadowAndRedReachesFurthest) {
    const LutTable& table = LutSet::loadDefault().penumbra();
    for (int iy = 0; iy < table.height(); ++iy) {
        for (int ix = 1; ix < table.width(); ++ix) {
            const glm::vec3 v = table.texel(ix, iy);
            const glm::vec3 before = table.texel(ix - 1, iy);
            for (int c = 0; c < 3; ++c) ASSERT_GE(v[c], before[c]) << "row " << iy << " column " << ix;
            if (table.x.valueAt(ix) < 0.5) {
                ASSERT_GE(v.r, v.g - 1e-3f) << "row " << iy << " column " << ix;
                ASSERT_GE(v.g, v.b - 1e-3f) << "row " << iy << " column " << ix;
            } else {
                ASSERT_LE(v.r, v.g + 1e-3f) << "row " << iy << " column " << ix;
                ASSERT_LE(v.g, v.b + 1e-3f) << "row " << iy << " column " << ix;
            }
        }
    }
}

TEST(LutPenumbra, GreenAndBlueSharpenAWideFilterAndRedReachesIntoTheDark) {
    const LutSet& luts = LutSet::loadDefault();
    const float reference = static_cast<float>(luts.penumbraReferenceWidthMm());
    // The plain shadow renormalised to the same window is what a profile as wide as the filter
    // would soften to; a filter three times the widest channel is wider than green's and blue's
    // profiles, so they see the edge's true place: less light one filter width into the shadow,
    // more one filter width out.
    const double phi3 = phi(-3.0);
    const double plain = (phi(-1.0) - phi3) / (1.0 - 2.0 * phi3);
    const glm::vec3 dark = luts.lookupPenumbra(static_cast<float>(phi(-1.0)), 3.0f * reference);
    const glm::vec3 lit = luts.lookupPenumbra(static_cast<float>(phi(1.0)), 3.0f * reference);
    for (int c = 1; c < 3; ++c) {
        EXPECT_LT(dark[c], 0.5 * plain) << "channel " << c;
        EXPECT_GT(lit[c], 1.0 - 0.5 * plain) << "channel " << c;
    }
    // A filter half as wide as the profile: two filter widths into the shadow red still receives
    // clearly more light than the shadow lets through, and more than blue.
    const float sigma = 0.5f * reference;
    const glm::vec3 v = luts.lookupPenumbra(static_cast<float>(phi(-2.0)), sigma);
    const double plain2 = (phi(-2.0) - phi3) / (1.0 - 2.0 * phi3);
    EXPECT_GT(v.r, 1.5 * plain2);
    EXPECT_GT(v.r, v.b + 0.02f);
}

TEST(LutPenumbra, MatchesIndependentComputation) {
    const LutSet& luts = LutSet::loadDefault();
    const LutTable& table = luts.penumbra();
    const double reference = luts.penumbraReferenceWidthMm();
    double maxTexelError = 0.0;
    for (int iy : {1, 40, 128, 200, 254}) {
        const double sigma = table.y.valueAt(iy) * reference;
        for (int ix = 0; ix < table.width(); ix += 5) {
            const glm::vec3 got = table.texel(ix, iy);
            for (int c = 0; c < 3; ++c) {
                const double want = referencePenumbra(luts.profile(), c, table.x.valueAt(ix), sigma);
                maxTexelError = std::max(maxTexelError, std::abs(static_cast<double>(got[c]) - want));
            }
        }
    }
    EXPECT_LE(maxTexelError, 5e-4);  // half rounding

    std::mt19937 rng(9);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    double maxLookupError = 0.0;
    for (int i = 0; i < 60; ++i) {
        const double shadow = unit(rng);
        const double sigma = reference * std::pow(10.0, -1.0 + 2.0 * unit(rng));  // 0.1 .. 10 profile widths
        const glm::vec3 got = luts.lookupPenumbra(static_cast<float>(shadow), static_cast<float>(sigma));
        for (int c = 0; c < 3; ++c)
            maxLookupError =
                std::max(maxLookupError,
                         std::abs(static_cast<double>(got[c]) - referencePenumbra(luts.profile(), c, shadow, sigma)));
    }
    std::printf("penumbra: max texel error %.3g, max lookup error %.3g\n", maxTexelError, maxLookupError);
    EXPECT_LE(maxLookupError, 3e-3);
}

TEST(LutPenumbra, BurleyEdgeResponseBakes) {
    const DiffusionProfile profile = DiffusionProfile::burley({0.8, 0.5, 0.3}, {2.0, 0.9, 0.4});
    LutBakeSettings settings = LutBakeSettings::withSize(16);
    settings.penumbraShadowSize = 64;
    const LutSet luts = LutSet::bake(profile, settings);
    const LutTable& table = luts.penumbra();
    for (int iy : {3, 8}) {
        const double sigma = table.y.valueAt(iy) * luts.penumbraReferenceWidthMm();
        for (int ix = 0; ix < table.width(); ix += 7) {
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(table.texel(ix, iy)[c], referencePenumbra(profile, c, table.x.valueAt(ix), sigma), 5e-4);
        }
    }
}

}  // namespace
}  // namespace preskin::test
