// Gauss-Legendre quadrature rules for the LUT bakes and profile integrals. An n-point rule
// integrates polynomials of degree 2n - 1 exactly; composite rules on graded meshes handle the
// narrow peaks and log singularities of diffusion kernels. Nodes are the roots of the Legendre
// polynomial P_n found by Newton's method from the asymptotic guess cos(pi (i - 1/4) / (n + 1/2))
// (Abramowitz & Stegun 25.4.29; Press et al., Numerical Recipes, 3rd ed., 4.6.1).
// Limits: accurate to double precision for n <= 256.
#pragma once

#include <span>

namespace preskin::skin {

struct GaussLegendreRule {
    std::span<const double> nodes;    // on [-1, 1], ascending
    std::span<const double> weights;  // sum to 2
};

// n in {4, 8, 16, 32, 64}; the rule is computed once and cached (thread-safe).
const GaussLegendreRule& gaussLegendre(int n);

// Integral of f over [a, b] with the n-point rule. f: double -> T (double or glm::dvec3).
template <typename T, typename F>
T integrateGaussLegendre(const GaussLegendreRule& rule, double a, double b, F&& f) {
    const double half = 0.5 * (b - a);
    const double mid = 0.5 * (a + b);
    T sum{};
    for (size_t i = 0; i < rule.nodes.size(); ++i) sum += rule.weights[i] * f(mid + half * rule.nodes[i]);
    return half * sum;
}

}  // namespace preskin::skin
