// SurfaceIntegral: I(x) = int_S Rn(k |x - y|) E(y) k^2 dA(y) over the skin triangles within the
// profile's reach of x, for the diffusion reference. Rn is the profile divided by its albedo
// (1/mm^2), k converts world metres to profile millimetres (1000 times the scatter scale).
//
// Quadrature (graded, deterministic):
//  1. Candidate triangles: those within the reach of x (RayScene::trianglesWithin), in index order.
//  2. Irradiance pieces: each triangle is split 4-way (midpoints, on a per-triangle lattice of
//     2^15 steps per edge) while a piece is larger than max(leafRatio * its distance to x,
//     finestMm); pieces beyond the reach, or whose largest possible contribution
//     (Rn at their distance times their area) is below 1e-3 momentTolerance, are dropped.
//  3. On a piece, E is the linear interpolation of E at its corners; E at a lattice point is a
//     pure function of the point, computed once per thread (IrradianceCache).
//  4. The piece's profile moments M_j = int Rn beta_j dA (beta_j its barycentric basis) are
//     integrated with Dunavant's degree-5 seven-point rule (Dunavant, "High degree efficient
//     symmetrical Gaussian quadrature rules for the triangle", IJNME 1985), adaptively: a
//     sub-triangle is split 4-way while the children's sum differs from its own estimate by more
//     than momentTolerance (up to 12 levels), which resolves the narrow Gaussians and Burley's
//     1/r peak at x; the piece contributes sum_j M_j E_j.
// The error sources (truncation at the reach, E linear over pieces, the moment tolerance) are
// measured in docs/reference.md.
#pragma once

#include "IrradianceField.h"
#include "RayScene.h"
#include "ReferenceMesh.h"

#include <preskin/DiffusionProfile.h>

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <functional>
#include <unordered_map>
#include <vector>

namespace preskin::reference {

// Rn(r) = R(r) / albedo per channel, 1/mm^2; r in mm (clamped away from 0 for Burley's 1/r).
// Sums of Gaussians are evaluated here with the normalisation folded into each term's weight,
// skipping terms below e^-40 of their peak (the integral sees them as zero anyway).
class ProfileKernel {
public:
    explicit ProfileKernel(const DiffusionProfile& profile);
    glm::dvec3 operator()(double rMm) const;
    // The largest channel at r: the profile decreases with r, so this bounds it beyond r.
    double bound(double rMm) const;

private:
    struct Term {
        glm::dvec3 weight;  // w / (albedo 2 pi v)
        double negHalfInvVariance;
    };
    const DiffusionProfile& profile_;
    glm::dvec3 invAlbedo_;
    std::vector<Term> terms_;  // sums of Gaussians only
};

// E at lattice points, per thread; values are pure functions of the key, so caching never
// changes a result.
class IrradianceCache {
public:
    const IrradianceSample& get(uint64_t key, const std::function<IrradianceSample()>& compute, uint32_t& misses);

private:
    std::unordered_map<uint64_t, IrradianceSample> map_;
};

// E at every corner of every skin triangle (lattice level 0), computed up front on all cores:
// most pieces far from x are whole triangles, so this is where the integral reads most.
class CornerIrradiance {
public:
    CornerIrradiance(const ReferenceMesh& mesh, const IrradianceField& irradiance,
                     const std::function<bool(uint32_t)>& isSkinTriangle,
                     const std::function<bool(uint32_t)>& isDoubleSidedTriangle);
    const IrradianceSample& at(uint32_t triangle, int corner, bool flip) const {
        return (flip ? flipped_ : front_)[3 * size_t(triangle) + size_t(corner)];
    }

private:
    std::vector<IrradianceSample> front_;
    std::vector<IrradianceSample> flipped_;  // filled only for double-sided skin materials
};

struct SurfaceIntegralSettings {
    double reachMm = 10.0;
    double leafRatio = 0.5;
    double finestMm = 0.08;
    double momentTolerance = 1e-7;
};

struct SurfaceIntegralResult {
    glm::dvec3 value{0.0};  // int Rn E dA, in irradiance units
    uint32_t irradianceSamples = 0;
};

class SurfaceIntegral {
public:
    SurfaceIntegral(const ReferenceMesh& mesh, const RayScene& rays, const IrradianceField& irradiance,
                    std::function<bool(uint32_t)> isSkinTriangle, std::function<bool(uint32_t)> isDoubleSidedTriangle,
                    const DiffusionProfile& profile, const SurfaceIntegralSettings& settings);

    // x on the surface; mmPerM = 1000 * scatter scale of x's material; flipNormals: x is seen from
    // the back of a double-sided surface (E is then taken on that side everywhere).
    SurfaceIntegralResult integrate(const glm::dvec3& x, double mmPerM, bool flipNormals, IrradianceCache& cache) const;

private:
    struct Context;
    void visitPiece(Context& c, uint32_t triangle, const std::array<glm::ivec2, 3>& lattice, int level) const;
    std::array<glm::dvec3, 3> pieceMoments(const Context& c, const std::array<glm::dvec3, 3>& corners) const;

    const ReferenceMesh& mesh_;
    const RayScene& rays_;
    const IrradianceField& irradiance_;
    std::function<bool(uint32_t)> isSkin_;
    CornerIrradiance corners_;
    ProfileKernel kernel_;
    SurfaceIntegralSettings settings_;
};

}  // namespace preskin::reference
