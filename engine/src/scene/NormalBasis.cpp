// The geometry half of the skin's per-channel prefiltered normals (see <preskin/NormalBasis.h>):
// per vertex x, M_b(x) = n(x) + int G_b(|x - y|) (n(y) - n(x)) dA(y) over the neighbours facing
// within 90 degrees of n(x), and O_b(x) = int G_b n(y) dA(y) with their centroid over the others,
// the vertex normals interpolated linearly, for the basis Gaussians G_b (the difference vanishes at x,
// so the narrow Gaussians need no fine pieces there), as a tree code (Barnes & Hut): a bounding
// volume hierarchy over the triangles holds each node's area, centroid and normal integral; a node
// small for the Gaussians it reaches, whose normals agree, counts as one sample at its centroid;
// triangles are split into sub-triangles until they are small for the Gaussians they reach
// (finest near x, where the narrow ones do). The cost per vertex grows with the logarithm of the mesh
// size, not with the triangles within reach. Computed in double precision, in parallel (TBB).
#include <preskin/Error.h>
#include <preskin/NormalBasis.h>

#include "scene/Weld.h"

#include <fmt/core.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>

namespace preskin {

namespace {

using dvec3 = glm::dvec3;

constexpr double kReachSigmas = 3.0;  // a basis Gaussian holds 98.9 % of its energy within 3 sigma
// A piece of size (radius) s at distance d samples each Gaussian G_b it reaches once its size is
// below theta s_b^2 / max(d, s_b): G_b changes by about exp(theta) across it. Triangles are then
// integrated by the three-point edge-midpoint rule (exact to second order), tree nodes as one point.
constexpr double kTriangleTheta = 2.0;
constexpr double kNodeTheta = 0.5;
constexpr double kCoherentNormals = 0.95;  // ... and its normal integral is at least this fraction of its area
constexpr int kLeafTriangles = 4;
constexpr double kOpposingRamp = 0.1;  // opposing neighbours weigh -n . nx / this, at most 1

struct Node {
    dvec3 centroid{0.0};
    dvec3 normalIntegral{0.0};  // int n dA, n interpolated linearly (not renormalised)
    double area = 0.0;
    double radius = 0.0;  // bounding sphere about the centroid
    // |int n dA|, and the spread of its normals about their mean: the sine of about their largest
    // angle to it, from |int n dA| / area; infinite where they agree too little (that ratio below
    // kCoherentNormals) for the node to count as one sample.
    double normalLength = 0.0, spread = 0.0;
    uint32_t first = 0, count = 0;  // leaf: triangles [first, first + count) of the order
    int32_t left = -1, right = -1;
};

struct Mesh {
    std::vector<dvec3> p, n;  // welded positions (mm) and unit normals
    std::vector<std::array<uint32_t, 3>> triangles;
    std::vector<uint32_t> order;  // triangles in tree order
    std::vector<Node> nodes;
};

int32_t build(Mesh& m, uint32_t first, uint32_t count) {
    Node node;
    node.first = first;
    node.count = count;
    dvec3 lo(1e300), hi(-1e300);
    for (uint32_t i = first; i < first + count; ++i) {
        const auto& t = m.triangles[m.order[i]];
        const dvec3 a = m.p[t[0]], b = m.p[t[1]], c = m.p[t[2]];
        const double area = 0.5 * glm::length(glm::cross(b - a, c - a));
        node.area += area;
        node.centroid += area * (a + b + c) / 3.0;
        node.normalIntegral += area * (m.n[t[0]] + m.n[t[1]] + m.n[t[2]]) / 3.0;
        for (const dvec3& q : {a, b, c}) {
            lo = glm::min(lo, q);
            hi = glm::max(hi, q);
        }
    }
    node.centroid = node.area > 0.0 ? node.centroid / node.area : 0.5 * (lo + hi);
    const double coherence = node.area > 0.0 ? glm::length(node.normalIntegral) / node.area : 0.0;
    node.normalLength = coherence * node.area;
    node.spread = coherence >= kCoherentNormals ? std::sqrt(std::max(0.0, 1.0 - coherence * coherence))
                                                : std::numeric_limits<double>::infinity();
    for (uint32_t i = first; i < first + count; ++i)
        for (uint32_t v : m.triangles[m.order[i]])
            node.radius = std::max(node.radius, glm::length(m.p[v] - node.centroid));
    const auto index = int32_t(m.nodes.size());
    m.nodes.push_back(node);
    if (count > uint32_t(kLeafTriangles)) {
        // Split at the median centroid along the longest side of the box.
        const dvec3 extent = hi - lo;
        const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
        auto key = [&](uint32_t t) {
            const auto& c = m.triangles[t];
            return m.p[c[0]][axis] + m.p[c[1]][axis] + m.p[c[2]][axis];
        };
        const uint32_t half = count / 2;
        std::nth_element(m.order.begin() + first, m.order.begin() + first + half, m.order.begin() + first + count,
                         [&](uint32_t a, uint32_t b) { return key(a) < key(b); });
        const int32_t left = build(m, first, half);
        const int32_t right = build(m, first + half, count - half);
        m.nodes[size_t(index)].left = left;
        m.nodes[size_t(index)].right = right;
    }
    return index;
}

// One basis Gaussian: its normalisation, reach and the largest piece that samples it.
struct Kernel {
    double halfInvVariance = 0.0;
    double norm = 0.0;  // 1 / (2 pi sigma^2)
    double sigma = 0.0;
    double reach = 0.0;
    double operator()(double r2) const { return norm * std::exp(-r2 * halfInvVariance); }
    // The largest piece (radius) at `distance` that samples the Gaussian to about exp(theta) (theta
    // times its width squared over the distance: where it changes fastest, the piece is smallest).
    double largestPiece(double distance, double theta) const {
        return theta * sigma * sigma / std::max(distance, sigma);
    }
};

// What one Gaussian gathers around x: over the neighbours facing within 90 degrees of nx,
// int G (n - nx) dA; over those facing away, weighted by c = min(-n . nx / kOpposingRamp, 1) (they
// fade in past the 90-degree cut, within 6 degrees: a wall meeting x at a right angle, which a
// coarse mesh would spread over a whole triangle, adds nothing), int c G n dA, int c G (y - x) dA
// and int c G dA.
struct Sums {
    dvec3 averaged{0.0};
    dvec3 opposing{0.0};
    dvec3 centroid{0.0};
    double weight = 0.0;
    // A sample of weight w (G dA) with normal integral n (n dA) at y.
    void add(double w, const dvec3& n, double area, const dvec3& y, const dvec3& x, const dvec3& nx) {
        if (glm::dot(n, nx) > 0.0) {
            averaged += w * (n - area * nx);
        } else {
            const double length = glm::length(n);
            const double c = length > 0.0 ? std::clamp(-glm::dot(n, nx) / (length * kOpposingRamp), 0.0, 1.0) : 0.0;
            opposing += (c * w) * n;
            centroid += (c * w * area) * (y - x);
            weight += c * w * area;
        }
    }
};

using Kernels = std::array<Kernel, kNormalBasisCount>;
using KernelSums = std::array<Sums, kNormalBasisCount>;
using KernelMask = uint32_t;  // bit b: the Gaussian kernels[b] still gathers here

// Adds the triangle (p, with corner normals n) to the sums of the Gaussians in `mask`, each
// splitting it into four while it is too large for that Gaussian: one recursion for all of them,
// each Gaussian's pieces and their order the same as in a recursion of its own.
void addTriangle(const Kernels& kernels, KernelMask mask, const dvec3& x, const dvec3& nx, const dvec3 (&p)[3],
                 const dvec3 (&n)[3], KernelSums& sums, int depth) {
    const dvec3 centre = (p[0] + p[1] + p[2]) / 3.0;
    double size = 0.0;
    for (int k = 0; k < 3; ++k) size = std::max(size, glm::length(p[k] - centre));
    const double distance = glm::length(centre - x);
    KernelMask split = 0, here = 0;
    for (int b = 0; b < kNormalBasisCount; ++b) {
        if ((mask & (1u << b)) == 0 || distance - size > kernels[size_t(b)].reach) continue;
        if (depth < 12 && size > kernels[size_t(b)].largestPiece(distance, kTriangleTheta))
            split |= 1u << b;
        else
            here |= 1u << b;
    }
    if (here != 0) {
        const double third = 0.5 * glm::length(glm::cross(p[1] - p[0], p[2] - p[0])) / 3.0;
        for (int k = 0; k < 3; ++k) {  // the edge midpoints, a third of the area each
            const dvec3 y = 0.5 * (p[k] + p[(k + 1) % 3]);
            const dvec3 ny = 0.5 * (n[k] + n[(k + 1) % 3]);
            const dvec3 d = y - x;
            const double r2 = glm::dot(d, d);
            for (int b = 0; b < kNormalBasisCount; ++b) {
                const Kernel& g = kernels[size_t(b)];
                if ((here & (1u << b)) == 0 || r2 > g.reach * g.reach) continue;
                sums[size_t(b)].add(g(r2) * third, ny, 1.0, y, x, nx);
            }
        }
    }
    if (split != 0) {
        const dvec3 pm[3] = {0.5 * (p[0] + p[1]), 0.5 * (p[1] + p[2]), 0.5 * (p[2] + p[0])};
        const dvec3 nm[3] = {0.5 * (n[0] + n[1]), 0.5 * (n[1] + n[2]), 0.5 * (n[2] + n[0])};
        const dvec3 t0[3] = {p[0], pm[0], pm[2]}, n0[3] = {n[0], nm[0], nm[2]};
        const dvec3 t1[3] = {pm[0], p[1], pm[1]}, n1[3] = {nm[0], n[1], nm[1]};
        const dvec3 t2[3] = {pm[2], pm[1], p[2]}, n2[3] = {nm[2], nm[1], n[2]};
        const dvec3 t3[3] = {pm[0], pm[1], pm[2]}, n3[3] = {nm[0], nm[1], nm[2]};
        addTriangle(kernels, split, x, nx, t0, n0, sums, depth + 1);
        addTriangle(kernels, split, x, nx, t1, n1, sums, depth + 1);
        addTriangle(kernels, split, x, nx, t2, n2, sums, depth + 1);
        addTriangle(kernels, split, x, nx, t3, n3, sums, depth + 1);
    }
}

// The sums over the mesh for every Gaussian, in one traversal of the tree: each node is opened
// for the Gaussians whose width needs it (the mask), and each Gaussian meets its nodes in the
// order a traversal of its own would.
KernelSums integrate(const Mesh& m, const Kernels& kernels, const dvec3& x, const dvec3& nx,
                     std::vector<std::pair<int32_t, KernelMask>>& stack) {
    KernelSums sums{};
    stack.assign(1, {0, (1u << kNormalBasisCount) - 1u});
    while (!stack.empty()) {
        const auto [index, mask] = stack.back();
        stack.pop_back();
        const Node& node = m.nodes[size_t(index)];
        const double distance = glm::length(node.centroid - x);
        // Its normals lie within about acos(|int n dA| / area) of their mean: wholly on one side of
        // the cut at 90 degrees from nx and small for a Gaussian, the node counts as one sample.
        const bool oneSided =
            std::isfinite(node.spread) && std::abs(glm::dot(node.normalIntegral, nx) / node.normalLength) > node.spread;
        KernelMask open = 0;
        for (int b = 0; b < kNormalBasisCount; ++b) {
            const Kernel& g = kernels[size_t(b)];
            if ((mask & (1u << b)) == 0 || distance - node.radius > g.reach) continue;
            if (oneSided && node.radius < g.largestPiece(distance, kNodeTheta)) {
                if (distance <= g.reach)
                    sums[size_t(b)].add(g(distance * distance), node.normalIntegral, node.area, node.centroid, x, nx);
                continue;
            }
            open |= 1u << b;
        }
        if (open == 0) continue;
        if (node.left >= 0) {
            stack.emplace_back(node.left, open);
            stack.emplace_back(node.right, open);
            continue;
        }
        for (uint32_t i = node.first; i < node.first + node.count; ++i) {
            const auto& t = m.triangles[m.order[i]];
            const dvec3 p[3] = {m.p[t[0]], m.p[t[1]], m.p[t[2]]};
            const dvec3 n[3] = {m.n[t[0]], m.n[t[1]], m.n[t[2]]};
            addTriangle(kernels, open, x, nx, p, n, sums, 0);
        }
    }
    return sums;
}

}  // namespace

std::vector<NormalBasis> computeNormalBasis(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                                            std::span<const uint32_t> indices, double mmPerUnit) {
    const size_t vertexCount = positions.size();
    if (normals.size() != vertexCount)
        throw Error(fmt::format("computeNormalBasis: {} normals for {} positions", normals.size(), vertexCount));
    if (indices.size() % 3 != 0)
        throw Error(fmt::format("computeNormalBasis: index count {} is not a multiple of 3", indices.size()));
    for (size_t i = 0; i < indices.size(); ++i)
        if (indices[i] >= vertexCount)
            throw Error(
                fmt::format("computeNormalBasis: indices[{}] = {} >= vertex count {}", i, indices[i], vertexCount));
    if (!std::isfinite(mmPerUnit) || !(mmPerUnit > 0.0))
        throw Error(fmt::format("computeNormalBasis: mmPerUnit must be a positive finite number, got {}", mmPerUnit));
    for (size_t i = 0; i < vertexCount; ++i)
        if (!std::isfinite(positions[i].x) || !std::isfinite(positions[i].y) || !std::isfinite(positions[i].z))
            throw Error(fmt::format("computeNormalBasis: positions[{}] is not finite", i));

    // Welded vertices (seams share one value): the first member's position, the unit sum of the
    // members' unit normals.
    const WeldedVertices weld = weldVertices(positions, normals);
    Mesh m;
    m.p.assign(weld.weldedCount, dvec3(0.0));
    m.n.assign(weld.weldedCount, dvec3(0.0));
    std::vector<bool> placed(weld.weldedCount, false);
    for (size_t i = 0; i < vertexCount; ++i) {
        const uint32_t w = weld.weldedOf[i];
        if (!placed[w]) m.p[w] = dvec3(positions[i]) * mmPerUnit;
        placed[w] = true;
        const dvec3 n(normals[i]);
        const double len = glm::length(n);
        if (std::isfinite(len) && len > 1e-12) m.n[w] += n / len;
    }
    for (dvec3& n : m.n) {
        const double len = glm::length(n);
        n = len > 1e-6 ? n / len : dvec3(0.0);
    }
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        const std::array<uint32_t, 3> c = {weld.weldedOf[indices[t]], weld.weldedOf[indices[t + 1]],
                                           weld.weldedOf[indices[t + 2]]};
        if (c[0] != c[1] && c[1] != c[2] && c[2] != c[0]) m.triangles.push_back(c);
    }
    std::vector<NormalBasis> welded(weld.weldedCount, NormalBasis{});
    if (!m.triangles.empty()) {
        m.order.resize(m.triangles.size());
        std::iota(m.order.begin(), m.order.end(), 0u);
        m.nodes.reserve(2 * m.triangles.size() / kLeafTriangles + 2);
        build(m, 0, uint32_t(m.triangles.size()));

        Kernels kernels{};
        for (size_t b = 0; b < kernels.size(); ++b) {
            const double sigma = kNormalBasisSigmaMm[b];
            kernels[b] = {0.5 / (sigma * sigma), 1.0 / (2.0 * std::numbers::pi * sigma * sigma), sigma,
                          kReachSigmas * sigma};
        }
        tbb::parallel_for(tbb::blocked_range<uint32_t>(0, weld.weldedCount, 64), [&](const auto& range) {
            std::vector<std::pair<int32_t, KernelMask>> stack;
            for (uint32_t w = range.begin(); w != range.end(); ++w) {
                if (m.n[w] == dvec3(0.0)) continue;
                const KernelSums sums = integrate(m, kernels, m.p[w], m.n[w], stack);
                dvec3 centroid(0.0);
                double weight = 0.0;
                for (size_t b = 0; b < kernels.size(); ++b) {
                    const Sums& s = sums[b];
                    welded[w].averaged[b] = glm::vec3(m.n[w] + s.averaged);
                    welded[w].opposing[b] = glm::vec3(s.opposing);
                    centroid += s.centroid;
                    weight += s.weight;
                }
                // The Gaussians' centroids together, the narrow ones (nearest neighbours) weighing most.
                if (weight > 1e-9) welded[w].opposingCentroid = glm::vec3(centroid / (weight * mmPerUnit));
            }
        });
    }
    std::vector<NormalBasis> out(vertexCount);
    for (size_t i = 0; i < vertexCount; ++i) out[i] = welded[weld.weldedOf[i]];
    return out;
}

}  // namespace preskin
