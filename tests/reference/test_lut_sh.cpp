// Tests of the SH transfer table A_l(curvature), l = 0, 1, 2: flat skin gives exactly
// Lambert's (pi, 2 pi / 3, pi / 4); curved skin matches an adaptive integration over cos(theta)
// of the (separately verified, test_lut_diffuse.cpp) response on the sphere, which is what the
// library's Funk-Hecke form must equal; higher bands are attenuated, red most.
#include "reference/test_lut_reference.h"

#include "skin/SphereScatter.h"

#include <preskin/LutSet.h>

#include <gtest/gtest.h>

namespace preskin::test {
namespace {

constexpr double kLambert[3] = {test::kPi, 2.0 * test::kPi / 3.0, test::kPi / 4.0};

TEST(LutSh, ZeroCurvatureIsLambert) {
    const LutSet& luts = LutSet::loadDefault();
    const std::array<glm::vec3, 3> a = luts.lookupShTransfer(0.0f);
    for (int l = 0; l < 3; ++l) {
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[static_cast<size_t>(l)][c], kLambert[l], 1e-3) << "band " << l;
        EXPECT_EQ(luts.shTransfer().texel(0, l), glm::vec3(1.0f));  // stored relative to Lambert
    }
    const std::array<glm::dvec3, 3> exact = skin::shTransfer(luts.profile(), 0.0);
    const std::array<glm::dvec3, 3> nearlyFlat = skin::shTransfer(luts.profile(), 1e-6);
    for (int l = 0; l < 3; ++l) {
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(exact[static_cast<size_t>(l)][c], kLambert[l], 1e-12);
            EXPECT_NEAR(nearlyFlat[static_cast<size_t>(l)][c], kLambert[l], 1e-3);
        }
    }
}

TEST(LutSh, MatchesAdaptiveIntegrationOfTheSphereResponse) {
    const LutSet& luts = LutSet::loadDefault();
    for (double curvature : {0.02, 0.2, 0.7}) {
        const std::array<glm::dvec3, 3> got = skin::shTransfer(luts.profile(), curvature);
        const std::array<glm::vec3, 3> looked = luts.lookupShTransfer(static_cast<float>(curvature));
        for (int l = 0; l < 3; ++l) {
            for (int c = 0; c < 3; ++c) {
                auto integrand = [&](double mu) {
                    const double legendre = l == 0 ? 1.0 : (l == 1 ? mu : 0.5 * (3.0 * mu * mu - 1.0));
                    return skin::sphereScatter(luts.profile(), curvature, luts.localPatchMm(), mu)[c] * legendre;
                };
                const double want = 2.0 * test::kPi *
                    (test::adaptiveSimpson(integrand, -1.0, 0.0, 1e-9, 6) +
                     test::adaptiveSimpson(integrand, 0.0, 1.0, 1e-9, 6));
                EXPECT_NEAR(got[static_cast<size_t>(l)][c], want, 1e-5)
                    << "curvature " << curvature << " band " << l << " channel " << c;
                EXPECT_NEAR(looked[static_cast<size_t>(l)][c], want, 2e-3)
                    << "curvature " << curvature << " band " << l;
            }
        }
    }
}

TEST(LutSh, HigherBandsAreAttenuatedRedMost) {
    const LutTable& table = LutSet::loadDefault().shTransfer();
    for (int ix = 0; ix < table.width(); ++ix) {
        for (int l = 1; l < 3; ++l) {
            const glm::vec3 ratio = table.texel(ix, l);
            for (int c = 0; c < 3; ++c) {
                EXPECT_GT(ratio[c], 0.0f);
                EXPECT_LE(ratio[c], 1.0f + 1e-3f) << "band " << l << " curvature " << table.x.valueAt(ix);
            }
            EXPECT_LE(ratio.r, ratio.b + 1e-3f) << "band " << l << " curvature " << table.x.valueAt(ix);
        }
    }
    const glm::vec3 band2AtMax = table.texel(table.width() - 1, 2);
    EXPECT_LT(band2AtMax.r, 0.9f);  // a 1 mm radius blurs red clearly
}

}  // namespace
}  // namespace preskin::test
