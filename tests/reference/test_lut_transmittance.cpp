// Tests of the transmittance LUT T(thickness): T(0) = 1, lookups match the Gaussian-sum closed
// form (written here) over the whole range, T decreases with thickness, red passes the most,
// and the range ends where every channel is below 1e-4.
#include <preskin/LutSet.h>

#include <gtest/gtest.h>

#include <random>

namespace preskin::test {
namespace {

// sum_i w_i exp(-d^2 / 2 v_i) / albedo: the plane integral of d'Eon & Luebke's profile.
glm::dvec3 closedForm(const DiffusionProfile& p, double d) {
    glm::dvec3 sum(0.0);
    for (const GaussianTerm& t : p.gaussians()) sum += t.weight * std::exp(-d * d / (2.0 * t.varianceMm2));
    return sum / p.albedo();
}

TEST(LutTransmittance, StartsAtOneAndEndsBelowTheFloor) {
    const LutSet& luts = LutSet::loadDefault();
    EXPECT_EQ(luts.lookupTransmittance(0.0f), glm::vec3(1.0f));
    EXPECT_EQ(luts.lookupTransmittance(-1.0f), glm::vec3(1.0f));
    const glm::vec3 end = luts.transmittance().texel(luts.transmittance().width() - 1, 0);
    for (int c = 0; c < 3; ++c) EXPECT_LE(end[c], 1e-4f);
    EXPECT_GT(luts.transmittanceMaxMm(), 5.0);  // red's widest Gaussian (v = 7.41 mm^2) reaches far
    EXPECT_LT(luts.transmittanceMaxMm(), 20.0);
}

TEST(LutTransmittance, MatchesClosedForm) {
    const LutSet& luts = LutSet::loadDefault();
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    double maxError = 0.0;
    for (int i = 0; i < 400; ++i) {
        // Half uniform over the range, half concentrated near 0 where the narrow Gaussians fall.
        const double d = luts.transmittanceMaxMm() * (i % 2 == 0 ? unit(rng) : std::pow(unit(rng), 4.0));
        const glm::vec3 got = luts.lookupTransmittance(static_cast<float>(d));
        const glm::dvec3 want = closedForm(luts.profile(), d);
        for (int c = 0; c < 3; ++c) maxError = std::max(maxError, std::abs(static_cast<double>(got[c]) - want[c]));
    }
    std::printf("transmittance lookup: max abs error %.3g\n", maxError);
    EXPECT_LE(maxError, 1e-3);
}

TEST(LutTransmittance, DecreasesWithThicknessRedMost) {
    const LutTable& table = LutSet::loadDefault().transmittance();
    for (int ix = 1; ix < table.width(); ++ix) {
        const glm::vec3 v = table.texel(ix, 0);
        for (int c = 0; c < 3; ++c) ASSERT_LE(v[c], table.texel(ix - 1, 0)[c]);
        ASSERT_GE(v.r, v.g);
        ASSERT_GE(v.g + 1e-4f, v.b);
    }
}

}  // namespace
}  // namespace preskin::test
