// The diffusion reference's surface integral: graded irradiance pieces and adaptive profile
// moments (see SurfaceIntegral.h).
#include "SurfaceIntegral.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace preskin::reference {
namespace {

constexpr int kLatticeBits = 15;
constexpr int kLatticeSteps = 1 << kLatticeBits;  // lattice steps per triangle edge
constexpr int kMaxMomentDepth = 12;
constexpr size_t kCacheLimit = size_t(1) << 16;
constexpr double kSmoothRatio = 1.5;

// Dunavant's degree-5 rule: barycentric nodes and weights (summing to 1).
struct RuleNode {
    glm::dvec3 lambda;
    double weight;
};
constexpr double kA1 = 0.059715871789770, kB1 = 0.470142064105115, kW1 = 0.132394152788506;
constexpr double kA2 = 0.797426985353087, kB2 = 0.101286507323456, kW2 = 0.125939180544827;
const std::array<RuleNode, 7> kRule{{
    {{1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0}, 0.225},
    {{kA1, kB1, kB1}, kW1},
    {{kB1, kA1, kB1}, kW1},
    {{kB1, kB1, kA1}, kW1},
    {{kA2, kB2, kB2}, kW2},
    {{kB2, kA2, kB2}, kW2},
    {{kB2, kB2, kA2}, kW2},
}};

using Moments = std::array<glm::dvec3, 3>;

Moments operator+(const Moments& a, const Moments& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }

double maxDifference(const Moments& a, const Moments& b) {
    double m = 0.0;
    for (size_t j = 0; j < 3; ++j) {
        const glm::dvec3 d = glm::abs(a[j] - b[j]);
        m = std::max({m, d.x, d.y, d.z});
    }
    return m;
}

double triangleArea(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    return 0.5 * glm::length(glm::cross(b - a, c - a));
}

uint64_t latticeKey(uint32_t triangle, glm::ivec2 point, bool flip) {
    return (uint64_t(triangle) << 33) | (uint64_t(flip) << 32) | (uint64_t(uint32_t(point.x)) << 16) |
        uint64_t(uint32_t(point.y));
}

glm::dvec3 latticeBary(glm::ivec2 point) {
    const double u = double(point.x) / kLatticeSteps, v = double(point.y) / kLatticeSteps;
    return {1.0 - u - v, u, v};
}

}  // namespace

ProfileKernel::ProfileKernel(const DiffusionProfile& profile) : profile_(profile), invAlbedo_(1.0 / profile.albedo()) {
    for (const GaussianTerm& g : profile.gaussians())
        terms_.push_back(
            {g.weight * invAlbedo_ / (2.0 * 3.14159265358979323846 * g.varianceMm2), -0.5 / g.varianceMm2});
}

glm::dvec3 ProfileKernel::operator()(double rMm) const {
    if (terms_.empty()) return profile_.R(std::max(rMm, 1e-9)) * invAlbedo_;
    const double r2 = rMm * rMm;
    glm::dvec3 sum(0.0);
    for (const Term& t : terms_) {
        const double exponent = r2 * t.negHalfInvVariance;
        if (exponent > -40.0) sum += t.weight * std::exp(exponent);
    }
    return sum;
}

double ProfileKernel::bound(double rMm) const {
    const glm::dvec3 r = (*this)(rMm);
    return std::max({r.x, r.y, r.z});
}

const IrradianceSample& IrradianceCache::get(uint64_t key, const std::function<IrradianceSample()>& compute,
                                             uint32_t& misses) {
    if (map_.size() > kCacheLimit) map_.clear();
    auto it = map_.find(key);
    if (it != map_.end()) return it->second;
    ++misses;
    return map_.emplace(key, compute()).first->second;
}

CornerIrradiance::CornerIrradiance(const ReferenceMesh& mesh, const IrradianceField& irradiance,
                                   const std::function<bool(uint32_t)>& isSkinTriangle,
                                   const std::function<bool(uint32_t)>& isDoubleSidedTriangle)
    : front_(3 * mesh.triangles.size()), flipped_(3 * mesh.triangles.size()) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, mesh.triangles.size()), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t t = r.begin(); t != r.end(); ++t) {
            if (!isSkinTriangle(uint32_t(t))) continue;
            const bool doubleSided = isDoubleSidedTriangle(uint32_t(t));
            for (int k = 0; k < 3; ++k) {
                glm::dvec3 bary(0.0);
                bary[k] = 1.0;
                front_[3 * t + size_t(k)] = irradiance.at({uint32_t(t), bary}, false);
                if (doubleSided) flipped_[3 * t + size_t(k)] = irradiance.at({uint32_t(t), bary}, true);
            }
        }
    });
}

struct SurfaceIntegral::Context {
    glm::dvec3 x;
    double k;  // profile mm per world m
    bool flip;
    IrradianceCache* cache;
    SurfaceIntegralResult result;
};

SurfaceIntegral::SurfaceIntegral(const ReferenceMesh& mesh, const RayScene& rays, const IrradianceField& irradiance,
                                 std::function<bool(uint32_t)> isSkinTriangle,
                                 std::function<bool(uint32_t)> isDoubleSidedTriangle, const DiffusionProfile& profile,
                                 const SurfaceIntegralSettings& settings)
    : mesh_(mesh),
      rays_(rays),
      irradiance_(irradiance),
      isSkin_(std::move(isSkinTriangle)),
      corners_(mesh, irradiance, isSkin_, isDoubleSidedTriangle),
      kernel_(profile),
      settings_(settings) {}

SurfaceIntegralResult SurfaceIntegral::integrate(const glm::dvec3& x, double mmPerM, bool flipNormals,
                                                 IrradianceCache& cache) const {
    Context c{x, mmPerM, flipNormals, &cache, {}};
    std::vector<uint32_t> candidates;
    rays_.trianglesWithin(x, settings_.reachMm / mmPerM, isSkin_, candidates);
    const std::array<glm::ivec2, 3> root{glm::ivec2(0, 0), glm::ivec2(kLatticeSteps, 0), glm::ivec2(0, kLatticeSteps)};
    for (uint32_t t : candidates) visitPiece(c, t, root, 0);
    return c.result;
}

void SurfaceIntegral::visitPiece(Context& c, uint32_t triangle, const std::array<glm::ivec2, 3>& lattice,
                                 int level) const {
    std::array<glm::dvec3, 3> p;
    for (size_t i = 0; i < 3; ++i) p[i] = mesh_.position({triangle, latticeBary(lattice[i])});
    const double distanceMm = pointTriangleDistance(c.x, p[0], p[1], p[2]) * c.k;
    if (distanceMm > settings_.reachMm) return;
    const double areaMm2 = triangleArea(p[0], p[1], p[2]) * c.k * c.k;
    if (kernel_.bound(distanceMm) * areaMm2 <= 1e-3 * settings_.momentTolerance) return;
    const double sizeMm =
        std::max({glm::length(p[1] - p[0]), glm::length(p[2] - p[1]), glm::length(p[0] - p[2])}) * c.k;
    if (level < kLatticeBits && sizeMm > std::max(settings_.leafRatio * distanceMm, settings_.finestMm)) {
        const glm::ivec2 m01 = (lattice[0] + lattice[1]) / 2, m12 = (lattice[1] + lattice[2]) / 2,
                         m20 = (lattice[2] + lattice[0]) / 2;
        visitPiece(c, triangle, {lattice[0], m01, m20}, level + 1);
        visitPiece(c, triangle, {m01, lattice[1], m12}, level + 1);
        visitPiece(c, triangle, {m20, m12, lattice[2]}, level + 1);
        visitPiece(c, triangle, {m01, m12, m20}, level + 1);
        return;
    }
    const Moments moments = pieceMoments(c, p);
    for (size_t i = 0; i < 3; ++i) {
        const int corner = lattice[i] == glm::ivec2(0, 0) ? 0
            : lattice[i] == glm::ivec2(kLatticeSteps, 0)  ? 1
            : lattice[i] == glm::ivec2(0, kLatticeSteps)  ? 2
                                                          : -1;
        const SurfacePoint point{triangle, latticeBary(lattice[i])};
        const IrradianceSample& e = corner >= 0
            ? corners_.at(triangle, corner, c.flip)
            : c.cache->get(
                  latticeKey(triangle, lattice[i], c.flip), [&] { return irradiance_.at(point, c.flip); },
                  c.result.irradianceSamples);
        c.result.value += moments[i] * e.irradiance;
    }
}

std::array<glm::dvec3, 3> SurfaceIntegral::pieceMoments(const Context& c,
                                                        const std::array<glm::dvec3, 3>& corners) const {
    // Sub-triangles are given by their corners' barycentric coordinates in the piece.
    using Sub = std::array<glm::dvec3, 3>;
    const double pieceAreaMm2 = triangleArea(corners[0], corners[1], corners[2]) * c.k * c.k;
    auto rule = [&](const Sub& s, double areaMm2) {
        Moments m{glm::dvec3(0.0), glm::dvec3(0.0), glm::dvec3(0.0)};
        for (const RuleNode& q : kRule) {
            const glm::dvec3 b = q.lambda.x * s[0] + q.lambda.y * s[1] + q.lambda.z * s[2];
            const glm::dvec3 y = b.x * corners[0] + b.y * corners[1] + b.z * corners[2];
            const glm::dvec3 r = kernel_(glm::length(y - c.x) * c.k) * (q.weight * areaMm2);
            m[0] += r * b.x;
            m[1] += r * b.y;
            m[2] += r * b.z;
        }
        return m;
    };
    auto children = [](const Sub& s) {
        const glm::dvec3 m01 = 0.5 * (s[0] + s[1]), m12 = 0.5 * (s[1] + s[2]), m20 = 0.5 * (s[2] + s[0]);
        return std::array<Sub, 4>{Sub{s[0], m01, m20}, Sub{m01, s[1], m12}, Sub{m20, m12, s[2]}, Sub{m01, m12, m20}};
    };
    auto refine = [&](auto&& self, const Sub& s, const Moments& estimate, double areaMm2, int depth) -> Moments {
        const glm::dvec3 a = s[0].x * corners[0] + s[0].y * corners[1] + s[0].z * corners[2];
        const glm::dvec3 b = s[1].x * corners[0] + s[1].y * corners[1] + s[1].z * corners[2];
        const glm::dvec3 d = s[2].x * corners[0] + s[2].y * corners[1] + s[2].z * corners[2];
        const double nearMm = pointTriangleDistance(c.x, a, b, d) * c.k;
        const double nearValue = kernel_.bound(nearMm);
        if (nearValue * areaMm2 <= 1e-3 * settings_.momentTolerance) return estimate;
        // Where the profile changes by less than kSmoothRatio over the sub-triangle (its value at
        // the nearest point over the farthest corner's, in every channel), the degree-5 rule is
        // exact to far below the tolerance: no children needed.
        const double farMm = std::max({glm::length(a - c.x), glm::length(b - c.x), glm::length(d - c.x)}) * c.k;
        const glm::dvec3 nearRgb = kernel_(nearMm), farRgb = kernel_(farMm);
        if (glm::all(glm::lessThanEqual(nearRgb, kSmoothRatio * farRgb))) return estimate;
        const auto parts = children(s);
        std::array<Moments, 4> q;
        for (size_t i = 0; i < 4; ++i) q[i] = rule(parts[i], 0.25 * areaMm2);
        const Moments sum = q[0] + q[1] + q[2] + q[3];
        if (depth >= kMaxMomentDepth || maxDifference(sum, estimate) <= settings_.momentTolerance) return sum;
        Moments total{glm::dvec3(0.0), glm::dvec3(0.0), glm::dvec3(0.0)};
        for (size_t i = 0; i < 4; ++i) total = total + self(self, parts[i], q[i], 0.25 * areaMm2, depth + 1);
        return total;
    };
    const Sub whole{glm::dvec3(1.0, 0.0, 0.0), glm::dvec3(0.0, 1.0, 0.0), glm::dvec3(0.0, 0.0, 1.0)};
    return refine(refine, whole, rule(whole, pieceAreaMm2), pieceAreaMm2, 0);
}

}  // namespace preskin::reference
