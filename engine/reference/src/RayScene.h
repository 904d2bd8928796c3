// RayScene: the reference's ray queries on a ReferenceMesh through Embree 3 (libembree-dev): the
// closest accepted hit along a ray (a caller's filter rejects hits the rasterizer would not see:
// culled back faces, alpha-masked texels), any-hit occlusion for shadow rays (every triangle
// occludes, like the shadow pass), and the triangles within a radius of a point (Embree's point
// query, then an exact point-triangle distance; returned sorted by index so results never depend
// on the BVH's traversal order).
// Limits: Embree works in single precision (positions are rounded to float); the BVH is built
// once (no deformation). The device runs Embree's own threads for the build only.
#pragma once

#include "ReferenceMesh.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

namespace preskin::reference {

struct RayHit {
    SurfacePoint point;
    double distance = 0.0;  // along the (unit) direction
};

class RayScene {
public:
    // accept(triangle, bary, direction): whether a candidate hit counts for `intersect`.
    using HitFilter = std::function<bool(uint32_t, const glm::dvec3&, const glm::dvec3&)>;

    RayScene(const ReferenceMesh& mesh, HitFilter filter);
    ~RayScene();
    RayScene(const RayScene&) = delete;
    RayScene& operator=(const RayScene&) = delete;

    std::optional<RayHit> intersect(const glm::dvec3& origin, const glm::dvec3& direction) const;
    // Whether anything lies along origin + t direction for t in (tNear, tFar).
    bool occluded(const glm::dvec3& origin, const glm::dvec3& direction, double tNear, double tFar) const;
    // Triangles for which keep(triangle) holds and whose closest point is within radius of p,
    // in ascending order.
    void trianglesWithin(const glm::dvec3& p, double radius, const std::function<bool(uint32_t)>& keep,
                         std::vector<uint32_t>& out) const;

    const HitFilter& filter() const { return filter_; }
    const ReferenceMesh& mesh() const { return mesh_; }

private:
    const ReferenceMesh& mesh_;
    HitFilter filter_;
    void* device_ = nullptr;  // RTCDevice
    void* scene_ = nullptr;   // RTCScene
};

// Distance from p to the triangle (a, b, c), exact (closest point by Voronoi regions, Ericson,
// Real-Time Collision Detection, 5.1.5).
double pointTriangleDistance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);

}  // namespace preskin::reference
