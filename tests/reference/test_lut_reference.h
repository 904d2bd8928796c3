// Independent reference computations for the profile and LUT tests: adaptive Simpson quadrature
// (written here, not the library's Gauss-Legendre), line and radial profiles from test-side
// closed forms (std::cyl_bessel_k for Burley, not the library's Abramowitz-Stegun K0), and the
// diffuse response on a sphere integrated over the surface directly (positions, normals and
// visibility as vectors; no closed form in the azimuth).
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

// Radial profile R(r) of one channel, from the closed forms (test-side code), 1/mm^2.
inline double referenceRadialProfile(const DiffusionProfile& profile, int channel, double r) {
    r = std::abs(r);
    if (profile.kind() == DiffusionProfile::Kind::SumOfGaussians) {
        double sum = 0.0;
        for (const GaussianTerm& t : profile.gaussians())
            sum += t.weight[channel] * std::exp(-r * r / (2.0 * t.varianceMm2)) / (2.0 * kPi * t.varianceMm2);
        return sum;
    }
    const double a = profile.albedo()[channel];
    const double l = profile.meanFreePathMm()[channel];
    const double d = l / (1.85 - a + 7.0 * std::pow(std::abs(a - 0.8), 3.0));
    return a * (std::exp(-r / d) + std::exp(-r / (3.0 * d))) / (8.0 * kPi * d * std::max(r, 1e-300));
}

// The pre-integrated diffuse response on a sphere for one channel, straight from its definition
// as a surface integral: nested adaptive Simpson over the angle psi from x (graded towards 0)
// and the azimuth phi, with each neighbour's position, normal and visibility built as vectors.
// Convex (curvature > 0): the outside of a sphere of radius 1/curvature, visible where
// n_y . L > 0. Concave (< 0): the inside, whose cap of arc radius patchMm around x shadows it: a
// neighbour facing the light is shadowed when the ray towards the light leaves the sphere
// inside that cap. Normalised by the profile's integral over the same surface. (The library
// integrates phi in closed form between visibility thresholds instead.)
inline double referenceSphereScatter(const DiffusionProfile& profile, int channel, double NoL, double curvaturePerMm,
                                     double patchMm) {
    if (curvaturePerMm == 0.0) return std::clamp(NoL, 0.0, 1.0);
    const bool concave = curvaturePerMm < 0.0;
    const double a = 1.0 / std::abs(curvaturePerMm);
    const double theta = std::acos(std::clamp(NoL, -1.0, 1.0));
    const double Lx = std::sin(theta), Lz = std::cos(theta);
    const double psiMax = kPi;
    const double cosPatch = std::cos(std::min(patchMm / a, kPi));
    // The light-weighted azimuthal integral at angle psi (phi in [0, pi], doubled by symmetry).
    auto lit = [&](double psi) {
        const double sp = std::sin(psi), cp = std::cos(psi);
        auto f = [&](double phi) {
            const double yx = a * sp * std::cos(phi), yy = a * sp * std::sin(phi), yz = concave ? -a * cp : a * cp;
            const double sign =
                concave ? -1.0 : 1.0;  // the normal: outward on a convex sphere, inward on a concave one
            const double cosine = sign * (yx * Lx + yz * Lz) / a;
            if (cosine <= 0.0) return 0.0;
            if (concave) {
                const double yl = yx * Lx + yz * Lz;
                const double exitZ = yz - 2.0 * yl * Lz;  // y - 2 (y . L) L, z component
                if (-exitZ / a >= cosPatch) return 0.0;   // leaves the sphere inside the patch
            }
            (void)yy;
            return cosine;
        };
        return 2.0 * adaptiveSimpson(f, 0.0, kPi, 1e-10, 6, 30);
    };
    auto kernel = [&](double psi) {
        return referenceRadialProfile(profile, channel, 2.0 * a * std::sin(0.5 * psi)) * a * a * std::sin(psi);
    };
    const double numerator = integrateGradedTowardsStart(
        [&](double psi) { return psi == 0.0 ? 0.0 : kernel(psi) * lit(psi); }, 0.0, psiMax, 1e-10);
    const double denominator = integrateGradedTowardsStart(
        [&](double psi) { return psi == 0.0 ? 0.0 : 2.0 * kPi * kernel(psi); }, 0.0, psiMax, 1e-10);
    return numerator / denominator;
}

}  // namespace preskin::test
