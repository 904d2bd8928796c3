// Joint influences and skins (see GltfSkins.h).
#include "scene/GltfSkins.h"
#include "scene/GltfAccessors.h"

#include <cmath>
#include <optional>

namespace preskin::gltf {

namespace {

constexpr double kWeightSumTolerance = 1e-3;  // |sum - 1| above this is reported

// The skin with the fewest joints among those that nodes draw meshes[meshIndex] with.
struct SkinUse {
    size_t node = 0;
    size_t skin = 0;
    size_t joints = 0;
};

std::optional<SkinUse> tightestSkin(const LoadContext& ctx, size_t meshIndex) {
    const tinygltf::Model& model = *ctx.model;
    std::optional<SkinUse> tightest;
    if (model.skins.empty()) return tightest;  // static files skip the walk over the nodes
    for (size_t n = 0; n < model.nodes.size(); ++n) {
        const tinygltf::Node& node = model.nodes[n];
        if (node.mesh != static_cast<int>(meshIndex) || node.skin == -1) continue;
        if (node.skin < 0 || static_cast<size_t>(node.skin) >= model.skins.size()) {
            ctx.fail(indexed("nodes", n) + ".skin",
                     std::to_string(node.skin) + " is out of range: the file has " +
                         std::to_string(model.skins.size()) + " skins");
        }
        const size_t joints = model.skins[static_cast<size_t>(node.skin)].joints.size();
        if (joints == 0)
            ctx.fail(indexed("skins", static_cast<size_t>(node.skin)) + ".joints",
                     "empty: a skin needs at least one joint");
        if (!tightest || joints < tightest->joints) tightest = SkinUse{n, static_cast<size_t>(node.skin), joints};
    }
    return tightest;
}

void requireComponentType(const LoadContext& ctx, int accessor, bool weights, const std::string& what) {
    const tinygltf::Accessor& a = ctx.model->accessors[static_cast<size_t>(accessor)];
    const bool integer = a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
        a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    const std::string name = indexed("accessors", static_cast<size_t>(accessor));
    if (weights) {
        if (a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) return;
        if (!integer) {
            ctx.fail(name + ".componentType",
                     std::to_string(a.componentType) + ", but " + what +
                         " needs float (5126) or normalized unsigned byte or short");
        }
        if (!a.normalized) ctx.fail(name + ".normalized", "false, but integer " + what + " must be normalized");
    } else {
        if (!integer) {
            ctx.fail(name + ".componentType",
                     std::to_string(a.componentType) + ", but " + what +
                         " needs unsigned byte (5121) or unsigned short (5123)");
        }
        if (a.normalized) ctx.fail(name + ".normalized", "true, but " + what + " must not be normalized");
    }
}

}  // namespace

void readJointInfluences(const LoadContext& ctx, size_t meshIndex, const tinygltf::Primitive& in,
                         const std::string& where, size_t vertexCount, Primitive& out) {
    auto attribute = [&](const std::string& name) {
        auto it = in.attributes.find(name);
        return it == in.attributes.end() ? -1 : it->second;
    };
    for (const auto& entry : in.attributes) {
        const std::string& name = entry.first;
        const bool influence = name.rfind("JOINTS_", 0) == 0 || name.rfind("WEIGHTS_", 0) == 0;
        if (influence && name != "JOINTS_0" && name != "WEIGHTS_0" && name != "JOINTS_1" && name != "WEIGHTS_1") {
            ctx.warn(where + ".attributes", "'" + name + "': only two sets of joint influences are used; ignored");
        }
    }
    const std::optional<SkinUse> skin = tightestSkin(ctx, meshIndex);
    const std::string skinText = skin ? indexed("nodes", skin->node) + " draws " + indexed("meshes", meshIndex) +
            " with " + indexed("skins", skin->skin)
                                      : std::string();
    if (attribute("JOINTS_0") < 0 && attribute("WEIGHTS_0") < 0 && attribute("JOINTS_1") < 0 &&
        attribute("WEIGHTS_1") < 0) {
        if (skin) ctx.fail(where + ".attributes", "no JOINTS_0 and WEIGHTS_0, but " + skinText);
        return;
    }

    std::vector<JointInfluences> influences(vertexCount);
    for (int set = 0; set < 2; ++set) {
        const std::string jointsName = "JOINTS_" + std::to_string(set), weightsName = "WEIGHTS_" + std::to_string(set);
        const int joints = attribute(jointsName), weights = attribute(weightsName);
        if (joints < 0 && weights < 0 && set == 1) continue;
        if (joints < 0 || weights < 0) {
            ctx.fail(where + ".attributes." + (joints < 0 ? jointsName : weightsName),
                     "missing: " + jointsName + " and " + weightsName + " come in pairs" +
                         (set == 1 ? " (and set 1 needs set 0)" : ""));
        }
        const std::string jointsAt = where + ".attributes." + jointsName,
                          weightsAt = where + ".attributes." + weightsName;
        const FloatAccessor j = readFloatAccessor(ctx, joints, {4}, jointsAt);
        requireComponentType(ctx, joints, false, jointsAt);
        const FloatAccessor w = readFloatAccessor(ctx, weights, {4}, weightsAt);
        requireComponentType(ctx, weights, true, weightsAt);
        auto checkCount = [&](const FloatAccessor& a, int index, const std::string& at) {
            if (a.count != vertexCount) {
                ctx.fail(at,
                         indexed("accessors", static_cast<size_t>(index)) + " has " + std::to_string(a.count) +
                             " elements, POSITION has " + std::to_string(vertexCount));
            }
        };
        checkCount(j, joints, jointsAt);
        checkCount(w, weights, weightsAt);
        for (size_t v = 0; v < vertexCount; ++v) {
            for (int k = 0; k < 4; ++k) {
                const auto joint = static_cast<uint32_t>(j.values[4 * v + static_cast<size_t>(k)]);
                const float weight = w.values[4 * v + static_cast<size_t>(k)];
                if (skin && joint >= skin->joints) {
                    ctx.fail(jointsAt,
                             "joint " + std::to_string(joint) + " at vertex " + std::to_string(v) +
                                 " is out of range: " + skinText + ", which has " + std::to_string(skin->joints) +
                                 " joints");
                }
                if (weight < 0.0f)
                    ctx.fail(weightsAt, "negative weight " + number(weight) + " at vertex " + std::to_string(v));
                influences[v].joints[set][k] = joint;
                influences[v].weights[set][k] = weight;
            }
        }
    }

    // Weights sum to 1 (glTF 2.0, "Skinned Mesh Attributes"); other sums are normalised.
    size_t offCount = 0;
    double largestDeviation = 0.0;
    for (size_t v = 0; v < vertexCount; ++v) {
        JointInfluences& influence = influences[v];
        double sum = 0.0;
        for (const glm::vec4& weights : influence.weights) {
            const glm::dvec4 w(weights);
            sum += w.x + w.y + w.z + w.w;
        }
        if (!(sum > 0.0))
            ctx.fail(where + ".attributes.WEIGHTS_0", "vertex " + std::to_string(v) + " has no joint weight (all 0)");
        if (std::abs(sum - 1.0) > kWeightSumTolerance) {
            ++offCount;
            largestDeviation = std::max(largestDeviation, std::abs(sum - 1.0));
        }
        for (glm::vec4& weights : influence.weights) weights = glm::vec4(glm::dvec4(weights) / sum);
    }
    if (offCount > 0) {
        ctx.warn(where + ".attributes.WEIGHTS_0",
                 std::to_string(offCount) + " of " + std::to_string(vertexCount) +
                     " vertices have joint weights that do not sum to 1 (off by up to " + number(largestDeviation) +
                     "); normalised");
    }
    out.influences = std::move(influences);
}

void convertSkins(const LoadContext& ctx) {
    const tinygltf::Model& model = *ctx.model;
    for (size_t s = 0; s < model.skins.size(); ++s) {
        const tinygltf::Skin& in = model.skins[s];
        const std::string where = indexed("skins", s);
        Skin out;
        out.name = in.name.empty() ? where : in.name;
        if (in.joints.empty()) ctx.fail(where + ".joints", "empty: a skin needs at least one joint");
        for (size_t k = 0; k < in.joints.size(); ++k) {
            if (in.joints[k] < 0 || static_cast<size_t>(in.joints[k]) >= model.nodes.size()) {
                ctx.fail(where + indexed(".joints", k),
                         std::to_string(in.joints[k]) + " is out of range: the file has " +
                             std::to_string(model.nodes.size()) + " nodes");
            }
        }
        out.joints = in.joints;
        out.inverseBindMatrices.assign(in.joints.size(), glm::mat4(1.0f));
        if (in.inverseBindMatrices >= 0) {
            const std::string at = where + ".inverseBindMatrices";
            const FloatAccessor matrices = readFloatAccessor(ctx, in.inverseBindMatrices, {16}, at);
            const tinygltf::Accessor& accessor = model.accessors[static_cast<size_t>(in.inverseBindMatrices)];
            if (accessor.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) {
                ctx.fail(indexed("accessors", static_cast<size_t>(in.inverseBindMatrices)) + ".componentType",
                         std::to_string(accessor.componentType) + ", but " + at + " needs float (5126)");
            }
            if (matrices.count != in.joints.size()) {
                ctx.fail(at,
                         indexed("accessors", static_cast<size_t>(in.inverseBindMatrices)) + " has " +
                             std::to_string(matrices.count) + " matrices for " + std::to_string(in.joints.size()) +
                             " joints");
            }
            for (size_t k = 0; k < matrices.count; ++k)
                for (int c = 0; c < 4; ++c)
                    for (int r = 0; r < 4; ++r)
                        out.inverseBindMatrices[k][c][r] = matrices.values[16 * k + static_cast<size_t>(4 * c + r)];
        }
        if (in.skeleton < -1 || (in.skeleton >= 0 && static_cast<size_t>(in.skeleton) >= model.nodes.size())) {
            ctx.fail(where + ".skeleton",
                     std::to_string(in.skeleton) + " is out of range: the file has " +
                         std::to_string(model.nodes.size()) + " nodes");
        }
        out.skeleton = in.skeleton;
        ctx.scene->skins.push_back(std::move(out));
    }
}

}  // namespace preskin::gltf
