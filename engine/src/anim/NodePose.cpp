// Node transforms and the node pose of a scene: at rest, or at a time of an animation (its
// channels written over the rest pose).
#include <preskin/Animation.h>
#include <preskin/Error.h>
#include <preskin/Scene.h>

#include "anim/Printable.h"

#include <glm/gtc/quaternion.hpp>

#include <string>

namespace preskin {

glm::mat4 NodeTransform::matrix() const {
    glm::mat4 m = glm::mat4_cast(glm::normalize(rotation));
    m[0] *= scale.x;
    m[1] *= scale.y;
    m[2] *= scale.z;
    m[3] = glm::vec4(translation, 1.0f);
    return m;
}

NodePose restNodePose(const Scene& scene) {
    NodePose pose;
    pose.transforms.reserve(scene.nodes.size());
    pose.weights.reserve(scene.nodes.size());
    for (const Node& node : scene.nodes) {
        pose.transforms.push_back(node.transform);
        pose.weights.push_back(node.weights);
    }
    return pose;
}

NodePose animationNodePose(const Scene& scene, const Animation& animation, float timeS) {
    NodePose pose = restNodePose(scene);
    const std::string where = "animation '" + anim::printable(animation.name) + "'";
    for (size_t c = 0; c < animation.channels.size(); ++c) {
        const AnimationChannel& channel = animation.channels[c];
        const std::string at = where + " channel " + std::to_string(c);
        if (channel.node < 0 || static_cast<size_t>(channel.node) >= scene.nodes.size()) {
            throw Error(at + ": node " + std::to_string(channel.node) + " is out of range: the scene has " +
                        std::to_string(scene.nodes.size()) + " nodes");
        }
        if (channel.sampler < 0 || static_cast<size_t>(channel.sampler) >= animation.samplers.size()) {
            throw Error(at + ": sampler " + std::to_string(channel.sampler) + " is out of range: the animation has " +
                        std::to_string(animation.samplers.size()) + " samplers");
        }
        const std::vector<float> v = animation.samplers[static_cast<size_t>(channel.sampler)].sample(timeS);
        const auto node = static_cast<size_t>(channel.node);
        NodeTransform& transform = pose.transforms[node];
        const size_t expected = channel.path == AnimationPath::Rotation ? 4
            : channel.path == AnimationPath::Weights                    ? v.size()
                                                                        : 3;
        if (v.size() != expected) {
            throw Error(at + ": the sampler gives " + std::to_string(v.size()) + " components, the path needs " +
                        std::to_string(expected));
        }
        switch (channel.path) {
        case AnimationPath::Translation: transform.translation = glm::vec3(v[0], v[1], v[2]); break;
        case AnimationPath::Rotation: transform.rotation = glm::quat(v[3], v[0], v[1], v[2]); break;
        case AnimationPath::Scale: transform.scale = glm::vec3(v[0], v[1], v[2]); break;
        case AnimationPath::Weights: pose.weights[node] = v; break;
        }
    }
    return pose;
}

}  // namespace preskin
