// The diffuse response on a sphere (convex) or a concave patch, and the SH transfer (method and
// sources: SphereScatter.h).
#include "skin/SphereScatter.h"

#include "skin/LutLayout.h"
#include "skin/Quadrature.h"
#include "skin/SpecialFunctions.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

namespace preskin::skin {
namespace {

constexpr double kPi = std::numbers::pi;

// Gauss-Legendre nodes in psi with the kernel weight W(psi) folded into each node's weight, one
// array per quantity (the N.L loop below runs over them in vector registers).
struct KernelNodes {
    std::vector<double> psi;  // ascending
    std::vector<double> cosPsi;
    std::vector<double> sinPsi;
    std::vector<double> invSinPsi;
    std::array<std::vector<double>, 3> weight;  // per channel: quadrature weight * a^2 Rn(chord) sin(psi)
    std::array<std::vector<double>, 3> cosSum;  // per channel: sum of weight * cos(psi) over the nodes before i
    glm::dvec3 total{0.0};                      // 2 pi sum(weight): the profile's integral over the surface
};

KernelNodes kernelNodes(const DiffusionProfile& profile, double radiusMm, double psiEnd) {
    const glm::dvec3 invAlbedo = 1.0 / profile.albedo();
    const double uniform = psiEnd / 64.0;
    std::vector<double> breaks{0.0};
    for (double psi = 1e-3 * profile.narrowestScaleMm() / radiusMm; psi < uniform; psi *= 1.5) breaks.push_back(psi);
    for (int j = 1; j <= 64; ++j) breaks.push_back(uniform * j);
    const GaussLegendreRule& rule = gaussLegendre(8);
    KernelNodes nodes;
    for (size_t k = 0; k + 1 < breaks.size(); ++k) {
        const double half = 0.5 * (breaks[k + 1] - breaks[k]), mid = 0.5 * (breaks[k + 1] + breaks[k]);
        for (size_t i = 0; i < rule.nodes.size(); ++i) {
            const double psi = mid + half * rule.nodes[i];
            const double chord = 2.0 * radiusMm * std::sin(0.5 * psi);
            nodes.psi.push_back(psi);
            nodes.cosPsi.push_back(std::cos(psi));
            nodes.sinPsi.push_back(std::sin(psi));
            nodes.invSinPsi.push_back(1.0 / std::sin(psi));
            const glm::dvec3 w = (half * rule.weights[i]) * radiusMm * radiusMm * std::sin(psi) *
                profile.R(std::max(chord, 1e-12)) * invAlbedo;
            for (int c = 0; c < 3; ++c) nodes.weight[size_t(c)].push_back(w[c]);
            nodes.total += 2.0 * kPi * w;
        }
    }
    for (size_t c = 0; c < 3; ++c) {
        std::vector<double>& sum = nodes.cosSum[c];
        sum.assign(nodes.psi.size() + 1, 0.0);
        for (size_t i = 0; i < nodes.psi.size(); ++i) sum[i + 1] = sum[i] + nodes.weight[c][i] * nodes.cosPsi[i];
    }
    return nodes;
}

// int_0^2pi (A + B cos(phi)) [A + B cos(phi) > tau] dphi for B >= 0 (any tau), given the
// limit's cos(phi) = x = (tau - A) / B: with x clamped to [-1, 1], 2 (A acos(x) + B sqrt(1 - x^2))
// is 2 pi A where the whole circle passes (A - B >= tau: x = -1) and 0 where none does (A + B <=
// tau: x = 1). Branch-free.
inline double azimuthal(double A, double B, double x) {
    x = std::clamp(x, -1.0, 1.0);
    return 2.0 * (A * acosPolynomial(x) + B * std::sqrt(1.0 - x * x));
}

// The psi range that matters: the chord out to the profile's reach, and for a concave patch its
// arc radius.
double psiEnd(const DiffusionProfile& profile, double radiusMm) {
    const double reach = profile.reachMm(kTransmittanceFloor);
    return reach >= 2.0 * radiusMm ? kPi : 2.0 * std::asin(reach / (2.0 * radiusMm));
}

}  // namespace

// The bake's hot loop runs in a copy compiled for x86-64-v3 (AVX2, FMA) where the CPU has it, the
// copy chosen when the library loads (GCC function multiversioning); the result is the same to
// rounding.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define PRESKIN_X86_64_V3_CLONE __attribute__((target_clones("arch=x86-64-v3", "default")))
#define PRESKIN_INLINE_LAMBDA __attribute__((always_inline))  // compiled into each copy
#else
#define PRESKIN_X86_64_V3_CLONE
#define PRESKIN_INLINE_LAMBDA
#endif

PRESKIN_X86_64_V3_CLONE
void sphereScatter(const DiffusionProfile& profile, double curvaturePerMm, double patchMm, std::span<const double> NoL,
                   std::span<glm::dvec3> out) {
    if (curvaturePerMm == 0.0 || !std::isfinite(curvaturePerMm)) {
        for (size_t i = 0; i < NoL.size(); ++i) out[i] = glm::dvec3(std::clamp(NoL[i], 0.0, 1.0));
        return;
    }
    const bool concave = curvaturePerMm < 0.0;
    const double radiusMm = 1.0 / std::abs(curvaturePerMm);
    const double cosPatch = std::cos(std::min(patchMm / radiusMm, kPi));
    const KernelNodes nodes = kernelNodes(profile, radiusMm, psiEnd(profile, radiusMm));
    const size_t count = nodes.psi.size();
    // The first node whose psi is not below `psi` (the nodes ascend).
    auto firstFrom = [&](double psi) {
        return size_t(std::lower_bound(nodes.psi.begin(), nodes.psi.end(), psi) - nodes.psi.begin());
    };
    // The patch's edge: cos(psi) - cos(patch) is > 0 before it and <= 0 from it on.
    const size_t patchEnd = size_t(
        std::partition_point(nodes.cosPsi.begin(), nodes.cosPsi.end(), [&](double cp) { return cp - cosPatch > 0.0; }) -
        nodes.cosPsi.begin());
    for (size_t n = 0; n < NoL.size(); ++n) {
        const double c = std::clamp(NoL[n], -1.0, 1.0);
        const double s = std::sqrt(std::max(0.0, 1.0 - c * c));
        const double theta = std::acos(c);
        // sum over [lo, hi) of weight * phi(A, B, tau(gap)), node by node: a vector loop.
        const double invS = 1.0 / std::max(s, 1e-300);
        auto explicitSum = [&](size_t lo, size_t hi, auto&& tauOf) PRESKIN_INLINE_LAMBDA {
            double sr = 0.0, sg = 0.0, sb = 0.0;
            const double* cosPsi = nodes.cosPsi.data();
            const double* sinPsi = nodes.sinPsi.data();
            const double* invSinPsi = nodes.invSinPsi.data();
            const double* wr = nodes.weight[0].data();
            const double* wg = nodes.weight[1].data();
            const double* wb = nodes.weight[2].data();
#pragma omp simd reduction(+ : sr, sg, sb)
            for (size_t i = lo; i < hi; ++i) {
                const double A = c * cosPsi[i];
                const double x = (tauOf(cosPsi[i] - cosPatch) - A) * invS * invSinPsi[i];
                const double phi = azimuthal(A, s * sinPsi[i], x);
                sr += wr[i] * phi;
                sg += wg[i] * phi;
                sb += wb[i] * phi;
            }
            return glm::dvec3(sr, sg, sb);
        };
        // sum over [lo, hi) of weight * Phi(A, B, 0). Phi is 2 pi A (the whole circle faces the
        // light) where cos(theta + psi) >= 0 and 0 where cos(theta - psi) <= 0, so only the nodes
        // of the band between are integrated one by one (widened by a node each side against
        // rounding); the rest is a difference of the prefix sums of weight * cos(psi).
        auto unshadowed = [&](size_t lo, size_t hi) PRESKIN_INLINE_LAMBDA {
            size_t fullLo, fullHi, bandLo, bandHi;
            if (theta <= 0.5 * kPi) {
                // Whole circle for psi <= pi/2 - theta, none from pi/2 + theta on.
                const size_t f = firstFrom(0.5 * kPi - theta);
                fullLo = 0;
                fullHi = bandLo = f > 0 ? f - 1 : 0;
                bandHi = std::min(firstFrom(0.5 * kPi + theta) + 1, count);
            } else {
                // None for psi <= theta - pi/2, whole circle from 3 pi/2 - theta on.
                const size_t z = firstFrom(theta - 0.5 * kPi);
                bandLo = z > 0 ? z - 1 : 0;
                bandHi = fullLo = std::min(firstFrom(1.5 * kPi - theta) + 1, count);
                fullHi = count;
            }
            glm::dvec3 sum =
                explicitSum(std::clamp(bandLo, lo, hi), std::clamp(bandHi, lo, hi), [](double) { return 0.0; });
            fullLo = std::clamp(fullLo, lo, hi);
            fullHi = std::clamp(fullHi, lo, hi);
            for (size_t ch = 0; ch < 3; ++ch)
                sum[int(ch)] += 2.0 * kPi * c * (nodes.cosSum[ch][fullHi] - nodes.cosSum[ch][fullLo]);
            return sum;
        };
        glm::dvec3 sum(0.0);
        if (!concave) {
            sum = unshadowed(0, count);
        } else if (c > 0.0) {
            // Visible where 2 u cos(theta) > cos(psi) - cos(patch), u = n_y . L > 0: a threshold
            // inside the patch, none beyond it.
            const double inv2c = 0.5 / c;
            sum = explicitSum(0, patchEnd, [inv2c](double gap) { return std::max(0.0, gap * inv2c); }) +
                unshadowed(patchEnd, count);
        } else if (c < 0.0) {
            // Only neighbours beyond the patch, below the threshold (cos(patch) - cos(psi)) / 2 |c|.
            const double inv2c = 0.5 / c;
            sum =
                unshadowed(patchEnd, count) - explicitSum(patchEnd, count, [inv2c](double gap) { return gap * inv2c; });
        } else {
            sum = unshadowed(patchEnd, count);
        }
        out[n] = glm::max(sum / nodes.total, glm::dvec3(0.0));
    }
}

glm::dvec3 sphereScatter(const DiffusionProfile& profile, double curvaturePerMm, double patchMm, double NoL) {
    glm::dvec3 result;
    sphereScatter(profile, curvaturePerMm, patchMm, std::span<const double>(&NoL, 1),
                  std::span<glm::dvec3>(&result, 1));
    return result;
}

std::array<glm::dvec3, 3> shTransfer(const DiffusionProfile& profile, double curvaturePerMm) {
    const double k = std::abs(curvaturePerMm);
    std::array<glm::dvec3, 3> a{};
    if (!(k > 0.0) || !std::isfinite(k)) {
        for (size_t l = 0; l < 3; ++l) a[l] = glm::dvec3(kLambertZonal[l]);
        return a;
    }
    const double radiusMm = 1.0 / k;
    const KernelNodes nodes = kernelNodes(profile, radiusMm, psiEnd(profile, radiusMm));
    std::array<glm::dvec3, 3> g{glm::dvec3(0.0), glm::dvec3(0.0), glm::dvec3(0.0)};
    for (size_t i = 0; i < nodes.cosPsi.size(); ++i) {
        const double m = nodes.cosPsi[i];
        const double legendre[3] = {1.0, m, 0.5 * (3.0 * m * m - 1.0)};
        const glm::dvec3 w(nodes.weight[0][i], nodes.weight[1][i], nodes.weight[2][i]);
        for (size_t l = 0; l < 3; ++l) g[l] += w * legendre[l];
    }
    for (size_t l = 0; l < 3; ++l) a[l] = kLambertZonal[l] * g[l] / g[0];
    return a;
}

}  // namespace preskin::skin
