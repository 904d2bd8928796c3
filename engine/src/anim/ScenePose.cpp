// From node transforms and weights to what the renderer draws: world transforms through the
// hierarchy, then per mesh instance its transform, morph weights and joint matrices
// (glTF 2.0, "Skins": jointMatrix_j = worldFromNode(joint_j) * inverseBindMatrix_j).
#include <preskin/Animation.h>
#include <preskin/Error.h>
#include <preskin/Scene.h>

#include "anim/NodeHierarchy.h"
#include "anim/Printable.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace preskin {

namespace {

bool finite(const NodeTransform& t) {
    for (int k = 0; k < 3; ++k)
        if (!std::isfinite(t.translation[k]) || !std::isfinite(t.scale[k])) return false;
    for (int k = 0; k < 4; ++k)
        if (!std::isfinite(t.rotation[k])) return false;
    return true;
}

bool finite(const std::vector<float>& values) {
    return std::all_of(values.begin(), values.end(), [](float v) { return std::isfinite(v); });
}

std::string nodeName(const Scene& scene, size_t i) {
    return "node " + std::to_string(i) +
        (scene.nodes[i].name.empty() ? "" : " '" + anim::printable(scene.nodes[i].name) + "'");
}

// worldFromNode of every node (the hierarchy's one walk, anim/NodeHierarchy.h).
std::vector<glm::mat4> worldTransforms(const Scene& scene, const NodePose& pose) {
    if (const auto problem = anim::hierarchyProblem(scene.nodes)) {
        const Node& node = scene.nodes[problem->node];
        if (problem->kind == anim::HierarchyProblem::Kind::Cycle)
            throw Error("node pose: " + nodeName(scene, problem->node) + " is part of a cycle of parents");
        throw Error("node pose: " + nodeName(scene, problem->node) + " has parent " + std::to_string(node.parent) +
                    ", out of range of " + std::to_string(scene.nodes.size()) + " nodes");
    }
    std::vector<glm::mat4> local(scene.nodes.size());
    for (size_t i = 0; i < local.size(); ++i)
        local[i] = scene.nodes[i].matrix ? *scene.nodes[i].matrix : pose.transforms[i].matrix();
    return anim::worldTransforms(scene.nodes, local);
}

size_t targetCount(const Mesh& mesh) {
    size_t count = 0;
    for (const Primitive& primitive : mesh.primitives) count = std::max(count, primitive.targets.size());
    return count;
}

}  // namespace

ScenePose posedScene(const Scene& scene, const NodePose& nodes) {
    const size_t nodeCount = scene.nodes.size();
    if (nodes.transforms.size() != nodeCount) {
        throw Error("node pose: " + std::to_string(nodes.transforms.size()) + " transforms for a scene of " +
                    std::to_string(nodeCount) + " nodes");
    }
    if (!nodes.weights.empty() && nodes.weights.size() != nodeCount) {
        throw Error("node pose: " + std::to_string(nodes.weights.size()) + " weight lists for a scene of " +
                    std::to_string(nodeCount) + " nodes");
    }
    for (size_t i = 0; i < nodeCount; ++i) {
        if (!finite(nodes.transforms[i]))
            throw Error("node pose: the transform of " + nodeName(scene, i) + " is not finite");
        if (!nodes.weights.empty() && !finite(nodes.weights[i])) {
            throw Error("node pose: a morph weight of " + nodeName(scene, i) + " is not finite");
        }
    }
    const std::vector<glm::mat4> world = worldTransforms(scene, nodes);

    ScenePose out;
    out.instances.resize(scene.instances.size());
    for (size_t i = 0; i < scene.instances.size(); ++i) {
        const MeshInstance& instance = scene.instances[i];
        InstancePose& pose = out.instances[i];
        const std::string where = "instance " + std::to_string(i) + " ('" + anim::printable(instance.nodeName) + "')";
        if (instance.mesh < 0 || static_cast<size_t>(instance.mesh) >= scene.meshes.size()) {
            throw Error(where + ": mesh " + std::to_string(instance.mesh) + " is out of range");
        }
        if (instance.node < -1 || (instance.node >= 0 && static_cast<size_t>(instance.node) >= nodeCount)) {
            throw Error(where + ": node " + std::to_string(instance.node) + " is out of range");
        }
        const Mesh& mesh = scene.meshes[static_cast<size_t>(instance.mesh)];
        const auto node = static_cast<size_t>(instance.node);
        pose.worldFromObject = instance.node >= 0 ? world[node] : instance.worldFromObject;

        // Morph weights: the pose's for the node, else the node's own, else the mesh's defaults.
        const size_t targets = targetCount(mesh);
        const std::vector<float>* weights = &mesh.weights;
        if (instance.node >= 0 && !nodes.weights.empty() && !nodes.weights[node].empty())
            weights = &nodes.weights[node];
        else if (instance.node >= 0 && !scene.nodes[node].weights.empty())
            weights = &scene.nodes[node].weights;
        if (weights != &mesh.weights && weights->size() != targets) {
            throw Error(where + ": " + std::to_string(weights->size()) + " morph weights for a mesh of " +
                        std::to_string(targets) + " morph targets");
        }
        pose.morphWeights.assign(targets, 0.0f);
        std::copy_n(weights->begin(), std::min(targets, weights->size()), pose.morphWeights.begin());

        if (instance.skin >= 0) {
            if (static_cast<size_t>(instance.skin) >= scene.skins.size()) {
                throw Error(where + ": skin " + std::to_string(instance.skin) + " is out of range");
            }
            const Skin& skin = scene.skins[static_cast<size_t>(instance.skin)];
            if (skin.inverseBindMatrices.size() != skin.joints.size()) {
                throw Error(where + ": the skin has " + std::to_string(skin.joints.size()) + " joints and " +
                            std::to_string(skin.inverseBindMatrices.size()) + " inverse bind matrices");
            }
            pose.jointMatrices.resize(skin.joints.size());
            for (size_t j = 0; j < skin.joints.size(); ++j) {
                const int joint = skin.joints[j];
                if (joint < 0 || static_cast<size_t>(joint) >= nodeCount) {
                    throw Error(where + ": joint " + std::to_string(j) + " is node " + std::to_string(joint) +
                                ", out of range");
                }
                pose.jointMatrices[j] = world[static_cast<size_t>(joint)] * skin.inverseBindMatrices[j];
            }
            pose.worldFromObject = glm::mat4(1.0f);  // the joint matrices give world space
        }
    }
    return out;
}

ScenePose restPose(const Scene& scene) { return posedScene(scene, restNodePose(scene)); }

}  // namespace preskin
