// Geometry of the froxel grid in view space, shared by the CPU build and (uploaded) the compute
// build: the tile boundary planes, the slice boundary depths and the tile corner lines.
//   - Column boundary i (i = 0 .. dims.x) is the plane through the pixel edge x = min(i * tile,
//     width) for every depth; row boundaries likewise. Planes are stored as (n, w), |n| = 1,
//     with n . p + w > 0 on the side of the higher tile index. Pixel edges (not centres) make
//     every tile half a pixel wider on each side than the fragments the shader puts into it.
//   - Corner lines: the view-space point of grid vertex (i, j) at view depth d is
//     origin + direction * d (exact for perspective and orthographic projections).
// Computed in double precision from the inverse projection, so any projection matrix of the
// usual form (no x/y terms in its depth row) works, off-centre and orthographic ones included.
#pragma once

#include <preskin/ClusterGrid.h>

#include <glm/glm.hpp>

#include <span>
#include <vector>

namespace preskin {

struct ClusterGeometry {
    ClusterGridShape shape;
    std::vector<glm::vec4> xPlanes;       // dims.x + 1
    std::vector<glm::vec4> yPlanes;       // dims.y + 1
    std::vector<float> sliceStartM;       // dims.z + 1; the last entry is +infinity
    std::vector<glm::vec4> cornerOrigin;  // (dims.x + 1) * (dims.y + 1), x fastest; w unused
    std::vector<glm::vec4> cornerDir;     // same layout
    glm::dmat4 clipFromView{1.0};         // the cluster camera's projection

    // The columns (axis 0) or rows (axis 1) whose slabs a view-space sphere may overlap, from
    // its projection (the tangents from the eye, or its extent for an orthographic camera) grown
    // by a tile: a range to test the slabs in instead of all of them. False when no such range
    // is known (a sphere reaching the eye's plane, an unusual projection): test them all.
    bool sphereTiles(int axis, const glm::vec3& center, float radius, uint32_t& lo, uint32_t& hi) const;

    uint32_t cornerIndex(uint32_t i, uint32_t j) const { return j * (shape.dims.x + 1) + i; }
};

struct ClusterLight;

// clusterGridShape (<preskin/ClusterGrid.h>) from the local lights as the grid bounds them.
ClusterGridShape clusterGridShape(const ClusterSettings& settings, const ClusterCamera& camera,
                                  const Bounds& sceneBounds, std::span<const ClusterLight> lights);

// `camera` is the cluster camera's eye (ClusterCamera::eye).
ClusterGeometry clusterGeometry(const ClusterGridShape& shape, const Eye& camera);
// The same into `out`, reusing its memory (a renderer's grid every frame).
void clusterGeometry(const ClusterGridShape& shape, const Eye& camera, ClusterGeometry& out);

// Relative growth applied to slice boundaries and light bounds so that float rounding (here and
// in the shader's slice formula) never drops a light at a boundary. Used by both builds.
inline constexpr float kClusterDepthSlack = 1e-4f;
inline constexpr float kClusterRadiusSlack = 1e-4f;
// Spot cones are widened by this much in cosine, for the same reason.
inline constexpr float kClusterConeSlack = 1e-4f;

}  // namespace preskin
