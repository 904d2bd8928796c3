// The CPU reference of the deformation (glTF 2.0, "Morph Targets" and "Skins"), written straight
// from the specification in double precision:
//   p' = p + sum_i w_i dp_i (likewise n' and t'.xyz), then, for a skinned primitive,
//   M = sum_k weight_k * jointMatrix[joint_k] over the eight influence slots,
//   position = M (p', 1); normal = normalize(inverse-transpose(M3) n'); tangent = normalize(M3 t').
// A normal or tangent that the deformation collapses to zero length keeps its undeformed value.
#include <preskin/Deformation.h>
#include <preskin/Error.h>

#include <glm/gtc/type_precision.hpp>

#include <cmath>
#include <string>

namespace preskin {

namespace {

// det(m) * inverse(transpose(m)): the cofactor matrix, whose columns are the cross products of
// the other two columns of m.
glm::dmat3 cofactor(const glm::dmat3& m) {
    return glm::dmat3(glm::cross(m[1], m[2]), glm::cross(m[2], m[0]), glm::cross(m[0], m[1]));
}

glm::dvec3 normalizedOr(const glm::dvec3& v, const glm::vec3& fallback) {
    const double length = glm::length(v);
    return length > 1e-30 && std::isfinite(length) ? v / length : glm::dvec3(fallback);
}

void checkSizes(const Primitive& primitive, const InstancePose& pose) {
    const size_t n = primitive.vertices.size();
    for (size_t t = 0; t < primitive.targets.size(); ++t) {
        const MorphTarget& target = primitive.targets[t];
        for (const auto* deltas : {&target.positionDeltas, &target.normalDeltas, &target.tangentDeltas}) {
            if (!deltas->empty() && deltas->size() != n) {
                throw Error("deformPrimitive: morph target " + std::to_string(t) + " has " +
                            std::to_string(deltas->size()) + " deltas for " + std::to_string(n) + " vertices");
            }
        }
    }
    if (!primitive.influences.empty() && primitive.influences.size() != n) {
        throw Error("deformPrimitive: " + std::to_string(primitive.influences.size()) + " joint influences for " +
                    std::to_string(n) + " vertices");
    }
    if (!pose.jointMatrices.empty()) {
        for (size_t v = 0; v < primitive.influences.size(); ++v)
            for (const glm::uvec4& joints : primitive.influences[v].joints)
                for (int k = 0; k < 4; ++k)
                    if (joints[k] >= pose.jointMatrices.size()) {
                        throw Error("deformPrimitive: vertex " + std::to_string(v) + " uses joint " +
                                    std::to_string(joints[k]) + " of " + std::to_string(pose.jointMatrices.size()));
                    }
    }
}

}  // namespace

void deformPrimitive(const Primitive& primitive, const InstancePose& pose, std::vector<Vertex>& out) {
    checkSizes(primitive, pose);
    const size_t n = primitive.vertices.size();
    const bool skinned = !primitive.influences.empty() && !pose.jointMatrices.empty();
    std::vector<glm::dmat4> joints(pose.jointMatrices.begin(), pose.jointMatrices.end());
    out.resize(n);
    for (size_t v = 0; v < n; ++v) {
        const Vertex& in = primitive.vertices[v];
        glm::dvec3 position(in.positionOs), normal(in.normalOs), tangent(glm::vec3(in.tangentOs));
        for (size_t t = 0; t < primitive.targets.size() && t < pose.morphWeights.size(); ++t) {
            const double w = pose.morphWeights[t];
            const MorphTarget& target = primitive.targets[t];
            if (!target.positionDeltas.empty()) position += w * glm::dvec3(target.positionDeltas[v]);
            if (!target.normalDeltas.empty()) normal += w * glm::dvec3(target.normalDeltas[v]);
            if (!target.tangentDeltas.empty()) tangent += w * glm::dvec3(target.tangentDeltas[v]);
        }
        if (skinned) {
            glm::dmat4 m(0.0);
            const JointInfluences& influence = primitive.influences[v];
            for (int set = 0; set < 2; ++set)
                for (int k = 0; k < 4; ++k)
                    m += static_cast<double>(influence.weights[set][k]) * joints[influence.joints[set][k]];
            const glm::dmat3 m3(m);
            const double det = glm::determinant(m3);
            position = glm::dvec3(m * glm::dvec4(position, 1.0));
            normal = (det < 0.0 ? -1.0 : 1.0) * (cofactor(m3) * normal);
            tangent = m3 * tangent;
        }
        Vertex& o = out[v];
        o.positionOs = glm::vec3(position);
        o.normalOs = glm::vec3(normalizedOr(normal, in.normalOs));
        o.tangentOs = glm::vec4(glm::vec3(normalizedOr(tangent, glm::vec3(in.tangentOs))), in.tangentOs.w);
        o.uv0 = in.uv0;
        o.curvaturePerM = in.curvaturePerM;
    }
}

}  // namespace preskin
