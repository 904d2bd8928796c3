// The screen-space baseline's separable kernel (skin/SeparableKernel.h) against the profile it
// comes from: normalised per channel, symmetric, and a straight edge blurred by it (horizontal
// then vertical: the vertical pass leaves a vertical edge as it is) equal to the profile's exact
// edge response (DiffusionProfile::edgeResponse, integrated independently here by quadrature of
// the line profile) at the midpoints between taps, and close between them.
#include "skin/SeparableKernel.h"

#include <preskin/DiffusionProfile.h>
#include <preskin/Error.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace preskin {
namespace {

// int P(t) dt over (-inf, x] / albedo by the midpoint rule over [-60 mm, x] (Burley's P has a
// logarithmic singularity at 0, which the rule meets to about 5e-4).
glm::dvec3 edgeByQuadrature(const DiffusionProfile& p, double x) {
    const double lo = -60.0;
    const int n = 120000;
    const double h = (x - lo) / n;
    glm::dvec3 sum(0.0);
    for (int i = 0; i < n; ++i) sum += p.lineProfile(lo + (i + 0.5) * h) * h;
    return sum / p.albedo();
}

// The blurred step (lit where x > 0) at x: the weights of the taps that land on the lit side.
glm::dvec3 blurredStep(const std::vector<SeparableTap>& kernel, double x) {
    glm::dvec3 lit(0.0);
    for (const SeparableTap& t : kernel)
        if (x + t.offsetMm > 0.0) lit += t.weight;
    return lit;
}

TEST(SeparableKernel, NormalisedSymmetricAndTheEdgeResponseAtTapBoundaries) {
    for (const DiffusionProfile& profile :
         {DiffusionProfile::deonLuebke(),
          DiffusionProfile::burley(glm::dvec3(0.8, 0.5, 0.3), glm::dvec3(3.0, 1.5, 0.8))}) {
        for (uint32_t taps : {7u, 17u, 25u}) {
            const std::vector<SeparableTap> kernel = separableKernel(profile, taps);
            ASSERT_EQ(kernel.size(), taps);
            glm::dvec3 sum(0.0);
            for (size_t i = 0; i < taps; ++i) {
                sum += kernel[i].weight;
                EXPECT_NEAR(kernel[i].offsetMm, -kernel[taps - 1 - i].offsetMm, 1e-12);
                for (int c = 0; c < 3; ++c) {
                    EXPECT_NEAR(kernel[i].weight[c], kernel[taps - 1 - i].weight[c], 1e-9);
                    EXPECT_GE(kernel[i].weight[c], 0.0);
                }
            }
            EXPECT_EQ(kernel[taps / 2].offsetMm, 0.0);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c], 1.0, 1e-12) << profile.name() << " " << taps;
            // At x, the taps on the lit side are those with offset > -x: between boundaries the
            // blurred step is constant, equal to the edge response at the boundary b = -(midpoint).
            for (size_t i = 0; i + 1 < taps; ++i) {
                const double b = 0.5 * (kernel[i].offsetMm + kernel[i + 1].offsetMm);
                const glm::dvec3 got = blurredStep(kernel, -b + 1e-9);
                const glm::dvec3 want = edgeByQuadrature(profile, -b);
                const double tolerance = profile.kind() == DiffusionProfile::Kind::SumOfGaussians ? 2e-4 : 1e-3;
                for (int c = 0; c < 3; ++c)
                    EXPECT_NEAR(got[c], want[c], tolerance) << profile.name() << " boundary " << i;
            }
        }
    }
}

TEST(SeparableKernel, ReachHoldsAllButTheTail) {
    const DiffusionProfile deon = DiffusionProfile::deonLuebke();
    const double reach = separableReachMm(deon, 0.01);
    const glm::dvec3 beyond = deon.edgeResponse(-reach);
    EXPECT_NEAR(std::max({beyond.r, beyond.g, beyond.b}), 0.005, 1e-6);
    std::printf("[ kernel   ] d'Eon's reach %.2f mm; 17 taps:", reach);
    for (const SeparableTap& t : separableKernel(deon, 17))
        std::printf(" %.2f (%.3f %.3f %.3f)", t.offsetMm, t.weight.r, t.weight.g, t.weight.b);
    std::printf("\n");
}

TEST(SeparableKernel, RefusesEvenAndOutOfRangeTapCounts) {
    const DiffusionProfile deon = DiffusionProfile::deonLuebke();
    for (uint32_t taps : {0u, 1u, 2u, 16u, 65u}) EXPECT_THROW(separableKernel(deon, taps), Error) << taps;
}

}  // namespace
}  // namespace preskin
