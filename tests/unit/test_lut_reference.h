// Independent reference computations for the profile and LUT tests: adaptive Simpson quadrature
// (written here, not the library's Gauss-Legendre), line profiles from test-side closed forms
// (std::cyl_bessel_k for Burley, not the library's Abramowitz-Stegun K0), and Penner's ring
// integral evaluated directly on [-pi, pi] with the clamped cosine (no lit-arc decomposition).
// Limits: slow (thousands of evaluations per value); for tests only.
#pragma once

#include <preskin/DiffusionProfile.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

namespace preskin::test {

inline constexpr double kPi = std::numbers::pi;

// Adaptive Simpson with Richardson correction; absolute tolerance `tol` over [a, b].
inline double adaptiveSimpson(const std::function<double(double)>& f, double a, double b, double tol, int minDepth = 4,
                              int maxDepth = 48) {
    struct Rec {
        static double run(const std::function<double(double)>& g, double a0, double b0, double fa, double fm, double fb,
                          double whole, double eps, int depth, int minD) {
            const double m = 0.5 * (a0 + b0);
            const double lm = 0.5 * (a0 + m);
            const double rm = 0.5 * (m + b0);
            const double flm = g(lm);
            const double frm = g(rm);
            const double left = (m - a0) / 6.0 * (fa + 4.0 * flm + fm);
            const double right = (b0 - m) / 6.0 * (fm + 4.0 * frm + fb);
            const double delta = left + right - whole;
            if (depth <= 0 || (minD <= 0 && std::abs(delta) <= 15.0 * eps)) return left + right + delta / 15.0;
            return run(g, a0, m, fa, flm, fm, left, 0.5 * eps, depth - 1, minD - 1) +
                   run(g, m, b0, fm, frm, fb, right, 0.5 * eps, depth - 1, minD - 1);
        }
    };
    const double fa = f(a);
    const double fb = f(b);
    const double fm = f(0.5 * (a + b));
    const double whole = (b - a) / 6.0 * (fa + 4.0 * fm + fb);
    return Rec::run(f, a, b, fa, fm, fb, whole, tol, maxDepth, minDepth);
}

// Integral over [a, b] split at geometrically spaced points towards a (so peaks and integrable
// singularities at a, at any scale down to 2^-60 of the interval, are found).
inline double integrateGradedTowardsStart(const std::function<double(double)>& f, double a, double b, double tol) {
    double sum = 0.0;
    double hi = b;
    for (int k = 0; k < 60; ++k) {
        const double lo = a + 0.5 * (hi - a);
        sum += adaptiveSimpson(f, lo, hi, tol / 64.0);
        hi = lo;
    }
    return sum;
}

// Line profile P(u) of one channel, from the closed forms (test-side code).
inline double referenceLineProfile(const DiffusionProfile& profile, int channel, double u) {
    u = std::abs(u);
    if (profile.kind() == DiffusionProfile::Kind::SumOfGaussians) {
        double sum = 0.0;
        for (const GaussianTerm& t : profile.gaussians())
            sum += t.weight[channel] * std::exp(-u * u / (2.0 * t.varianceMm2)) / std::sqrt(2.0 * kPi * t.varianceMm2);
        return sum;
    }
    const double a = profile.albedo()[channel];
    const double l = profile.meanFreePathMm()[channel];
    const double s = 1.85 - a + 7.0 * std::pow(std::abs(a - 0.8), 3.0);
    const double d = l / s;
    if (u == 0.0) return std::numeric_limits<double>::infinity();
    return a / (4.0 * kPi * d) * (std::cyl_bessel_k(0.0, u / d) + std::cyl_bessel_k(0.0, u / (3.0 * d)));
}

// Penner's D(theta, r) for one channel, integrating cos(theta + x)+ K(x) and K(x) over [-pi, pi]
// directly; the substitution x = t^2 on each side removes Burley's log singularity at x = 0,
// and the lit-arc ends (kinks of the integrand) are split points.
inline double referenceRingScatter(const DiffusionProfile& profile, int channel, double NoL, double curvaturePerMm) {
    if (curvaturePerMm <= 0.0) return std::clamp(NoL, 0.0, 1.0);
    const double r = 1.0 / curvaturePerMm;
    const double theta = std::acos(std::clamp(NoL, -1.0, 1.0));
    auto kernel = [&](double x) { return referenceLineProfile(profile, channel, 2.0 * r * std::sin(0.5 * std::abs(x))); };
    double numerator = 0.0;
    double denominator = 0.0;
    for (int side = -1; side <= 1; side += 2) {
        // Kinks where cos(theta + x) changes sign, as t = sqrt(|x|) on this side.
        std::vector<double> cuts{0.0, std::sqrt(kPi)};
        for (double k : {kPi / 2 - theta, -kPi / 2 - theta, 3 * kPi / 2 - theta, -3 * kPi / 2 - theta}) {
            if (k * side > 0.0 && std::abs(k) < kPi) cuts.push_back(std::sqrt(std::abs(k)));
        }
        std::sort(cuts.begin(), cuts.end());
        auto lit = [&](double t) {
            if (t == 0.0) return 0.0;
            const double x = side * t * t;
            return 2.0 * t * std::max(std::cos(theta + x), 0.0) * kernel(x);
        };
        auto all = [&](double t) {
            if (t == 0.0) return 0.0;
            return 2.0 * t * kernel(side * t * t);
        };
        for (size_t i = 0; i + 1 < cuts.size(); ++i) {
            if (cuts[i + 1] <= cuts[i]) continue;
            numerator += integrateGradedTowardsStart(lit, cuts[i], cuts[i + 1], 1e-11);
            denominator += integrateGradedTowardsStart(all, cuts[i], cuts[i + 1], 1e-11);
        }
    }
    return numerator / denominator;
}

}  // namespace preskin::test
