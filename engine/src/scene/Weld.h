// Welding a triangle mesh's vertices for per-vertex estimates that must not break at seams: one
// welded id per (exact position, normal hemisphere), so vertices duplicated along UV or normal
// seams share an id while the two sides of a hard edge or a double-sided sheet (normals more than
// 90 degrees apart) stay separate. Used by computeVertexCurvature and, for the GPU curvature pass
// of deformed meshes, by the renderer's deformer, so both weld alike.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace preskin {

struct WeldedVertices {
    std::vector<uint32_t> weldedOf;  // per vertex
    uint32_t weldedCount = 0;
};

// `normals` need not be unit length; zero or non-finite ones weld with any normal.
WeldedVertices weldVertices(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals);

}  // namespace preskin
