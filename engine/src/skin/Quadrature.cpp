// Gauss-Legendre nodes and weights (see Quadrature.h for the method and sources).
#include "skin/Quadrature.h"

#include <preskin/Error.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace preskin::skin {
namespace {

struct StoredRule {
    std::vector<double> nodes;
    std::vector<double> weights;
    GaussLegendreRule rule;
};

StoredRule computeRule(int n) {
    StoredRule stored;
    stored.nodes.resize(static_cast<size_t>(n));
    stored.weights.resize(static_cast<size_t>(n));
    for (int i = 0; i < (n + 1) / 2; ++i) {
        double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
        double derivative = 1.0;
        for (int iteration = 0; iteration < 100; ++iteration) {
            // Three-term recurrence (k+1) P_{k+1} = (2k+1) x P_k - k P_{k-1}.
            double p0 = 1.0;
            double p1 = x;
            for (int k = 1; k < n; ++k) {
                const double p2 = ((2.0 * k + 1.0) * x * p1 - k * p0) / (k + 1.0);
                p0 = p1;
                p1 = p2;
            }
            derivative = n * (x * p1 - p0) / (x * x - 1.0);
            const double step = p1 / derivative;
            x -= step;
            if (std::abs(step) < 1e-16) break;
        }
        const double weight = 2.0 / ((1.0 - x * x) * derivative * derivative);
        const auto lo = static_cast<size_t>(i);
        const auto hi = static_cast<size_t>(n - 1 - i);
        stored.nodes[lo] = -x;
        stored.nodes[hi] = x;
        stored.weights[lo] = weight;
        stored.weights[hi] = weight;
    }
    if (n % 2 == 1) stored.nodes[static_cast<size_t>(n / 2)] = 0.0;
    stored.rule = {stored.nodes, stored.weights};
    return stored;
}

template <int N>
const GaussLegendreRule& cachedRule() {
    static const StoredRule stored = computeRule(N);
    return stored.rule;
}

}  // namespace

const GaussLegendreRule& gaussLegendre(int n) {
    switch (n) {
    case 4: return cachedRule<4>();
    case 8: return cachedRule<8>();
    case 16: return cachedRule<16>();
    case 32: return cachedRule<32>();
    case 64: return cachedRule<64>();
    default: throw Error("gaussLegendre: unsupported rule size " + std::to_string(n));
    }
}

}  // namespace preskin::skin
