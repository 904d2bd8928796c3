// Animated scenes (glTF 2.0): the node hierarchy, skins, animations, and the pose a frame is drawn
// in. Data flows one way: an animation (or a host's own animation system) gives node transforms
// and morph weights at a time -> posedScene() turns them into a ScenePose (per mesh instance:
// transform, morph weights, joint matrices) -> Renderer::setPose, whose compute pass deforms the
// meshes on the GPU. A static scene is the one-pose case: restPose().
//
// Conventions (glTF 2.0 specification, "Skins", "Morph Targets", "Animations"):
//  - morph targets add weighted deltas to POSITION, NORMAL and TANGENT first; then skinning
//    applies sum_j w_j * jointMatrix_j with jointMatrix_j = worldFromNode(joint_j) *
//    inverseBindMatrix_j, which gives world-space vertices directly (the skinned mesh node's own
//    transform is ignored); normals and tangents take the inverse transpose of the same blended
//    3x3, renormalised;
//  - rotations interpolate by slerp over the short arc; CUBICSPLINE tangents are scaled by the
//    key interval; times before the first key and after the last clamp to them;
//  - joint weights that do not sum to 1 are normalised at load (with a warning).
#pragma once

#include <preskin/Export.h>

#include <preskin/Glm.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace preskin {

struct Scene;

// A node's local transform: translation, rotation, scale (glTF TRS).
struct NodeTransform {
    glm::vec3 translation{0.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // w, x, y, z
    glm::vec3 scale{1.0f};

    PRESKIN_API glm::mat4 matrix() const;  // T * R * S
};

// One node of the glTF hierarchy as loaded (Scene::nodes).
struct Node {
    std::string name;
    int parent = -1;
    std::vector<int> children;
    NodeTransform transform;          // the rest transform (TRS, or a decomposed matrix)
    std::optional<glm::mat4> matrix;  // the file gave a matrix: used as is and never animated
    int mesh = -1;
    int skin = -1;
    std::vector<float> weights;  // morph weights overriding the mesh's defaults (empty: the mesh's)
};

struct Skin {
    std::string name;
    std::vector<int> joints;                     // node indices
    std::vector<glm::mat4> inverseBindMatrices;  // one per joint (identity when the file has none)
    int skeleton = -1;                           // node index, informative only
};

enum class Interpolation { Step, Linear, CubicSpline };
enum class AnimationPath { Translation, Rotation, Scale, Weights };

struct AnimationSampler {
    std::vector<float> times;  // seconds, finite and strictly increasing
    // Per key `components` floats (3 for translation and scale, 4 for a rotation x, y, z, w, the
    // morph target count for weights); CUBICSPLINE keys hold in-tangent, value, out-tangent.
    std::vector<float> values;
    uint32_t components = 0;
    Interpolation interpolation = Interpolation::Linear;
    // The values are unit quaternions (a rotation channel's sampler): LINEAR interpolates them by
    // slerp over the short arc and every result is normalised. A weights sampler of four morph
    // targets has 4 components too, so the component count alone cannot tell.
    bool rotation = false;

    // The value at a time (clamped to the keys; rotations normalised), `components` floats.
    PRESKIN_API std::vector<float> sample(float timeS) const;
};

struct AnimationChannel {
    int sampler = 0;
    int node = -1;
    AnimationPath path = AnimationPath::Translation;
};

struct Animation {
    std::string name;
    std::vector<AnimationSampler> samplers;
    std::vector<AnimationChannel> channels;

    // The first and last key over all samplers (0, 0 without keys).
    PRESKIN_API float startS() const;
    PRESKIN_API float endS() const;
};

// The state of every node at one moment: local transforms and morph weights, one entry per
// Scene::nodes. What an animation gives at a time, or what a host's animation system fills in.
struct NodePose {
    std::vector<NodeTransform> transforms;
    std::vector<std::vector<float>> weights;  // per node; empty: the node's (or its mesh's) defaults
};

// What the renderer draws: per mesh instance (Scene::instances, same order) the transform of its
// draw space, its morph weights and, when skinned, its joint matrices.
struct InstancePose {
    // Object space to world. For a skinned instance the deformed vertices are already in world
    // space (the skin's joint matrices put them there), so this is the identity.
    glm::mat4 worldFromObject{1.0f};
    std::vector<float> morphWeights;       // one per morph target of the mesh (empty: none)
    std::vector<glm::mat4> jointMatrices;  // skinned: worldFromNode(joint) * inverseBind, per joint
};

struct ScenePose {
    std::vector<InstancePose> instances;
};

// The rest pose of every node (Node::transform or matrix, Node::weights).
PRESKIN_API NodePose restNodePose(const Scene& scene);
// The nodes at `timeS` of an animation: its channels applied over the rest pose.
PRESKIN_API NodePose animationNodePose(const Scene& scene, const Animation& animation, float timeS);
// Node transforms and weights -> the per-instance pose the renderer takes. Throws preskin::Error
// when the node pose does not match the scene (counts, non-finite values).
PRESKIN_API ScenePose posedScene(const Scene& scene, const NodePose& nodes);
// posedScene(scene, restNodePose(scene)).
PRESKIN_API ScenePose restPose(const Scene& scene);

// The animation named `nameOrIndex` (a name, or a decimal index); throws preskin::Error listing
// the scene's animations when there is none.
PRESKIN_API const Animation& findAnimation(const Scene& scene, const std::string& nameOrIndex);

}  // namespace preskin
