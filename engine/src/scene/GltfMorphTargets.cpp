// Morph target deltas, default weights and target names (see GltfMorphTargets.h).
#include "scene/GltfMorphTargets.h"
#include "scene/GltfAccessors.h"

#include <cmath>

namespace preskin::gltf {

void readMorphTargets(const LoadContext& ctx, const tinygltf::Primitive& in, const std::string& where,
                      size_t vertexCount, Primitive& out) {
    out.targets.resize(in.targets.size());
    for (size_t t = 0; t < in.targets.size(); ++t) {
        MorphTarget& target = out.targets[t];
        for (const auto& [name, accessor] : in.targets[t]) {
            std::vector<glm::vec3>* deltas = name == "POSITION" ? &target.positionDeltas
                : name == "NORMAL"                              ? &target.normalDeltas
                : name == "TANGENT"                             ? &target.tangentDeltas
                                                                : nullptr;
            if (!deltas) {
                ctx.warn(where + indexed(".targets", t),
                         "'" + name + "': morphing this attribute is not supported; ignored");
                continue;
            }
            const std::string at = where + indexed(".targets", t) + "." + name;
            const FloatAccessor values = readFloatAccessor(ctx, accessor, {3}, at);
            if (values.count != vertexCount) {
                ctx.fail(at,
                         indexed("accessors", static_cast<size_t>(accessor)) + " has " + std::to_string(values.count) +
                             " elements, POSITION has " + std::to_string(vertexCount));
            }
            deltas->resize(vertexCount);
            for (size_t i = 0; i < vertexCount; ++i) {
                (*deltas)[i] = glm::vec3(values.values[3 * i], values.values[3 * i + 1], values.values[3 * i + 2]);
            }
        }
    }
}

void convertMorphWeights(const LoadContext& ctx, size_t meshIndex, Mesh& mesh) {
    const tinygltf::Mesh& in = ctx.model->meshes[meshIndex];
    const std::string where = indexed("meshes", meshIndex);
    const size_t targets = in.primitives.empty() ? 0 : in.primitives[0].targets.size();
    for (size_t p = 1; p < in.primitives.size(); ++p) {
        if (in.primitives[p].targets.size() != targets) {
            ctx.fail(where + indexed(".primitives", p) + ".targets",
                     std::to_string(in.primitives[p].targets.size()) + " morph targets, primitives[0] has " +
                         std::to_string(targets) + " (every primitive of a mesh has the same targets)");
        }
    }
    mesh.weights.assign(targets, 0.0f);
    if (!in.weights.empty()) {
        if (in.weights.size() != targets) {
            ctx.fail(where + ".weights",
                     std::to_string(in.weights.size()) + " weights for " + std::to_string(targets) + " morph targets");
        }
        for (size_t i = 0; i < targets; ++i) {
            if (!std::isfinite(in.weights[i])) ctx.fail(where + indexed(".weights", i), "not finite");
            mesh.weights[i] = static_cast<float>(in.weights[i]);
        }
    }
    // extras.targetNames: a de facto convention (Blender, three.js), one string per target.
    if (!in.extras.IsObject() || !in.extras.Has("targetNames")) return;
    const tinygltf::Value& names = in.extras.Get("targetNames");
    bool valid = names.IsArray() && names.ArrayLen() == targets;
    for (size_t i = 0; valid && i < targets; ++i) valid = names.Get(static_cast<int>(i)).IsString();
    if (!valid) {
        ctx.warn(where + ".extras.targetNames", "not an array of " + std::to_string(targets) + " strings; ignored");
        return;
    }
    for (size_t i = 0; i < targets; ++i) mesh.targetNames.push_back(names.Get(static_cast<int>(i)).Get<std::string>());
}

}  // namespace preskin::gltf
