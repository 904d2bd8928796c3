#include "skin/GaussianFit.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace preskin {

namespace {

constexpr double kPi = 3.14159265358979323846;

double gaussian(double v, double r) { return std::exp(-r * r / (2.0 * v)) / (2.0 * kPi * v); }

}  // namespace

std::vector<GaussianTerm> normalizedGaussians(const DiffusionProfile& profile) {
    std::vector<GaussianTerm> terms;
    if (profile.kind() == DiffusionProfile::Kind::SumOfGaussians) {
        terms = profile.gaussians();
    } else {
        constexpr int kTerms = 8;
        constexpr int kSamples = 400;
        const double sigma0 = 0.25 * profile.narrowestScaleMm();
        const double reach = profile.reachMm(1e-4);
        for (int k = 0; k < kTerms; ++k) terms.push_back({std::pow(sigma0 * std::pow(2.0, k), 2.0), glm::dvec3(0.0)});
        // Least squares with weights 2 pi r dr over r in (0, reach], per channel: the normal
        // equations A w = b, then non-negative coordinate descent on them.
        std::array<std::array<double, kTerms>, kTerms> a{};
        std::array<glm::dvec3, kTerms> b{};
        for (int i = 0; i < kSamples; ++i) {
            // Samples denser near 0, where R is large: r = reach t^2.
            const double t = (i + 0.5) / kSamples;
            const double r = reach * t * t;
            const double area = 2.0 * kPi * r * (2.0 * reach * t / kSamples);
            const glm::dvec3 target = profile.R(r);
            for (int p = 0; p < kTerms; ++p) {
                const double gp = gaussian(terms[size_t(p)].varianceMm2, r);
                b[size_t(p)] += area * gp * target;
                for (int q = 0; q < kTerms; ++q)
                    a[size_t(p)][size_t(q)] += area * gp * gaussian(terms[size_t(q)].varianceMm2, r);
            }
        }
        for (int c = 0; c < 3; ++c) {
            std::array<double, kTerms> w{};
            for (int sweep = 0; sweep < 2000; ++sweep)
                for (int p = 0; p < kTerms; ++p) {
                    double residual = b[size_t(p)][c];
                    for (int q = 0; q < kTerms; ++q)
                        if (q != p) residual -= a[size_t(p)][size_t(q)] * w[size_t(q)];
                    w[size_t(p)] = std::max(residual / a[size_t(p)][size_t(p)], 0.0);
                }
            for (int p = 0; p < kTerms; ++p) terms[size_t(p)].weight[c] = w[size_t(p)];
        }
    }
    glm::dvec3 sum(0.0);
    for (const GaussianTerm& t : terms) sum += t.weight;
    for (GaussianTerm& t : terms) t.weight /= glm::max(sum, glm::dvec3(1e-12));
    std::sort(terms.begin(), terms.end(),
              [](const GaussianTerm& x, const GaussianTerm& y) { return x.varianceMm2 < y.varianceMm2; });
    std::erase_if(terms, [](const GaussianTerm& t) { return t.weight == glm::dvec3(0.0); });
    return terms;
}

}  // namespace preskin
