// Linearly transformed cosines for GGX; see env/Ltc.h.
#include "env/Ltc.h"
#include "env/Dfg.h"

#include <tbb/parallel_for.h>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <numbers>

namespace preskin::env {

namespace {

constexpr double kPi = std::numbers::pi;

// GGX times NoL (Fresnel 1), the BRDF of preskin/brdf.glsl.
double ggxCosine(const glm::dvec3& V, const glm::dvec3& L, double alpha) {
    if (L.z <= 0.0) return 0.0;
    const glm::dvec3 H = glm::normalize(V + L);
    const double a2 = alpha * alpha;
    const double d = H.z * H.z * (a2 - 1.0) + 1.0;
    const double D = a2 / (kPi * d * d);
    const double vis =
        0.5 / (L.z * std::sqrt(V.z * V.z * (1.0 - a2) + a2) + V.z * std::sqrt(L.z * L.z * (1.0 - a2) + a2));
    return D * vis * L.z;
}

// Directions on a polar grid around `axis`, denser near it (polar angle pi t^2), and their solid angles.
struct PolarGrid {
    std::vector<glm::dvec3> directions;
    std::vector<double> weights;
};

PolarGrid polarGrid(const glm::dvec3& axis, int rings, int segments) {
    const glm::dvec3 t1 = glm::normalize(glm::cross(axis, glm::dvec3(0.0, 1.0, 0.0)));
    const glm::dvec3 t2 = glm::cross(axis, t1);
    PolarGrid g;
    for (int i = 0; i < rings; ++i) {
        const double t = (i + 0.5) / rings;
        const double psi = kPi * t * t, dpsi = 2.0 * kPi * t / rings;
        for (int j = 0; j < segments; ++j) {
            const double phi = 2.0 * kPi * (j + 0.5) / segments;
            g.directions.push_back(std::cos(psi) * axis + std::sin(psi) * (std::cos(phi) * t1 + std::sin(phi) * t2));
            g.weights.push_back(std::sin(psi) * dpsi * (2.0 * kPi / segments));
        }
    }
    return g;
}

glm::dmat3 ltcMatrix(const glm::dvec3& meanDirection, const glm::dvec4& p) {
    const double angle = std::atan2(meanDirection.x, meanDirection.z) + p.w;
    const glm::dvec3 z(std::sin(angle), 0.0, std::cos(angle)), y(0.0, 1.0, 0.0), x = glm::cross(y, z);
    glm::dmat3 s(1.0);
    s[0][0] = p.x;
    s[1][1] = p.y;
    s[2][0] = p.z;  // column 2, row 0: x' = sx x + k z
    return glm::dmat3(x, y, z) * s;
}

double nelderMead(const std::function<double(const glm::dvec4&)>& f, glm::dvec4& x, double step, int iterations) {
    std::array<glm::dvec4, 5> s;
    std::array<double, 5> v;
    for (int i = 0; i < 5; ++i) {
        s[size_t(i)] = x;
        if (i > 0) s[size_t(i)][i - 1] += step;
        v[size_t(i)] = f(s[size_t(i)]);
    }
    for (int it = 0; it < iterations; ++it) {
        std::array<int, 5> order = {0, 1, 2, 3, 4};
        std::sort(order.begin(), order.end(), [&](int a, int b) { return v[size_t(a)] < v[size_t(b)]; });
        const size_t best = size_t(order[0]), worst = size_t(order[4]), second = size_t(order[3]);
        glm::dvec4 c(0.0);
        for (int i = 0; i < 4; ++i) c += s[size_t(order[size_t(i)])] / 4.0;
        const auto along = [&](double t) { return c + t * (s[worst] - c); };
        const glm::dvec4 r = along(-1.0);
        const double fr = f(r);
        if (fr < v[best]) {
            const glm::dvec4 e = along(-2.0);
            const double fe = f(e);
            s[worst] = fe < fr ? e : r;
            v[worst] = std::min(fe, fr);
        } else if (fr < v[second]) {
            s[worst] = r;
            v[worst] = fr;
        } else {
            const glm::dvec4 k = along(0.5);
            const double fk = f(k);
            if (fk < v[worst]) {
                s[worst] = k;
                v[worst] = fk;
            } else {
                for (size_t i = 0; i < 5; ++i) {
                    if (i == best) continue;
                    s[i] = s[best] + 0.5 * (s[i] - s[best]);
                    v[i] = f(s[i]);
                }
            }
        }
    }
    size_t best = 0;
    for (size_t i = 1; i < 5; ++i)
        if (v[i] < v[best]) best = i;
    x = s[best];
    return v[best];
}

}  // namespace

LtcEntry fitLtc(float NoV, float roughness, const glm::dvec4* start, glm::dvec4* parameters) {
    const double alpha = std::pow(std::max(double(roughness), 0.1), 2.0);
    const double nov = std::clamp(double(NoV), 0.02, 1.0);
    const glm::dvec3 V(std::sqrt(1.0 - nov * nov), 0.0, nov);
    // The lobe's integral and mean direction (on a grid around the mirror direction).
    const PolarGrid coarse = polarGrid(glm::dvec3(-V.x, 0.0, V.z), 96, 96);
    double albedo = 0.0;
    glm::dvec3 mean(0.0);
    for (size_t i = 0; i < coarse.directions.size(); ++i) {
        const double f = ggxCosine(V, coarse.directions[i], alpha) * coarse.weights[i];
        albedo += f;
        mean += f * coarse.directions[i];
    }
    mean = glm::normalize(glm::dvec3(mean.x, 0.0, mean.z));
    const PolarGrid grid = polarGrid(mean, 48, 48);
    std::vector<double> target(grid.directions.size());
    for (size_t i = 0; i < target.size(); ++i) target[i] = ggxCosine(V, grid.directions[i], alpha) / albedo;
    const auto error = [&](const glm::dvec4& p) {
        if (!(p.x > 1e-4 && p.y > 1e-4)) return 1e30;
        const glm::dmat3 minv = glm::inverse(ltcMatrix(mean, p));
        const double det = std::abs(glm::determinant(minv));
        double e = 0.0;
        for (size_t i = 0; i < target.size(); ++i) {
            const glm::dvec3 lo = minv * grid.directions[i];
            const double l = glm::length(lo);
            const double d = std::max(lo.z / l, 0.0) / kPi * det / (l * l * l) - target[i];
            e += std::abs(d * d * d) * grid.weights[i];
        }
        return e;
    };
    glm::dvec4 p = start ? *start : glm::dvec4(alpha, alpha, 0.0, 0.0);
    nelderMead(error, p, 0.05, 500);
    nelderMead(error, p, 0.01, 500);
    if (parameters) *parameters = p;
    glm::dmat3 minv = glm::inverse(ltcMatrix(mean, p));
    minv /= minv[2][2];
    return LtcEntry(float(minv[0][0]), float(minv[2][0]), float(minv[0][2]), float(minv[1][1]));
}

std::vector<LtcEntry> ltcTable(uint32_t size) {
    std::vector<LtcEntry> table(size_t(size) * size);
    std::vector<glm::dvec4> params(table.size());
    // Each roughness column from the normal towards grazing, each entry from its neighbour:
    // roughness from 1 down, in parallel over NoV for the first entry of a column.
    std::vector<glm::dvec4> columnStart(size);
    for (uint32_t jj = 0; jj < size; ++jj) {
        const uint32_t j = size - 1 - jj;
        const float roughness = float(j) / float(size - 1);
        const glm::dvec4* start = jj == 0 ? nullptr : &columnStart[j + 1];
        table[size_t(j) * size + size - 1] = fitLtc(1.0f, roughness, start, &columnStart[j]);
    }
    tbb::parallel_for(uint32_t(0), size, [&](uint32_t j) {
        glm::dvec4 p = columnStart[j];
        for (uint32_t ii = 1; ii < size; ++ii) {
            const uint32_t i = size - 1 - ii;
            const glm::dvec4 start = p;
            table[size_t(j) * size + i] = fitLtc(float(i) / float(size - 1), float(j) / float(size - 1), &start, &p);
        }
    });
    return table;
}

const std::vector<LtcEntry>& defaultLtcTable() {
    static const std::vector<LtcEntry> table = {
#include "env/LtcTable.inc"
    };
    return table;
}

double ltcPolygonIntegral(const LtcEntry& e, const std::vector<glm::dvec3>& corners) {
    glm::dmat3 minv(1.0);
    minv[0][0] = e.x;
    minv[2][0] = e.y;
    minv[0][2] = e.z;
    minv[1][1] = e.w;
    std::vector<glm::dvec3> in, out;
    for (const glm::dvec3& c : corners) in.push_back(minv * c);
    for (size_t i = 0; i < in.size(); ++i) {
        const glm::dvec3 &a = in[i], &b = in[(i + 1) % in.size()];
        if (a.z >= 0.0) out.push_back(a);
        if ((a.z >= 0.0) != (b.z >= 0.0)) out.push_back(a + (b - a) * (a.z / (a.z - b.z)));
    }
    if (out.size() < 3) return 0.0;
    double sum = 0.0;
    for (size_t i = 0; i < out.size(); ++i) {
        const glm::dvec3 a = glm::normalize(out[i]), b = glm::normalize(out[(i + 1) % out.size()]);
        const glm::dvec3 c = glm::cross(a, b);
        const double s = glm::length(c);
        if (s > 0.0) sum += std::atan2(s, glm::dot(a, b)) * c.z / s;
    }
    return std::abs(sum) / (2.0 * kPi);
}

}  // namespace preskin::env
