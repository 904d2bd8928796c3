// Where the fragments that read a light grid can be: per froxel the interval of view depths that
// the frame's surfaces (ClusterSurfaces, <preskin/ClusterGrid.h>) occupy inside it. Both builds
// then test a light against that interval instead of the froxel's whole slice, and list nothing
// in froxels no surface crosses (the "2.5D" culling of T. Harada, "A 2.5D Culling for Forward+",
// SIGGRAPH Asia 2012 technical briefs, with an interval instead of a bit mask).
//
// Per triangle, in the cluster camera: clipped to the near plane, projected to pixels; every tile
// that its pixel box meets and no edge of it separates gets the depth range of the triangle's
// plane over that part of the tile. On a plane both depth / w and 1 / w are affine in the image,
// so depth is a ratio of two affine functions, whose extremes over a rectangle lie at its
// corners: exact for the plane. A fragment's position is its triangle's plane at the pixel's
// centre, which with MSAA may lie outside the triangle (a pixel it covers in part): the boxes are
// grown by a pixel for that, and depths by kClusterDepthSlack on both ends. A plane seen edge-on
// (or passing the eye near the triangle) gives its tiles their whole depth.
#pragma once

#include "lights/ClusterGeometry.h"

#include <preskin/ClusterGrid.h>

#include <glm/glm.hpp>

#include <vector>

namespace preskin {

// An empty band: no surface in the froxel.
inline constexpr glm::vec2 kEmptyBand{3.0e38f, -3.0e38f};

// Fills `bands` (one per froxel, x fastest, then y, then z) with the view-depth interval
// [min, max] the surfaces occupy in each froxel, kEmptyBand where they occupy none. Triangles
// with an index out of range or a non-finite corner are skipped.
void froxelDepthBands(const ClusterGridShape& shape, const ClusterCamera& camera, const ClusterSurfaces& surfaces,
                      std::vector<glm::vec2>& bands);

}  // namespace preskin
