// Where the fragments that read a light grid can be: per froxel the part of it that the frame's
// surfaces (ClusterSurfaces, <preskin/ClusterGrid.h>) occupy, as an interval of view depths and a
// slab between two planes normal to the tile's mean surface normal. Both builds cut each light's
// sphere to these before their row and column tests, and list nothing in froxels no surface
// crosses: the "2.5D" culling of T. Harada ("A 2.5D Culling for Forward+", SIGGRAPH Asia 2012
// technical briefs), with intervals instead of a bit mask, plus the slab, which stays thin where a
// surface is seen at a slant and its depth interval is not.
//
// Per triangle, in the cluster camera: clipped to the near plane, projected to tiles, then to
// each tile it reaches (grown by how far a fragment may lie outside it): the part inside gives the
// depths and the extent along the axis of the slices it spans. On a plane, each view-space
// coordinate over w and 1 / w are affine in the image, so depth and dot(axis, p) are ratios of
// affine functions, whose extremes over a convex polygon lie at its corners: exact for the plane.
// A fragment's position is its triangle's plane at the pixel's centre, which with MSAA may lie
// outside the triangle (ClusterSurfaces::outsidePx; the rasterizer's snapping adds 1/64 pixel):
// the extents grow by that distance times a bound on how fast the plane's points move across the
// image there, and by kClusterDepthSlack. A plane seen edge-on (or passing the eye near the
// triangle) gives, without MSAA, the triangle's own extents grown by a twentieth (a fragment then
// interpolates its corners with weights in [0, 1], up to the snapping); with MSAA, the tile's
// whole depth. The slab's axis per tile: the triangles' normals turned towards the camera, summed
// weighted by area over every tile of each triangle's box (a first, rougher pass).
#pragma once

#include "lights/ClusterGeometry.h"

#include <preskin/ClusterGrid.h>

#include <glm/glm.hpp>

#include <vector>

namespace preskin {

// Where the surfaces are, laid out as the compute build reads it (one vec4 array):
//   values[f], f < froxels: (min depth, max depth, min along the axis, max along the axis); min
//     depth > max depth where there is no surface;
//   values[froxels + t], t < tiles (x fastest): the tile's slab axis (unit, view space) and w = 1,
//     or w = 0 where it has none.
// Besides, per slice and row the columns holding surfaces (a span), and per slice the rows
// (x > y: none), and a bit per froxel set where a surface is, so that a reader skips a span's
// empty froxels without reading them. A build writes each row's froxels within its span only
// (the CPU build reads nothing else); fillOutsideSpans() empties the rest, for a reader of the
// whole array.
struct FroxelSurfaces {
    std::vector<glm::vec4> values;
    glm::uvec3 dims{0u};
    std::vector<glm::uvec2> rowColumns;      // [slice * rows + row]
    std::vector<glm::uvec2> sliceRows;       // [slice]
    std::vector<uint64_t> occupiedBits;      // [(slice * rows + row) * wordsPerRow() + column / 64], bit column % 64
    std::vector<glm::vec3> viewScratch;      // the surfaces' vertices in view space (kept between builds)
    std::vector<glm::dvec4> clusterScratch;  // and in cluster coordinates (clip x, clip y, view depth, clip w)
    std::vector<std::vector<uint32_t>> bandScratch;  // triangles per chunk and band of rows (likewise)
    bool filled = false;                             // every froxel written (fillOutsideSpans)

    bool empty() const { return values.empty(); }
    size_t froxels() const { return size_t(dims.x) * dims.y * dims.z; }
    size_t wordsPerRow() const { return (size_t(dims.x) + 63) / 64; }
    // The bits of row `row` of slice `slice`.
    const uint64_t* occupiedRow(uint32_t slice, uint32_t row) const {
        return occupiedBits.data() + (size_t(slice) * dims.y + row) * wordsPerRow();
    }
    // A froxel within its row's span (x in rowColumns[z * rows + y]).
    const glm::vec4& spanExtent(size_t froxel) const { return values[froxel]; }
    // Any froxel (empty outside its row's span).
    glm::vec4 extent(size_t froxel) const;
    const glm::vec4& axis(size_t tile) const { return values[froxels() + tile]; }
    bool occupied(size_t froxel) const {
        const glm::vec4 e = extent(froxel);
        return e.x <= e.y;
    }
    void fillOutsideSpans();
};

// Fills `out` for this grid. Triangles with an index out of range or a non-finite corner are skipped.
void froxelSurfaces(const ClusterGridShape& shape, const ClusterCamera& camera, const ClusterSurfaces& surfaces,
                    FroxelSurfaces& out);

}  // namespace preskin
