// Special functions the profile integrals need.
//  - besselK0: modified Bessel function of the second kind, order 0, by the polynomial
//    approximations of Abramowitz & Stegun, Handbook of Mathematical Functions, 9.8.1 (I0 for
//    x <= 3.75), 9.8.5 (K0 for x <= 2) and 9.8.6 (K0 for x >= 2); relative error below 2e-7.
//    Burley's line profile is a sum of two K0 terms.
//  - acosPolynomial: arccos by Abramowitz & Stegun 4.4.46, sqrt(1 - x) times a degree-7
//    polynomial on [0, 1] (absolute error below 2e-8) and pi - acos(-x) below 0; no branches,
//    so loops of it vectorise (the diffuse LUT bake evaluates it millions of times).
//  - normalCdf / normalQuantile: the standard normal CDF via std::erfc, and its inverse by
//    bracketed Newton iteration (accurate to ~1e-14 in x).
// Limits: besselK0 requires x > 0 (it diverges logarithmically at 0).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace preskin::skin {

inline double besselK0(double x) {
    if (x <= 2.0) {
        const double t = x / 3.75;
        const double t2 = t * t;
        const double i0 = 1.0 +
            t2 *
                (3.5156229 +
                 t2 * (3.0899424 + t2 * (1.2067492 + t2 * (0.2659732 + t2 * (0.0360768 + t2 * 0.0045813)))));
        const double y = 0.25 * x * x;
        return -std::log(0.5 * x) * i0 - 0.57721566 +
            y *
            (0.42278420 + y * (0.23069756 + y * (0.03488590 + y * (0.00262698 + y * (0.00010750 + y * 0.0000074)))));
    }
    const double y = 2.0 / x;
    const double poly = 1.25331414 +
        y *
            (-0.07832358 +
             y * (0.02189568 + y * (-0.01062446 + y * (0.00587872 + y * (-0.00251540 + y * 0.00053208)))));
    return std::exp(-x) / std::sqrt(x) * poly;
}

inline double acosPolynomial(double x) {
    const double a = std::abs(x);
    const double p = 1.5707963050 +
        a *
            (-0.2145988016 +
             a *
                 (0.0889789874 +
                  a *
                      (-0.0501743046 +
                       a * (0.0308918810 + a * (-0.0170881256 + a * (0.0066700901 - a * 0.0012624911))))));
    const double r = std::sqrt(std::max(1.0 - a, 0.0)) * p;
    return x < 0.0 ? std::numbers::pi - r : r;
}

inline double normalCdf(double x) { return 0.5 * std::erfc(-x / std::numbers::sqrt2); }

// x with normalCdf(x) = p, for p in (0, 1); -inf / +inf at 0 / 1.
inline double normalQuantile(double p) {
    if (p <= 0.0) return -std::numeric_limits<double>::infinity();
    if (p >= 1.0) return std::numeric_limits<double>::infinity();
    double lo = -40.0;
    double hi = 40.0;
    double x = 0.0;
    for (int iteration = 0; iteration < 200; ++iteration) {
        const double f = normalCdf(x) - p;
        if (f == 0.0) return x;
        if (f < 0.0)
            lo = x;
        else
            hi = x;
        const double density = std::exp(-0.5 * x * x) / std::sqrt(2.0 * std::numbers::pi);
        double next = density > 0.0 ? x - f / density : 0.5 * (lo + hi);
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        if (std::abs(next - x) < 1e-15 * (1.0 + std::abs(x))) return next;
        x = next;
    }
    return x;
}

}  // namespace preskin::skin
