// Scene::nodes from the file's nodes (see GltfNodes.h).
#include "scene/GltfNodes.h"

#include "anim/NodeHierarchy.h"

#include <glm/gtc/quaternion.hpp>

#include <cmath>

namespace preskin::gltf {

NodeTransform decomposeMatrix(const glm::mat4& m) {
    NodeTransform t;
    t.translation = glm::vec3(m[3]);
    glm::dmat3 axes{glm::mat3(m)};
    glm::dvec3 scale(glm::length(axes[0]), glm::length(axes[1]), glm::length(axes[2]));
    if (glm::determinant(axes) < 0.0) scale.x = -scale.x;
    t.scale = glm::vec3(scale);
    if (scale.x == 0.0 || scale.y == 0.0 || scale.z == 0.0) return t;  // no rotation to recover
    for (int k = 0; k < 3; ++k) axes[k] /= scale[k];
    t.rotation = glm::quat(glm::normalize(glm::quat_cast(axes)));
    return t;
}

void convertNodeHierarchy(const LoadContext& ctx) {
    const tinygltf::Model& model = *ctx.model;
    Scene& scene = *ctx.scene;
    const size_t count = model.nodes.size();
    scene.nodes.assign(count, Node{});
    for (size_t i = 0; i < count; ++i) {
        const tinygltf::Node& in = model.nodes[i];
        const std::string where = indexed("nodes", i);
        Node& out = scene.nodes[i];
        out.name = in.name.empty() ? where : in.name;
        for (size_t k = 0; k < in.children.size(); ++k) {
            const int child = in.children[k];
            if (child < 0 || static_cast<size_t>(child) >= count) {
                ctx.fail(where + indexed(".children", k),
                         std::to_string(child) + " is out of range: the file has " + std::to_string(count) + " nodes");
            }
            Node& childNode = scene.nodes[static_cast<size_t>(child)];
            if (childNode.parent >= 0) {
                ctx.fail(where + indexed(".children", k),
                         indexed("nodes", static_cast<size_t>(child)) + " is already a child of " +
                             indexed("nodes", static_cast<size_t>(childNode.parent)) +
                             " (a node has at most one parent)");
            }
            childNode.parent = static_cast<int>(i);
            out.children.push_back(child);
        }

        if (auto m = fixedArray(ctx, in.matrix, 16, where + ".matrix")) {
            glm::mat4 matrix(1.0f);
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r) matrix[c][r] = static_cast<float>((*m)[static_cast<size_t>(4 * c + r)]);
            out.matrix = matrix;
            out.transform = decomposeMatrix(matrix);
        } else {
            if (auto v = fixedArray(ctx, in.translation, 3, where + ".translation")) {
                out.transform.translation = glm::vec3(glm::dvec3((*v)[0], (*v)[1], (*v)[2]));
            }
            if (auto q = fixedArray(ctx, in.rotation, 4, where + ".rotation")) {
                const glm::dquat rotation((*q)[3], (*q)[0], (*q)[1], (*q)[2]);  // glTF stores x, y, z, w
                if (!(glm::length(rotation) > 1e-6)) ctx.fail(where + ".rotation", "zero-length quaternion");
                out.transform.rotation = glm::quat(glm::normalize(rotation));
            }
            if (auto v = fixedArray(ctx, in.scale, 3, where + ".scale")) {
                out.transform.scale = glm::vec3(glm::dvec3((*v)[0], (*v)[1], (*v)[2]));
            }
        }

        if (in.mesh < -1 || (in.mesh >= 0 && static_cast<size_t>(in.mesh) >= scene.meshes.size())) {
            ctx.fail(where + ".mesh",
                     std::to_string(in.mesh) + " is out of range: the file has " + std::to_string(scene.meshes.size()) +
                         " meshes");
        }
        out.mesh = in.mesh;
        if (in.skin < -1 || (in.skin >= 0 && static_cast<size_t>(in.skin) >= model.skins.size())) {
            ctx.fail(where + ".skin",
                     std::to_string(in.skin) + " is out of range: the file has " + std::to_string(model.skins.size()) +
                         " skins");
        }
        if (in.skin >= 0 && in.mesh < 0) ctx.fail(where + ".skin", "given, but the node has no mesh to skin");
        out.skin = in.skin;

        if (!in.weights.empty()) {
            if (in.mesh < 0) ctx.fail(where + ".weights", "given, but the node has no mesh");
            const size_t targets = scene.meshes[static_cast<size_t>(in.mesh)].weights.size();
            if (in.weights.size() != targets) {
                ctx.fail(where + ".weights",
                         std::to_string(in.weights.size()) + " weights, but " +
                             indexed("meshes", static_cast<size_t>(in.mesh)) + " has " + std::to_string(targets) +
                             " morph targets");
            }
            for (size_t k = 0; k < targets; ++k) {
                if (!std::isfinite(in.weights[k])) ctx.fail(where + indexed(".weights", k), "not finite");
                out.weights.push_back(static_cast<float>(in.weights[k]));
            }
        }
    }

    // Every node reaches a root through its parents (no cycle of children): the hierarchy's one
    // check, which posing repeats for scenes built in code.
    if (const auto problem = anim::hierarchyProblem(scene.nodes))
        ctx.fail(indexed("nodes", problem->node), "is part of a cycle of children");
}

}  // namespace preskin::gltf
