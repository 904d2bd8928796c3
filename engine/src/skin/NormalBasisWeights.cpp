// The profile half of the skin's per-channel prefiltered normals (see <preskin/NormalBasis.h>):
// per colour channel, the weights of the normal basis that stand for a diffusion profile.
#include <preskin/NormalBasis.h>

#include <cmath>
#include <numbers>
#include <vector>

namespace preskin {

std::array<glm::vec4, 3> normalBasisWeights(const DiffusionProfile& profile, double scatterScale) {
    // What the prefiltered normal takes from a kernel K is, for a smoothly varying normal field,
    // its second moment, and for features of size l the part of that moment beyond l. So match
    // the second-moment tail V(r) = int_r^inf K(t) t^2 2 pi t dt of the profile (in world mm:
    // V_profile(s r) / s^2 for scatter scale s) by sum_b a_b V_b(r), V_b(r) = 2 s_b^2 (1 + u) e^-u,
    // u = r^2 / 2 s_b^2, at radii spaced evenly in log r; the identity (the vertex normal) has no
    // second moment and takes 1 - sum a_b. Least squares over every subset of the basis, keeping
    // the best whose weights are all positive; the sum scaled to at most 1.
    constexpr int kRadii = 64;
    constexpr double rMin = 0.05, rMax = 20.0;
    const double scale = std::isfinite(scatterScale) && scatterScale > 0.0 ? scatterScale : 1.0;
    // The profile's tail V_profile on a fine log grid (trapezoids in log t, from the far end).
    constexpr int kFine = 4096;
    const double tMin = 1e-4, tMax = 200.0;
    std::vector<double> fineT(kFine);
    std::vector<glm::dvec3> tail(kFine, glm::dvec3(0.0));
    const glm::dvec3 albedo = glm::max(profile.albedo(), glm::dvec3(1e-300));
    auto integrand = [&](double t) { return profile.R(t) / albedo * (2.0 * std::numbers::pi * t * t * t * t); };
    for (int k = 0; k < kFine; ++k) fineT[size_t(k)] = tMin * std::pow(tMax / tMin, double(k) / (kFine - 1));
    const double dLog = std::log(tMax / tMin) / (kFine - 1);
    glm::dvec3 next = integrand(fineT.back());
    for (int k = kFine - 2; k >= 0; --k) {
        const glm::dvec3 here = integrand(fineT[size_t(k)]);
        tail[size_t(k)] = tail[size_t(k) + 1] + 0.5 * (here + next) * dLog;
        next = here;
    }
    auto profileTail = [&](double t) {
        if (t <= tMin) return tail.front();
        if (t >= tMax) return glm::dvec3(0.0);
        const double x = std::log(t / tMin) / dLog;
        const auto k = std::min(size_t(x), size_t(kFine - 2));
        const double f = x - double(k);
        return tail[k] * (1.0 - f) + tail[k + 1] * f;
    };
    std::array<std::array<double, kNormalBasisCount>, kRadii> basis{};
    std::array<glm::dvec3, kRadii> target{};
    for (int i = 0; i < kRadii; ++i) {
        const double r = rMin * std::pow(rMax / rMin, double(i) / (kRadii - 1));
        for (int b = 0; b < kNormalBasisCount; ++b) {
            const double v = kNormalBasisSigmaMm[size_t(b)] * kNormalBasisSigmaMm[size_t(b)];
            const double u = r * r / (2.0 * v);
            basis[size_t(i)][size_t(b)] = 2.0 * v * (1.0 + u) * std::exp(-u);
        }
        target[size_t(i)] = profileTail(r * scale) / (scale * scale);
    }
    std::array<glm::vec4, 3> result{};
    for (int c = 0; c < 3; ++c) {
        double bestError = 0.0;
        std::array<double, kNormalBasisCount> best{};
        for (int i = 0; i < kRadii; ++i) bestError += target[size_t(i)][c] * target[size_t(i)][c];  // all zero
        for (unsigned subset = 1; subset < (1u << kNormalBasisCount); ++subset) {
            // Normal equations over the subset's columns, solved by Gauss-Jordan elimination.
            std::vector<int> cols;
            for (int b = 0; b < kNormalBasisCount; ++b)
                if (subset & (1u << b)) cols.push_back(b);
            const size_t k = cols.size();
            std::vector<double> a(k * (k + 1), 0.0);
            for (int i = 0; i < kRadii; ++i)
                for (size_t u = 0; u < k; ++u) {
                    for (size_t v = 0; v < k; ++v)
                        a[u * (k + 1) + v] += basis[size_t(i)][size_t(cols[u])] * basis[size_t(i)][size_t(cols[v])];
                    a[u * (k + 1) + k] += basis[size_t(i)][size_t(cols[u])] * target[size_t(i)][c];
                }
            bool singular = false;
            for (size_t u = 0; u < k && !singular; ++u) {
                const double pivot = a[u * (k + 1) + u];
                if (!(std::abs(pivot) > 1e-300)) {
                    singular = true;
                    break;
                }
                for (size_t v = 0; v < k; ++v) {
                    if (v == u) continue;
                    const double f = a[v * (k + 1) + u] / pivot;
                    for (size_t w = u; w <= k; ++w) a[v * (k + 1) + w] -= f * a[u * (k + 1) + w];
                }
            }
            if (singular) continue;
            std::array<double, kNormalBasisCount> x{};
            bool positive = true;
            for (size_t u = 0; u < k; ++u) {
                x[size_t(cols[u])] = a[u * (k + 1) + k] / a[u * (k + 1) + u];
                positive = positive && x[size_t(cols[u])] > 0.0;
            }
            if (!positive) continue;
            double error = 0.0;
            for (int i = 0; i < kRadii; ++i) {
                double model = 0.0;
                for (int b = 0; b < kNormalBasisCount; ++b) model += x[size_t(b)] * basis[size_t(i)][size_t(b)];
                error += (model - target[size_t(i)][c]) * (model - target[size_t(i)][c]);
            }
            if (error < bestError) {
                bestError = error;
                best = x;
            }
        }
        double sum = 0.0;
        for (double v : best) sum += v;
        for (int b = 0; b < kNormalBasisCount; ++b)
            result[size_t(c)][b] = float(sum > 1.0 ? best[size_t(b)] / sum : best[size_t(b)]);
    }
    return result;
}

}  // namespace preskin
