// Per-vertex signed mean curvature: weld by position, fit each triangle's shape operator to the change of
// the vertex normals along its edges (Rusinkiewicz 2004, see preskin/Curvature.h), average half
// its trace to the vertices by area, smooth once over the one-ring. Computed in double precision.
#include <preskin/Curvature.h>
#include <preskin/Error.h>
#include <preskin/Scene.h>

#include "scene/Weld.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>

namespace preskin {
namespace {

using dvec3 = glm::dvec3;

// Solves the symmetric 3x3 system m x = r by Cramer's rule; false when (nearly) singular.
bool solve3(const std::array<std::array<double, 3>, 3>& m, const std::array<double, 3>& r, std::array<double, 3>& x) {
    auto det3 = [](const std::array<std::array<double, 3>, 3>& a) {
        return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
            a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    };
    const double det = det3(m);
    double scale = 0.0;
    for (const auto& row : m)
        for (double v : row) scale = std::max(scale, std::abs(v));
    if (!(std::abs(det) > 1e-12 * scale * scale * scale)) return false;
    for (size_t c = 0; c < 3; ++c) {
        auto mc = m;
        for (size_t row = 0; row < 3; ++row) mc[row][c] = r[row];
        x[c] = det3(mc) / det;
    }
    return true;
}

}  // namespace

std::vector<float> computeVertexCurvature(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                                          std::span<const uint32_t> indices) {
    const size_t vertexCount = positions.size();
    if (normals.size() != vertexCount) {
        throw Error("computeVertexCurvature: " + std::to_string(normals.size()) + " normals for " +
                    std::to_string(vertexCount) + " positions");
    }
    if (indices.size() % 3 != 0) {
        throw Error("computeVertexCurvature: index count " + std::to_string(indices.size()) +
                    " is not a multiple of 3");
    }
    for (size_t i = 0; i < indices.size(); ++i) {
        if (indices[i] >= vertexCount) {
            throw Error("computeVertexCurvature: indices[" + std::to_string(i) + "] = " + std::to_string(indices[i]) +
                        " >= vertex count " + std::to_string(vertexCount));
        }
    }

    // 1. Weld: one id per (position, normal hemisphere) (scene/Weld.h).
    const WeldedVertices weld = weldVertices(positions, normals);
    const std::vector<uint32_t>& weldedOf = weld.weldedOf;
    std::vector<dvec3> weldedPosition(weld.weldedCount);
    std::vector<dvec3> weldedNormalSum(weld.weldedCount, dvec3(0.0));
    std::vector<bool> placed(weld.weldedCount, false);
    for (size_t i = 0; i < vertexCount; ++i) {
        const uint32_t id = weldedOf[i];
        if (!placed[id]) weldedPosition[id] = dvec3(positions[i]);
        placed[id] = true;
        dvec3 n(normals[i]);
        const double len = glm::length(n);
        weldedNormalSum[id] += (std::isfinite(len) && len > 1e-12) ? n / len : dvec3(0.0);
    }
    const size_t weldedCount = weldedPosition.size();

    // Welded unit normals; where the given normals cancel or are missing, the area-weighted
    // normal of the incident triangles.
    std::vector<dvec3> weldedNormal(weldedCount);
    {
        std::vector<dvec3> faceNormalSum(weldedCount, dvec3(0.0));
        for (size_t t = 0; t + 2 < indices.size(); t += 3) {
            const uint32_t a = weldedOf[indices[t]], b = weldedOf[indices[t + 1]], c = weldedOf[indices[t + 2]];
            const dvec3 areaNormal =
                glm::cross(weldedPosition[b] - weldedPosition[a], weldedPosition[c] - weldedPosition[a]);
            faceNormalSum[a] += areaNormal;
            faceNormalSum[b] += areaNormal;
            faceNormalSum[c] += areaNormal;
        }
        for (size_t w = 0; w < weldedCount; ++w) {
            dvec3 n = weldedNormalSum[w];
            if (glm::length(n) < 1e-9) n = faceNormalSum[w];
            const double len = glm::length(n);
            weldedNormal[w] = len > 0.0 ? n / len : dvec3(0.0);
        }
    }

    // 2. Per-triangle mean curvature, area-weighted onto the welded vertices.
    std::vector<double> curvatureSum(weldedCount, 0.0);
    std::vector<double> weightSum(weldedCount, 0.0);
    std::vector<std::pair<uint32_t, uint32_t>> edges;
    edges.reserve(indices.size());
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        const std::array<uint32_t, 3> w = {weldedOf[indices[t]], weldedOf[indices[t + 1]], weldedOf[indices[t + 2]]};
        if (w[0] == w[1] || w[1] == w[2] || w[2] == w[0]) continue;
        for (size_t k = 0; k < 3; ++k) {
            const uint32_t i = w[k], j = w[(k + 1) % 3];
            edges.emplace_back(std::min(i, j), std::max(i, j));
        }
        const dvec3 p0 = weldedPosition[w[0]], p1 = weldedPosition[w[1]], p2 = weldedPosition[w[2]];
        const dvec3 areaNormal = glm::cross(p1 - p0, p2 - p0);
        const double twiceArea = glm::length(areaNormal);
        const double longestEdgeSq =
            std::max({glm::dot(p1 - p0, p1 - p0), glm::dot(p2 - p1, p2 - p1), glm::dot(p0 - p2, p0 - p2)});
        if (!(twiceArea > 1e-10 * longestEdgeSq)) continue;  // degenerate (sliver or zero area)
        const dvec3 faceNormal = areaNormal / twiceArea;
        const dvec3 u = glm::normalize(p1 - p0);
        const dvec3 v = glm::cross(faceNormal, u);

        // Least squares for the shape operator [[e f] [f g]] in the (u, v) frame:
        //   [eu ev 0] (e f g)^T = dn.u,  [0 eu ev] (e f g)^T = dn.v   for each edge.
        std::array<std::array<double, 3>, 3> m{};
        std::array<double, 3> r{};
        for (size_t k = 0; k < 3; ++k) {
            const uint32_t from = w[k], to = w[(k + 1) % 3];
            const dvec3 edge = weldedPosition[to] - weldedPosition[from];
            const dvec3 dn = weldedNormal[to] - weldedNormal[from];
            const double eu = glm::dot(edge, u), ev = glm::dot(edge, v);
            const double dnu = glm::dot(dn, u), dnv = glm::dot(dn, v);
            const std::array<std::array<double, 3>, 2> rows = {{{eu, ev, 0.0}, {0.0, eu, ev}}};
            const std::array<double, 2> rhs = {dnu, dnv};
            for (size_t q = 0; q < 2; ++q) {
                for (size_t a = 0; a < 3; ++a) {
                    for (size_t b = 0; b < 3; ++b) m[a][b] += rows[q][a] * rows[q][b];
                    r[a] += rows[q][a] * rhs[q];
                }
            }
        }
        std::array<double, 3> x{};
        if (!solve3(m, r, x)) continue;
        const double meanCurvature = 0.5 * (x[0] + x[2]);
        if (!std::isfinite(meanCurvature)) continue;
        const double area = 0.5 * twiceArea;
        for (uint32_t id : w) {
            curvatureSum[id] += area * meanCurvature;
            weightSum[id] += area;
        }
    }
    std::vector<double> curvature(weldedCount, 0.0);
    for (size_t i = 0; i < weldedCount; ++i) {
        if (weightSum[i] > 0.0) curvature[i] = curvatureSum[i] / weightSum[i];
    }

    // 3. One smoothing pass over the welded one-ring: half own value, half the neighbours' mean.
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    std::vector<double> neighbourSum(weldedCount, 0.0);
    std::vector<uint32_t> neighbourCount(weldedCount, 0);
    for (const auto& [i, j] : edges) {
        neighbourSum[i] += curvature[j];
        neighbourSum[j] += curvature[i];
        ++neighbourCount[i];
        ++neighbourCount[j];
    }
    std::vector<float> smoothed(weldedCount, 0.0f);
    for (size_t i = 0; i < weldedCount; ++i) {
        double h = curvature[i];
        if (neighbourCount[i] > 0) h = 0.5 * h + 0.5 * neighbourSum[i] / neighbourCount[i];
        smoothed[i] = static_cast<float>(h);
    }

    std::vector<float> result(vertexCount);
    for (size_t i = 0; i < vertexCount; ++i) result[i] = smoothed[weldedOf[i]];
    return result;
}

void updateMeshCurvature(Mesh& mesh) {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<uint32_t> indices;
    for (const Primitive& primitive : mesh.primitives) {
        const auto base = static_cast<uint32_t>(positions.size());
        for (const Vertex& vertex : primitive.vertices) {
            positions.push_back(vertex.positionOs);
            normals.push_back(vertex.normalOs);
        }
        for (uint32_t index : primitive.indices) indices.push_back(base + index);
    }
    const std::vector<float> curvature = computeVertexCurvature(positions, normals, indices);
    size_t next = 0;
    for (Primitive& primitive : mesh.primitives) {
        for (Vertex& vertex : primitive.vertices) vertex.curvaturePerM = curvature[next++];
    }
}

}  // namespace preskin
