// The split-sum environment BRDF table; see env/Dfg.h.
#include "env/Dfg.h"

#include <tbb/parallel_for.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace preskin::env {

glm::vec2 dfgIntegral(float NoV, float roughness, uint32_t heightSteps, uint32_t turnSteps) {
    const double alpha = std::max(double(roughness) * double(roughness), 1e-3);
    const double a2 = alpha * alpha;
    const double nov = std::max(double(NoV), 1e-4);
    const glm::dvec3 V(std::sqrt(std::max(0.0, 1.0 - nov * nov)), 0.0, nov);
    const double viewTerm = std::sqrt(nov * nov * (1.0 - a2) + a2);
    double a = 0.0, b = 0.0;
    for (uint32_t i = 0; i < heightSteps; ++i) {
        // GGX half vectors (Walter et al. 2007): cos^2 theta_h = (1 - u) / (1 + (a^2 - 1) u).
        const double u = (double(i) + 0.5) / double(heightSteps);
        const double cosH = std::sqrt((1.0 - u) / (1.0 + (a2 - 1.0) * u));
        const double sinH = std::sqrt(std::max(0.0, 1.0 - cosH * cosH));
        for (uint32_t j = 0; j < turnSteps; ++j) {
            const double phi = M_PI * (double(j) + 0.5) / double(turnSteps);  // mirror-symmetric about phi = 0
            const glm::dvec3 H(sinH * std::cos(phi), sinH * std::sin(phi), cosH);
            const double VoH = glm::dot(V, H);
            const double NoL = 2.0 * VoH * cosH - nov;
            if (NoL <= 0.0 || VoH <= 0.0) continue;
            const double vis = 0.5 / std::max(NoL * viewTerm + nov * std::sqrt(NoL * NoL * (1.0 - a2) + a2), 1e-12);
            // D V NoL over the density of L, D NoH / (4 VoH).
            const double weight = 4.0 * vis * NoL * VoH / cosH;
            const double m = 1.0 - VoH;
            const double fc = m * m * m * m * m;
            a += (1.0 - fc) * weight;
            b += fc * weight;
        }
    }
    const double n = double(heightSteps) * double(turnSteps);
    return glm::vec2(float(a / n), float(b / n));
}

std::vector<glm::vec2> dfgTable(uint32_t size, uint32_t heightSteps, uint32_t turnSteps) {
    std::vector<glm::vec2> table(size_t(size) * size);
    tbb::parallel_for(uint32_t(0), size * size, [&](uint32_t k) {
        const uint32_t i = k % size, j = k / size;
        table[k] = dfgIntegral(float(i) / float(size - 1), float(j) / float(size - 1), heightSteps, turnSteps);
    });
    return table;
}

const std::vector<glm::vec2>& defaultDfgTable() {
    static const std::vector<glm::vec2> table = dfgTable(kDfgTableSize);
    return table;
}

}  // namespace preskin::env
