// ReferenceMesh: every mesh instance of a Scene flattened into one world-space triangle list in
// double precision, the surface the diffusion reference integrates over: triangle positions,
// vertex normals (normalWorldFromObject, renormalised), TEXCOORD_0 and the signed mean
// curvature (Vertex::curvaturePerM divided by the instance's curvature scale, as forward.vert
// does). Triangles keep their material index (the scene's default material is
// Scene::materials.size()).
// Limits: no deformation (the static pose, like the loader); degenerate triangles are kept (they
// integrate to nothing).
#pragma once

#include <preskin/Scene.h>

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace preskin::reference {

struct MeshTriangle {
    std::array<uint32_t, 3> v{};
    uint32_t material = 0;
};

// A point on a triangle: barycentric weights of its corners 0, 1, 2 (they sum to 1).
struct SurfacePoint {
    uint32_t triangle = 0;
    glm::dvec3 bary{1.0, 0.0, 0.0};
};

struct ReferenceMesh {
    std::vector<glm::dvec3> positionsWs;
    std::vector<glm::dvec3> normalsWs;
    std::vector<glm::dvec2> uvs;
    std::vector<double> curvaturePerM;  // signed mean curvature in world 1/m (> 0 convex)
    std::vector<MeshTriangle> triangles;

    static ReferenceMesh fromScene(const Scene& scene);

    std::array<glm::dvec3, 3> corners(uint32_t triangle) const;
    glm::dvec3 position(const SurfacePoint& p) const;
    glm::dvec3 normal(const SurfacePoint& p) const;  // interpolated, unit length
    glm::dvec2 uv(const SurfacePoint& p) const;
    double curvature(const SurfacePoint& p) const;
    // Unit normal of the triangle's plane from its winding (counter-clockwise front faces).
    glm::dvec3 faceNormal(uint32_t triangle) const;
};

}  // namespace preskin::reference
