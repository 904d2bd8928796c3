// Penner's ring integral and the SH transfer built from it (method and sources: RingScatter.h).
#include "skin/RingScatter.h"

#include "skin/Quadrature.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace preskin::skin {
namespace {

constexpr double kPi = std::numbers::pi;

struct Cumulative {
    std::vector<double> x;
    std::vector<glm::dvec3> cosK;  // int_0^x cos(t) K(t) dt
    std::vector<glm::dvec3> sinK;  // int_0^x sin(t) K(t) dt
    std::vector<glm::dvec3> K;     // int_0^x K(t) dt
    size_t index(double at) const { return static_cast<size_t>(std::lower_bound(x.begin(), x.end(), at) - x.begin()); }
};

}  // namespace

void ringScatter(const DiffusionProfile& profile, double curvaturePerMm, std::span<const double> NoL,
                 std::span<glm::dvec3> out) {
    if (!(curvaturePerMm > 0.0)) {
        for (size_t i = 0; i < NoL.size(); ++i) out[i] = glm::dvec3(std::clamp(NoL[i], 0.0, 1.0));
        return;
    }
    const double radiusMm = 1.0 / curvaturePerMm;

    Cumulative cumulative;
    std::vector<double>& breaks = cumulative.x;
    breaks.reserve(2 * NoL.size() + 200);
    breaks.push_back(0.0);
    breaks.push_back(kPi);
    for (double nol : NoL) {
        const double a = std::abs(std::asin(std::clamp(nol, -1.0, 1.0)));
        breaks.push_back(a);
        breaks.push_back(kPi - a);
    }
    const double scale = std::min(profile.narrowestScaleMm() * curvaturePerMm, kPi);
    for (double x = 1e-7 * scale; x < kPi; x *= 1.25) breaks.push_back(x);
    for (int k = 1; k < 32; ++k) breaks.push_back(k * kPi / 32.0);
    std::sort(breaks.begin(), breaks.end());
    breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());

    const size_t count = breaks.size();
    cumulative.cosK.assign(count, glm::dvec3(0.0));
    cumulative.sinK.assign(count, glm::dvec3(0.0));
    cumulative.K.assign(count, glm::dvec3(0.0));
    const GaussLegendreRule& rule = gaussLegendre(8);
    for (size_t k = 0; k + 1 < count; ++k) {
        const double a = breaks[k];
        const double b = breaks[k + 1];
        const double half = 0.5 * (b - a);
        const double mid = 0.5 * (a + b);
        glm::dvec3 sumCos(0.0), sumSin(0.0), sumK(0.0);
        for (size_t i = 0; i < rule.nodes.size(); ++i) {
            const double x = mid + half * rule.nodes[i];
            const double s = std::sin(0.5 * x);
            const double c = std::cos(0.5 * x);
            const glm::dvec3 kernel = rule.weights[i] * profile.lineProfile(2.0 * radiusMm * s);
            sumK += kernel;
            sumCos += kernel * (1.0 - 2.0 * s * s);
            sumSin += kernel * (2.0 * s * c);
        }
        cumulative.K[k + 1] = cumulative.K[k] + half * sumK;
        cumulative.cosK[k + 1] = cumulative.cosK[k] + half * sumCos;
        cumulative.sinK[k + 1] = cumulative.sinK[k] + half * sumSin;
    }

    const size_t end = count - 1;  // x = pi
    const glm::dvec3 total = 2.0 * cumulative.K[end];
    for (size_t i = 0; i < NoL.size(); ++i) {
        const double nol = std::clamp(NoL[i], -1.0, 1.0);
        const double a = std::abs(std::asin(nol));
        const size_t ia = cumulative.index(a);
        const size_t ib = cumulative.index(kPi - a);
        const double sinTheta = std::sqrt(std::max(0.0, 1.0 - nol * nol));
        // Lit arc, theta = acos(NoL): NoL >= 0: [-(pi - a), a]; NoL < 0: [-pi, -a] and [pi - a, pi].
        const glm::dvec3 cosPart = nol >= 0.0 ? cumulative.cosK[ia] + cumulative.cosK[ib]
                                              : 2.0 * cumulative.cosK[end] - cumulative.cosK[ia] - cumulative.cosK[ib];
        const glm::dvec3 sinPart = cumulative.sinK[ia] - cumulative.sinK[ib];
        out[i] = glm::max((nol * cosPart - sinTheta * sinPart) / total, glm::dvec3(0.0));
    }
}

glm::dvec3 ringScatter(const DiffusionProfile& profile, double curvaturePerMm, double NoL) {
    glm::dvec3 result;
    ringScatter(profile, curvaturePerMm, std::span<const double>(&NoL, 1), std::span<glm::dvec3>(&result, 1));
    return result;
}

std::array<glm::dvec3, 3> shTransfer(const DiffusionProfile& profile, double curvaturePerMm) {
    static constexpr std::array<double, 6> kBreaks{0.0, 1.0 / 256.0, 1.0 / 64.0, 1.0 / 16.0, 0.25, 1.0};
    const GaussLegendreRule& rule = gaussLegendre(16);
    std::vector<double> mu;
    std::vector<double> weight;
    for (int side = -1; side <= 1; side += 2) {
        for (size_t k = 0; k + 1 < kBreaks.size(); ++k) {
            const double half = 0.5 * (kBreaks[k + 1] - kBreaks[k]);
            const double mid = 0.5 * (kBreaks[k + 1] + kBreaks[k]);
            for (size_t i = 0; i < rule.nodes.size(); ++i) {
                mu.push_back(side * (mid + half * rule.nodes[i]));
                weight.push_back(half * rule.weights[i]);
            }
        }
    }
    std::vector<glm::dvec3> d(mu.size());
    ringScatter(profile, curvaturePerMm, mu, d);
    std::array<glm::dvec3, 3> a{glm::dvec3(0.0), glm::dvec3(0.0), glm::dvec3(0.0)};
    for (size_t i = 0; i < mu.size(); ++i) {
        const double m = mu[i];
        const double legendre[3] = {1.0, m, 0.5 * (3.0 * m * m - 1.0)};
        for (int l = 0; l < 3; ++l) a[static_cast<size_t>(l)] += (2.0 * kPi * weight[i] * legendre[l]) * d[i];
    }
    return a;
}

}  // namespace preskin::skin
