// Animation samplers and channels (see GltfAnimations.h).
#include "scene/GltfAnimations.h"
#include "scene/GltfAccessors.h"

#include <cmath>
#include <optional>

namespace preskin::gltf {

namespace {

std::optional<AnimationPath> pathFromName(const std::string& name) {
    if (name == "translation") return AnimationPath::Translation;
    if (name == "rotation") return AnimationPath::Rotation;
    if (name == "scale") return AnimationPath::Scale;
    if (name == "weights") return AnimationPath::Weights;
    return std::nullopt;
}

const char* pathName(AnimationPath path) {
    switch (path) {
    case AnimationPath::Translation: return "translation";
    case AnimationPath::Rotation: return "rotation";
    case AnimationPath::Scale: return "scale";
    case AnimationPath::Weights: return "weights";
    }
    return "";
}

// What a sampler's output holds, from the first channel that uses it.
struct SamplerUse {
    AnimationPath path = AnimationPath::Translation;
    uint32_t components = 0;  // per key value
    size_t channel = 0;
};

std::vector<float> readTimes(const LoadContext& ctx, int accessor, const std::string& at) {
    const FloatAccessor input = readFloatAccessor(ctx, accessor, {1}, at);
    const tinygltf::Accessor& a = ctx.model->accessors[static_cast<size_t>(accessor)];
    if (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) {
        ctx.fail(indexed("accessors", static_cast<size_t>(accessor)) + ".componentType",
                 std::to_string(a.componentType) + ", but " + at + " needs float (5126)");
    }
    for (size_t k = 0; k < input.count; ++k) {
        if (input.values[k] < 0.0f) {
            ctx.fail(at, "time " + number(input.values[k]) + " s at key " + std::to_string(k) + " is negative");
        }
        if (k > 0 && !(input.values[k] > input.values[k - 1])) {
            ctx.fail(at,
                     "time " + number(input.values[k]) + " s at key " + std::to_string(k) + " is not after " +
                         number(input.values[k - 1]) + " s at key " + std::to_string(k - 1) + " (times must increase)");
        }
    }
    return input.values;
}

void checkOutputType(const LoadContext& ctx, int accessor, AnimationPath path, const std::string& at) {
    const tinygltf::Accessor& a = ctx.model->accessors[static_cast<size_t>(accessor)];
    const std::string name = indexed("accessors", static_cast<size_t>(accessor));
    if (a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) return;
    const bool integer = a.componentType == TINYGLTF_COMPONENT_TYPE_BYTE ||
        a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE || a.componentType == TINYGLTF_COMPONENT_TYPE_SHORT ||
        a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    const bool quantizable = path == AnimationPath::Rotation || path == AnimationPath::Weights;
    if (!integer || !quantizable) {
        ctx.fail(name + ".componentType",
                 std::to_string(a.componentType) + ", but " + at + " (" + pathName(path) + ") needs float (5126)" +
                     (quantizable ? " or a normalized 8- or 16-bit integer" : ""));
    }
    if (!a.normalized) ctx.fail(name + ".normalized", "false, but integer " + at + " must be normalized");
}

}  // namespace

void convertAnimations(const LoadContext& ctx) {
    const tinygltf::Model& model = *ctx.model;
    const Scene& scene = *ctx.scene;
    for (size_t a = 0; a < model.animations.size(); ++a) {
        const tinygltf::Animation& in = model.animations[a];
        const std::string where = indexed("animations", a);
        Animation out;
        out.name = in.name;

        // Channels first: they say what each sampler's output holds.
        std::vector<std::optional<SamplerUse>> uses(in.samplers.size());
        for (size_t c = 0; c < in.channels.size(); ++c) {
            const tinygltf::AnimationChannel& channel = in.channels[c];
            const std::string at = where + indexed(".channels", c);
            if (channel.sampler < 0 || static_cast<size_t>(channel.sampler) >= in.samplers.size()) {
                ctx.fail(at + ".sampler",
                         std::to_string(channel.sampler) + " is out of range: the animation has " +
                             std::to_string(in.samplers.size()) + " samplers");
            }
            if (channel.target_node < 0) {
                ctx.warn(at + ".target", "no node; the channel is ignored");
                continue;
            }
            if (static_cast<size_t>(channel.target_node) >= scene.nodes.size()) {
                ctx.fail(at + ".target.node",
                         std::to_string(channel.target_node) + " is out of range: the file has " +
                             std::to_string(scene.nodes.size()) + " nodes");
            }
            const std::optional<AnimationPath> path = pathFromName(channel.target_path);
            if (!path) {
                ctx.warn(at + ".target.path", "'" + channel.target_path + "' is not animated; the channel is ignored");
                continue;
            }
            const auto nodeIndex = static_cast<size_t>(channel.target_node);
            const Node& node = scene.nodes[nodeIndex];
            const std::string nodeName = indexed("nodes", nodeIndex);
            if (node.matrix) {
                ctx.fail(at + ".target.node",
                         nodeName +
                             " has a matrix; an animated node must use translation, "
                             "rotation and scale");
            }
            uint32_t components = *path == AnimationPath::Rotation ? 4 : 3;
            if (*path == AnimationPath::Weights) {
                const size_t targets = node.mesh < 0 ? 0 : scene.meshes[static_cast<size_t>(node.mesh)].weights.size();
                if (targets == 0) ctx.fail(at + ".target.node", nodeName + " has no mesh with morph targets to weight");
                components = static_cast<uint32_t>(targets);
            }
            auto& use = uses[static_cast<size_t>(channel.sampler)];
            const bool rotation = *path == AnimationPath::Rotation;
            const bool weights = *path == AnimationPath::Weights;
            if (use &&
                ((use->path == AnimationPath::Rotation) != rotation ||
                 (use->path == AnimationPath::Weights) != weights || use->components != components)) {
                ctx.fail(at + ".sampler",
                         "samplers[" + std::to_string(channel.sampler) + "] also drives channels[" +
                             std::to_string(use->channel) + "] (" + pathName(use->path) +
                             "), whose values differ in kind from " + pathName(*path));
            }
            if (!use) use = SamplerUse{*path, components, c};
            out.channels.push_back(AnimationChannel{channel.sampler, channel.target_node, *path});
        }

        for (size_t s = 0; s < in.samplers.size(); ++s) {
            const tinygltf::AnimationSampler& sampler = in.samplers[s];
            const std::string at = where + indexed(".samplers", s);
            AnimationSampler result;
            if (sampler.interpolation == "LINEAR" || sampler.interpolation.empty())
                result.interpolation = Interpolation::Linear;
            else if (sampler.interpolation == "STEP")
                result.interpolation = Interpolation::Step;
            else if (sampler.interpolation == "CUBICSPLINE")
                result.interpolation = Interpolation::CubicSpline;
            else {
                ctx.fail(at + ".interpolation",
                         "'" + sampler.interpolation + "' (expected LINEAR, STEP or CUBICSPLINE)");
            }
            result.times = readTimes(ctx, sampler.input, at + ".input");

            // An unused sampler is read with its accessor's own element size.
            const std::optional<SamplerUse>& use = uses[s];
            const AnimationPath path = use ? use->path : AnimationPath::Translation;
            const bool cubic = result.interpolation == Interpolation::CubicSpline;
            const FloatAccessor output = use
                ? readFloatAccessor(ctx, sampler.output, {path == AnimationPath::Weights ? 1 : int(use->components)},
                                    at + ".output")
                : readFloatAccessor(ctx, sampler.output, {1, 2, 3, 4}, at + ".output");
            if (use) checkOutputType(ctx, sampler.output, path, at + ".output");
            result.components = use ? use->components : static_cast<uint32_t>(output.components);
            result.rotation = use && path == AnimationPath::Rotation;
            // Output elements per key: one value (a weights element is one target's weight), three for CUBICSPLINE.
            const size_t elementsPerKey = (path == AnimationPath::Weights ? result.components : 1) * (cubic ? 3 : 1);
            if (output.count != result.times.size() * elementsPerKey) {
                ctx.fail(at,
                         "input " + indexed("accessors", static_cast<size_t>(sampler.input)) + " has " +
                             std::to_string(result.times.size()) + " keys, but output " +
                             indexed("accessors", static_cast<size_t>(sampler.output)) + " has " +
                             std::to_string(output.count) + " elements (" +
                             (use ? std::string(pathName(path)) + ", " : std::string()) + sampler.interpolation + ": " +
                             std::to_string(elementsPerKey) + " per key)");
            }
            if (result.rotation) {
                const size_t valueOffset = cubic ? 4 : 0, stride = cubic ? 12 : 4;
                for (size_t k = 0; k < result.times.size(); ++k) {
                    const float* q = &output.values[k * stride + valueOffset];
                    if (!(std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]) > 1e-6f)) {
                        ctx.fail(at + ".output", "the rotation at key " + std::to_string(k) + " is a zero quaternion");
                    }
                }
            }
            result.values = output.values;
            out.samplers.push_back(std::move(result));
        }
        ctx.scene->animations.push_back(std::move(out));
    }
}

}  // namespace preskin::gltf
