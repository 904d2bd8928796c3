// Flattening a Scene into the reference's world-space triangle list (see ReferenceMesh.h).
#include "ReferenceMesh.h"

#include <glm/gtc/matrix_inverse.hpp>

#include <cmath>

namespace preskin::reference {

ReferenceMesh ReferenceMesh::fromScene(const Scene& scene) {
    ReferenceMesh mesh;
    const uint32_t defaultMaterial = static_cast<uint32_t>(scene.materials.size());
    for (const MeshInstance& instance : scene.instances) {
        if (instance.mesh < 0 || static_cast<size_t>(instance.mesh) >= scene.meshes.size()) continue;
        const glm::dmat4 worldFromObject(instance.worldFromObject);
        const glm::dmat3 normalFromObject = glm::inverseTranspose(glm::dmat3(worldFromObject));
        const double curvatureScale = instance.curvatureScale();
        const double curvatureToWorld = curvatureScale > 0.0 ? 1.0 / curvatureScale : 1.0;
        for (const Primitive& primitive : scene.meshes[static_cast<size_t>(instance.mesh)].primitives) {
            const auto base = static_cast<uint32_t>(mesh.positionsWs.size());
            for (const Vertex& v : primitive.vertices) {
                mesh.positionsWs.emplace_back(worldFromObject * glm::dvec4(glm::dvec3(v.positionOs), 1.0));
                const glm::dvec3 n = normalFromObject * glm::dvec3(v.normalOs);
                const double len = glm::length(n);
                mesh.normalsWs.push_back(len > 0.0 ? n / len : glm::dvec3(0.0, 0.0, 1.0));
                mesh.uvs.emplace_back(v.uv0);
                mesh.curvaturePerM.push_back(double(v.curvaturePerM) * curvatureToWorld);
            }
            const uint32_t material =
                primitive.material >= 0 && static_cast<size_t>(primitive.material) < scene.materials.size()
                ? static_cast<uint32_t>(primitive.material)
                : defaultMaterial;
            for (size_t i = 0; i + 2 < primitive.indices.size(); i += 3)
                mesh.triangles.push_back(
                    {{base + primitive.indices[i], base + primitive.indices[i + 1], base + primitive.indices[i + 2]},
                     material});
        }
    }
    return mesh;
}

std::array<glm::dvec3, 3> ReferenceMesh::corners(uint32_t triangle) const {
    const MeshTriangle& t = triangles[triangle];
    return {positionsWs[t.v[0]], positionsWs[t.v[1]], positionsWs[t.v[2]]};
}

glm::dvec3 ReferenceMesh::position(const SurfacePoint& p) const {
    const MeshTriangle& t = triangles[p.triangle];
    return p.bary.x * positionsWs[t.v[0]] + p.bary.y * positionsWs[t.v[1]] + p.bary.z * positionsWs[t.v[2]];
}

glm::dvec3 ReferenceMesh::normal(const SurfacePoint& p) const {
    const MeshTriangle& t = triangles[p.triangle];
    const glm::dvec3 n = p.bary.x * normalsWs[t.v[0]] + p.bary.y * normalsWs[t.v[1]] + p.bary.z * normalsWs[t.v[2]];
    const double len = glm::length(n);
    return len > 0.0 ? n / len : faceNormal(p.triangle);
}

glm::dvec2 ReferenceMesh::uv(const SurfacePoint& p) const {
    const MeshTriangle& t = triangles[p.triangle];
    return p.bary.x * uvs[t.v[0]] + p.bary.y * uvs[t.v[1]] + p.bary.z * uvs[t.v[2]];
}

double ReferenceMesh::curvature(const SurfacePoint& p) const {
    const MeshTriangle& t = triangles[p.triangle];
    return p.bary.x * curvaturePerM[t.v[0]] + p.bary.y * curvaturePerM[t.v[1]] + p.bary.z * curvaturePerM[t.v[2]];
}

glm::dvec3 ReferenceMesh::faceNormal(uint32_t triangle) const {
    const auto c = corners(triangle);
    const glm::dvec3 n = glm::cross(c[1] - c[0], c[2] - c[0]);
    const double len = glm::length(n);
    return len > 0.0 ? n / len : glm::dvec3(0.0, 0.0, 1.0);
}

}  // namespace preskin::reference
