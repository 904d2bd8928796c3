#include "support/TestScenes.h"

#include <cmath>

namespace preskin::test {

namespace {

// Two triangles per cell of a (rows + 1) x (columns + 1) vertex grid, row-major; `flip` reverses
// the winding.
void appendGridTriangles(Primitive& p, uint32_t rows, uint32_t columns, bool flip) {
    for (uint32_t r = 0; r < rows; ++r)
        for (uint32_t s = 0; s < columns; ++s) {
            const uint32_t a = r * (columns + 1) + s;
            const uint32_t b = a + columns + 1;
            if (flip)
                p.indices.insert(p.indices.end(), {a, a + 1, b, a + 1, b + 1, b});
            else
                p.indices.insert(p.indices.end(), {a, b, a + 1, a + 1, b, b + 1});
        }
}

}  // namespace

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
    appendGridTriangles(p, rings, segments, false);  // counter-clockwise seen from outside
    return p;
}

Primitive makeTorus(float majorM, float minorM, uint32_t segments, uint32_t rings) {
    Primitive p;
    const float pi = 3.14159265358979f;
    for (uint32_t r = 0; r <= rings; ++r) {
        const float theta = 2.0f * pi * float(r) / float(rings);  // around the tube
        for (uint32_t s = 0; s <= segments; ++s) {
            const float phi = 2.0f * pi * float(s) / float(segments);  // around the axis
            const glm::vec3 radial(std::sin(phi), 0.0f, std::cos(phi));
            Vertex v;
            v.normalOs = std::cos(theta) * radial + std::sin(theta) * glm::vec3(0.0f, 1.0f, 0.0f);
            v.positionOs = majorM * radial + minorM * v.normalOs;
            v.tangentOs = glm::vec4(std::cos(phi), 0.0f, -std::sin(phi), 1.0f);
            v.uv0 = glm::vec2(float(s) / float(segments), float(r) / float(rings));
            p.vertices.push_back(v);
            p.boundsOs.extend(v.positionOs);
        }
    }
    appendGridTriangles(p, rings, segments, true);  // its rings run the other way round: counter-clockwise outside
    return p;
}

Primitive makeCylinder(float radiusM, float lengthM, uint32_t around, uint32_t along) {
    Primitive p;
    const float pi = 3.14159265358979f;
    for (uint32_t r = 0; r <= along; ++r)
        for (uint32_t s = 0; s <= around; ++s) {
            const float theta = 2.0f * pi * float(s) / float(around);
            Vertex v;
            v.normalOs = glm::vec3(0.0f, std::sin(theta), std::cos(theta));
            v.positionOs = glm::vec3((float(r) / float(along) - 0.5f) * lengthM, 0.0f, 0.0f) + radiusM * v.normalOs;
            v.tangentOs = glm::vec4(1.0f, 0.0f, 0.0f, 1.0f);
            v.uv0 = glm::vec2(float(s) / float(around), float(r) / float(along));
            p.vertices.push_back(v);
            p.boundsOs.extend(v.positionOs);
        }
    appendGridTriangles(p, along, around, false);  // counter-clockwise seen from outside
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
    appendGridTriangles(p, n, n, false);
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
