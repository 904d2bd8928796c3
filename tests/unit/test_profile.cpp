// Tests of DiffusionProfile (d'Eon & Luebke 2007 sums of Gaussians, Christensen & Burley 2015
// normalized diffusion): normalisation to the albedo, and the line profile, edge response,
// transmittance and RMS width against independent adaptive integrals of R(r); the library's
// Bessel K0 and normal quantile against the standard library.
#include "reference/test_lut_reference.h"

#include "skin/SpecialFunctions.h"

#include <preskin/DiffusionProfile.h>
#include <preskin/Error.h>

#include <gtest/gtest.h>

namespace preskin::test {
namespace {

using test::kPi;

std::vector<DiffusionProfile> profiles() {
    return {
        DiffusionProfile::deonLuebke(),
        DiffusionProfile::fromJsonFile(PRESKIN_SOURCE_DIR "/tests/data/profiles/good_three_gaussians.json"),
        DiffusionProfile::burley({0.8, 0.5, 0.3}, {2.0, 0.9, 0.4}),
        DiffusionProfile::burley({1.0, 0.8, 0.05}, {0.5, 3.0, 0.1}),
    };
}

// A length beyond which every channel's profile is negligible (< 1e-30 of its peak).
double outerRadiusMm(const DiffusionProfile& p) { return 40.0 * (p.maxWidthMm() + 1.0); }

// int 2 pi r g(r) dr over [0, inf) for one channel, graded towards 0.
double radialIntegral(const DiffusionProfile& p, const std::function<double(double)>& g) {
    return test::integrateGradedTowardsStart(g, 0.0, outerRadiusMm(p), 1e-12);
}

TEST(Profile, DeonLuebkeIsNormalisedToOne) {
    const DiffusionProfile p = DiffusionProfile::deonLuebke();
    EXPECT_EQ(p.kind(), DiffusionProfile::Kind::SumOfGaussians);
    ASSERT_EQ(p.gaussians().size(), 6u);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(p.albedo()[c], 1.0, 1e-12);
}

TEST(Profile, EveryProfileIntegratesToItsAlbedo) {
    for (const DiffusionProfile& p : profiles()) {
        for (int c = 0; c < 3; ++c) {
            const double integral =
                radialIntegral(p, [&](double r) { return r == 0.0 ? 0.0 : 2.0 * kPi * r * p.R(r)[c]; });
            EXPECT_NEAR(integral, p.albedo()[c], 1e-4) << p.name() << " channel " << c;
            EXPECT_NEAR(integral, p.albedo()[c], 1e-8) << p.name() << " channel " << c;  // far tighter in fact
        }
    }
}

TEST(Profile, BurleyAlbedoAndDistanceFollowTheSearchlightFit) {
    const DiffusionProfile p = DiffusionProfile::burley({0.8, 0.5, 0.3}, {2.0, 0.9, 0.4});
    EXPECT_EQ(p.albedo(), glm::dvec3(0.8, 0.5, 0.3));
    // s(0.8) = 1.85 - 0.8 = 1.05; s(0.5) = 1.35 + 7 * 0.027 = 1.539.
    EXPECT_NEAR(p.scatteringDistanceMm().x, 2.0 / 1.05, 1e-12);
    EXPECT_NEAR(p.scatteringDistanceMm().y, 0.9 / 1.539, 1e-12);
}

TEST(Profile, LineProfileIsTheLineIntegralOfR) {
    for (const DiffusionProfile& p : profiles()) {
        for (double u : {0.003, 0.05, 0.4, 1.3, 5.0}) {
            const glm::dvec3 got = p.lineProfile(u);
            for (int c = 0; c < 3; ++c) {
                const double want = 2.0 *
                    test::integrateGradedTowardsStart([&](double y) { return p.R(std::hypot(u, y))[c]; }, 0.0,
                                                      outerRadiusMm(p), 1e-13);
                EXPECT_NEAR(got[c], want, 1e-6 * std::max(want, 1e-3)) << p.name() << " u " << u << " channel " << c;
                EXPECT_NEAR(got[c], test::referenceLineProfile(p, c, u), 5e-7 * want + 1e-12);
            }
        }
    }
}

TEST(Profile, EdgeResponseIsTheCumulativeLineProfile) {
    for (const DiffusionProfile& p : profiles()) {
        EXPECT_NEAR(p.edgeResponse(0.0).x, 0.5, 1e-12);
        for (double x : {-4.0, -0.6, -0.02, 0.01, 0.3, 2.5}) {
            const glm::dvec3 got = p.edgeResponse(x);
            for (int c = 0; c < 3; ++c) {
                // Mass of the line profile beyond |x|, from the test's own closed form.
                const double beyond =
                    test::integrateGradedTowardsStart([&](double t) { return test::referenceLineProfile(p, c, t); },
                                                      std::abs(x), outerRadiusMm(p), 1e-13);
                const double want = (x < 0.0 ? beyond : p.albedo()[c] - beyond) / p.albedo()[c];
                EXPECT_NEAR(got[c], want, 2e-7) << p.name() << " x " << x << " channel " << c;
            }
        }
    }
}

TEST(Profile, TransmittanceIsThePlaneIntegralOfR) {
    for (const DiffusionProfile& p : profiles()) {
        EXPECT_NEAR(p.transmittance(0.0).x, 1.0, 1e-12);
        for (double d : {0.05, 0.5, 2.0, 6.0}) {
            const glm::dvec3 got = p.transmittance(d);
            for (int c = 0; c < 3; ++c) {
                const double want =
                    radialIntegral(p, [&](double r) { return 2.0 * kPi * r * p.R(std::hypot(r, d))[c]; }) /
                    p.albedo()[c];
                EXPECT_NEAR(got[c], want, 1e-7) << p.name() << " d " << d << " channel " << c;
            }
        }
    }
    // Gaussians: sum_i w_i exp(-d^2 / 2 v_i) (Jimenez et al.'s form with the variances doubled).
    const DiffusionProfile deon = DiffusionProfile::deonLuebke();
    double red = 0.0;
    for (const GaussianTerm& t : deon.gaussians()) red += t.weight.r * std::exp(-1.0 / (2.0 * t.varianceMm2));
    EXPECT_NEAR(deon.transmittance(1.0).r, red, 1e-12);
}

TEST(Profile, WidthIsTheRmsRadius) {
    for (const DiffusionProfile& p : profiles()) {
        for (int c = 0; c < 3; ++c) {
            const double second =
                radialIntegral(p, [&](double r) { return r == 0.0 ? 0.0 : 2.0 * kPi * r * r * r * p.R(r)[c]; });
            EXPECT_NEAR(p.widthMm()[c], std::sqrt(second / p.albedo()[c]), 1e-6 * p.widthMm()[c]) << p.name();
        }
        EXPECT_EQ(p.maxWidthMm(), std::max({p.widthMm().x, p.widthMm().y, p.widthMm().z}));
    }
    // Skin: red scatters farthest.
    const glm::dvec3 w = DiffusionProfile::deonLuebke().widthMm();
    EXPECT_GT(w.r, w.g);
    EXPECT_GT(w.g, w.b);
}

TEST(Profile, FactoriesValidate) {
    EXPECT_THROW(DiffusionProfile::burley({0.8, 0.0, 0.3}, {1.0, 1.0, 1.0}), Error);
    EXPECT_THROW(DiffusionProfile::burley({0.8, 0.5, 1.5}, {1.0, 1.0, 1.0}), Error);
    EXPECT_THROW(DiffusionProfile::burley({0.8, 0.5, 0.3}, {1.0, -1.0, 1.0}), Error);
    EXPECT_THROW(DiffusionProfile::burley({0.8, 0.5, 0.3}, {1.0, std::nan(""), 1.0}), Error);
    EXPECT_THROW(DiffusionProfile::sumOfGaussians({}), Error);
    EXPECT_THROW(DiffusionProfile::sumOfGaussians({{std::nan(""), {0.5, 0.5, 0.5}}}), Error);
    EXPECT_THROW(DiffusionProfile::sumOfGaussians({{0.1, {0.5, -0.5, 0.5}}}), Error);
    try {
        DiffusionProfile::burley({0.8, 0.0, 0.3}, {1.0, 1.0, 1.0});
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "burley: albedo[1]: must be in (0, 1], got 0");
    }
}

TEST(SpecialFunctions, BesselK0MatchesStandardLibrary) {
    for (double x = 1e-6; x < 60.0; x *= 1.37) {
        const double want = std::cyl_bessel_k(0.0, x);
        EXPECT_NEAR(skin::besselK0(x), want, 3e-7 * want) << "x " << x;
    }
}

TEST(SpecialFunctions, NormalQuantileInvertsTheCdf) {
    for (double p : {1e-12, 1e-4, 0.00135, 0.1, 0.5, 0.77, 0.999, 1.0 - 1e-10}) {
        EXPECT_NEAR(skin::normalCdf(skin::normalQuantile(p)), p, 1e-14 + 1e-12 * p);
    }
    EXPECT_EQ(skin::normalQuantile(0.5), 0.0);
    EXPECT_TRUE(std::isinf(skin::normalQuantile(0.0)));
}

}  // namespace
}  // namespace preskin::test
