// Flat normals and per-vertex tangent frames (see TangentFrames.h for the method and its limits).
#include "scene/TangentFrames.h"

#include <algorithm>
#include <cmath>

namespace preskin::scene {

glm::vec3 anyPerpendicular(const glm::vec3& n) {
    // Cross with the axis least aligned with n.
    const glm::vec3 a = glm::abs(n);
    const glm::vec3 axis = (a.x <= a.y && a.x <= a.z) ? glm::vec3(1, 0, 0)
        : (a.y <= a.z)                                ? glm::vec3(0, 1, 0)
                                                      : glm::vec3(0, 0, 1);
    return glm::normalize(glm::cross(n, axis));
}

void makeFlatNormals(Primitive& primitive) {
    std::vector<Vertex> flat;
    flat.reserve(primitive.indices.size());
    for (size_t t = 0; t + 2 < primitive.indices.size(); t += 3) {
        Vertex v[3] = {primitive.vertices[primitive.indices[t]], primitive.vertices[primitive.indices[t + 1]],
                       primitive.vertices[primitive.indices[t + 2]]};
        const glm::vec3 areaNormal = glm::cross(v[1].positionOs - v[0].positionOs, v[2].positionOs - v[0].positionOs);
        const float len = glm::length(areaNormal);
        const glm::vec3 n = (len > 0.0f && std::isfinite(len)) ? areaNormal / len : glm::vec3(0, 0, 1);
        for (Vertex& vertex : v) {
            vertex.normalOs = n;
            flat.push_back(vertex);
        }
    }
    primitive.vertices = std::move(flat);
    // Morph deltas and joint influences follow their vertices (flat vertex i was indices[i]).
    auto split = [&](auto& perVertex) {
        if (perVertex.empty()) return;
        std::remove_reference_t<decltype(perVertex)> out;
        out.reserve(primitive.indices.size());
        for (uint32_t source : primitive.indices) out.push_back(perVertex[source]);
        perVertex = std::move(out);
    };
    for (MorphTarget& target : primitive.targets) {
        split(target.positionDeltas);
        split(target.normalDeltas);
        split(target.tangentDeltas);
    }
    split(primitive.influences);
    primitive.indices.resize(primitive.vertices.size());
    for (size_t i = 0; i < primitive.indices.size(); ++i) primitive.indices[i] = static_cast<uint32_t>(i);
}

namespace {

float cornerAngle(const glm::vec3& a, const glm::vec3& b) {
    const float la = glm::length(a), lb = glm::length(b);
    if (!(la > 0.0f) || !(lb > 0.0f)) return 0.0f;
    return std::acos(std::clamp(glm::dot(a, b) / (la * lb), -1.0f, 1.0f));
}

glm::vec3 projectToPlane(const glm::vec3& v, const glm::vec3& n) { return v - n * glm::dot(n, v); }

}  // namespace

size_t generateTangents(Primitive& primitive) {
    const size_t n = primitive.vertices.size();
    std::vector<glm::vec3> tangentSum(n, glm::vec3(0.0f));
    std::vector<glm::vec3> bitangentSum(n, glm::vec3(0.0f));  // toward decreasing glTF v

    for (size_t t = 0; t + 2 < primitive.indices.size(); t += 3) {
        const uint32_t idx[3] = {primitive.indices[t], primitive.indices[t + 1], primitive.indices[t + 2]};
        const Vertex& v0 = primitive.vertices[idx[0]];
        const Vertex& v1 = primitive.vertices[idx[1]];
        const Vertex& v2 = primitive.vertices[idx[2]];
        const glm::vec3 e1 = v1.positionOs - v0.positionOs, e2 = v2.positionOs - v0.positionOs;
        const glm::vec2 d1 = v1.uv0 - v0.uv0, d2 = v2.uv0 - v0.uv0;
        const float det = d1.x * d2.y - d2.x * d1.y;
        const float uvScale = std::max(glm::dot(d1, d1), glm::dot(d2, d2));
        if (!(std::abs(det) > 1e-7f * uvScale) || !std::isfinite(det)) continue;  // degenerate UVs
        if (!(glm::length(glm::cross(e1, e2)) > 0.0f)) continue;                  // zero area
        const glm::vec3 dPdu = (e1 * d2.y - e2 * d1.y) / det;
        const glm::vec3 dPdv = (e2 * d1.x - e1 * d2.x) / det;
        const glm::vec3 up = -dPdv;

        for (int corner = 0; corner < 3; ++corner) {
            const Vertex& v = primitive.vertices[idx[corner]];
            const Vertex& next = primitive.vertices[idx[(corner + 1) % 3]];
            const Vertex& prev = primitive.vertices[idx[(corner + 2) % 3]];
            const float angle = cornerAngle(next.positionOs - v.positionOs, prev.positionOs - v.positionOs);
            if (!(angle > 0.0f)) continue;
            const glm::vec3 tp = projectToPlane(dPdu, v.normalOs);
            const glm::vec3 bp = projectToPlane(up, v.normalOs);
            const float lt = glm::length(tp), lb = glm::length(bp);
            if (lt > 0.0f && std::isfinite(lt)) tangentSum[idx[corner]] += tp * (angle / lt);
            if (lb > 0.0f && std::isfinite(lb)) bitangentSum[idx[corner]] += bp * (angle / lb);
        }
    }

    size_t fallbacks = 0;
    for (size_t i = 0; i < n; ++i) {
        Vertex& v = primitive.vertices[i];
        const glm::vec3 normal = v.normalOs;
        glm::vec3 tangent = projectToPlane(tangentSum[i], normal);
        float len = glm::length(tangent);
        if (!(len > 1e-6f)) {
            // No usable dP/du: derive it from the bitangent if there is one, else any perpendicular.
            const glm::vec3 b = projectToPlane(bitangentSum[i], normal);
            if (glm::length(b) > 1e-6f) {
                tangent = glm::cross(glm::normalize(b), normal);
            } else {
                tangent = anyPerpendicular(normal);
                ++fallbacks;
            }
            len = glm::length(tangent);
        }
        tangent /= len;
        const float handedness = glm::dot(glm::cross(normal, tangent), bitangentSum[i]) < 0.0f ? -1.0f : 1.0f;
        v.tangentOs = glm::vec4(tangent, handedness);
    }
    return fallbacks;
}

size_t orthonormalizeTangents(Primitive& primitive) {
    size_t replaced = 0;
    for (Vertex& v : primitive.vertices) {
        glm::vec3 t = projectToPlane(glm::vec3(v.tangentOs), v.normalOs);
        const float len = glm::length(t);
        if (len > 1e-6f && std::isfinite(len)) {
            t /= len;
        } else {
            t = anyPerpendicular(v.normalOs);
            ++replaced;
        }
        v.tangentOs = glm::vec4(t, v.tangentOs.w < 0.0f ? -1.0f : 1.0f);
    }
    return replaced;
}

}  // namespace preskin::scene
