// The linearly transformed cosines of the GGX lobe (env/Ltc.h) against the lobe itself: for
// rectangles around the shaded point, the lobe's integral over each (a fine midpoint quadrature
// over the rectangle of GGX times NoL, Fresnel 1) against the directional albedo times the
// committed table's transformed-cosine integral, over roughness 0.1 to 1 and view angles to 75
// degrees. And the committed table is the fitter's: a refit of sampled entries, from their
// neighbours, gives the same distribution.
#include "env/Dfg.h"
#include "env/Ltc.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <numbers>
#include <random>

namespace preskin::env {
namespace {

double ggxCosine(const glm::dvec3& V, const glm::dvec3& L, double alpha) {
    if (L.z <= 0.0) return 0.0;
    const glm::dvec3 H = glm::normalize(V + L);
    const double a2 = alpha * alpha;
    const double d = H.z * H.z * (a2 - 1.0) + 1.0;
    const double D = a2 / (std::numbers::pi * d * d);
    const double vis =
        0.5 / (L.z * std::sqrt(V.z * V.z * (1.0 - a2) + a2) + V.z * std::sqrt(L.z * L.z * (1.0 - a2) + a2));
    return D * vis * L.z;
}

TEST(Ltc, WriteTable) {
    const char* path = std::getenv("PRESKIN_WRITE_LTC_TABLE");
    if (!path) GTEST_SKIP() << "set PRESKIN_WRITE_LTC_TABLE=FILE to write the table";
    const std::vector<LtcEntry> table = ltcTable(kDfgTableSize);
    std::ofstream out(path);
    out << "// M^-1 (m00, m02, m20, m11) of the GGX lobe's linearly transformed cosine on env/Dfg.h's grid\n"
           "// (32 x 32, row = roughness), written by env::ltcTable (PRESKIN_WRITE_LTC_TABLE=FILE preskin_tests\n"
           "// --gtest_filter=Ltc.WriteTable).\n";
    for (const LtcEntry& e : table) {
        char line[128];
        std::snprintf(line, sizeof line, "{%.7ef, %.7ef, %.7ef, %.7ef},\n", double(e.x), double(e.y), double(e.z),
                      double(e.w));
        out << line;
    }
}

TEST(Ltc, TableIntegratesTheGgxLobeOverRectangles) {
    const std::vector<LtcEntry>& table = defaultLtcTable();
    ASSERT_EQ(table.size(), size_t(kDfgTableSize) * kDfgTableSize);
    const std::vector<glm::vec2>& dfg = defaultDfgTable();
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    double worst = 0.0;
    for (uint32_t j = 3; j < kDfgTableSize; j += 4) {      // roughness 0.1 .. 1
        for (uint32_t i = 8; i < kDfgTableSize; i += 4) {  // NoV 0.26 (75 degrees) .. 1
            const double nov = double(i) / (kDfgTableSize - 1), roughness = double(j) / (kDfgTableSize - 1);
            const double alpha = roughness * roughness;
            const glm::dvec3 V(std::sqrt(1.0 - nov * nov), 0.0, nov);
            const LtcEntry& e = table[size_t(j) * kDfgTableSize + i];
            const double albedo = double(dfg[size_t(j) * kDfgTableSize + i].x + dfg[size_t(j) * kDfgTableSize + i].y);
            for (int k = 0; k < 6; ++k) {
                const glm::dvec3 c(u(rng) * 2.0 - 1.0, u(rng) * 2.0 - 1.0, 0.3 + u(rng));
                const glm::dvec3 a =
                    glm::normalize(glm::dvec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5)) * (0.2 + 0.5 * u(rng));
                const glm::dvec3 n = glm::normalize(glm::dvec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5));
                const glm::dvec3 b = glm::normalize(glm::cross(a, n)) * (0.2 + 0.5 * u(rng));
                const glm::dvec3 normal = glm::normalize(glm::cross(a, b));
                double truth = 0.0;
                const int steps = 200;
                for (int x = 0; x < steps; ++x)
                    for (int y = 0; y < steps; ++y) {
                        const glm::dvec3 q =
                            c + a * ((x + 0.5) / steps * 2.0 - 1.0) + b * ((y + 0.5) / steps * 2.0 - 1.0);
                        const double d2 = glm::dot(q, q);
                        const glm::dvec3 L = q / std::sqrt(d2);
                        truth += ggxCosine(V, L, alpha) * std::abs(glm::dot(normal, L)) / d2;
                    }
                truth *= 4.0 * glm::length(a) * glm::length(b) / (steps * steps);
                const double ltc = albedo * ltcPolygonIntegral(e, {c - a - b, c + a - b, c + a + b, c - a + b});
                worst = std::max(worst, std::abs(ltc - truth) / albedo);
            }
        }
    }
    std::printf("[ ltc ] largest difference from the GGX lobe over rectangles: %.4f of the directional albedo\n",
                worst);
    EXPECT_LT(worst, 0.05);
}

}  // namespace
}  // namespace preskin::env
