#include "support/TestScenes.h"

#include <cmath>

namespace preskin::test {

Primitive makeSphere(float radiusM, uint32_t segments, uint32_t rings) {
    Primitive p;
    const float pi = 3.14159265358979f;
    for (uint32_t r = 0; r <= rings; ++r) {
        const float theta = pi * float(r) / float(rings);
        for (uint32_t s = 0; s <= segments; ++s) {
            const float phi = 2.0f * pi * float(s) / float(segments);
            Vertex v;
            v.normalOs = glm::vec3(std::sin(theta) * std::sin(phi), std::cos(theta), std::sin(theta) * std::cos(phi));
            v.positionOs = v.normalOs * radiusM;
            v.tangentOs = glm::vec4(std::cos(phi), 0.0f, -std::sin(phi), 1.0f);
            v.uv0 = glm::vec2(float(s) / float(segments), float(r) / float(rings));
            v.curvaturePerM = 1.0f / radiusM;
            p.vertices.push_back(v);
            p.boundsOs.extend(v.positionOs);
        }
    }
    for (uint32_t r = 0; r < rings; ++r)
        for (uint32_t s = 0; s < segments; ++s) {
            const uint32_t a = r * (segments + 1) + s;
            const uint32_t b = a + segments + 1;
            // Counter-clockwise seen from outside.
            p.indices.insert(p.indices.end(), {a, b, a + 1, a + 1, b, b + 1});
        }
    return p;
}

Primitive makeQuad(float sizeM, uint32_t n) {
    Primitive p;
    for (uint32_t y = 0; y <= n; ++y)
        for (uint32_t x = 0; x <= n; ++x) {
            Vertex v;
            v.uv0 = glm::vec2(float(x) / float(n), float(y) / float(n));
            v.positionOs = glm::vec3((v.uv0.x - 0.5f) * sizeM, (0.5f - v.uv0.y) * sizeM, 0.0f);
            v.normalOs = glm::vec3(0.0f, 0.0f, 1.0f);
            v.tangentOs = glm::vec4(1.0f, 0.0f, 0.0f, 1.0f);
            p.vertices.push_back(v);
            p.boundsOs.extend(v.positionOs);
        }
    for (uint32_t y = 0; y < n; ++y)
        for (uint32_t x = 0; x < n; ++x) {
            const uint32_t a = y * (n + 1) + x;
            const uint32_t b = a + n + 1;
            p.indices.insert(p.indices.end(), {a, b, a + 1, a + 1, b, b + 1});
        }
    return p;
}

Primitive makeBox(const glm::vec3& sizeM) {
    Primitive p;
    const glm::vec3 h = 0.5f * sizeM;
    const glm::vec3 normals[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (const glm::vec3& n : normals) {
        const glm::vec3 t =
            std::abs(n.y) > 0.5f ? glm::vec3(1, 0, 0) : glm::normalize(glm::cross(glm::vec3(0, 1, 0), n));
        const glm::vec3 b = glm::cross(n, t);
        const uint32_t base = static_cast<uint32_t>(p.vertices.size());
        const glm::vec2 corners[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
        for (const glm::vec2& c : corners) {
            Vertex v;
            v.positionOs = (n + t * c.x + b * c.y) * h;
            v.normalOs = n;
            v.tangentOs = glm::vec4(t, 1.0f);
            v.uv0 = 0.5f * (c + 1.0f);
            p.vertices.push_back(v);
            p.boundsOs.extend(v.positionOs);
        }
        p.indices.insert(p.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
    return p;
}

Material skinMaterial(const glm::vec3& albedo, float scatterScale) {
    Material m;
    m.baseColorFactor = glm::vec4(albedo, 1.0f);
    m.metallicFactor = 0.0f;
    m.skin = SkinMaterial{};
    m.skin->scatterScale = scatterScale;
    return m;
}

Scene makeScene(const std::vector<std::pair<Primitive, glm::mat4>>& parts, const std::vector<Material>& materials) {
    Scene scene;
    scene.materials = materials;
    for (const auto& [primitive, transform] : parts) {
        Mesh mesh;
        mesh.primitives.push_back(primitive);
        scene.instances.push_back({static_cast<int>(scene.meshes.size()), transform, ""});
        scene.meshes.push_back(std::move(mesh));
    }
    return scene;
}

}  // namespace preskin::test
