// An animation's time range, and finding an animation of a scene by name or index.
#include <preskin/Animation.h>
#include <preskin/Error.h>
#include <preskin/Scene.h>

#include "anim/Printable.h"

#include <algorithm>
#include <limits>

namespace preskin {

float Animation::startS() const {
    float start = std::numeric_limits<float>::max();
    for (const AnimationSampler& sampler : samplers)
        if (!sampler.times.empty()) start = std::min(start, sampler.times.front());
    return start == std::numeric_limits<float>::max() ? 0.0f : start;
}

float Animation::endS() const {
    float end = -std::numeric_limits<float>::max();
    for (const AnimationSampler& sampler : samplers)
        if (!sampler.times.empty()) end = std::max(end, sampler.times.back());
    return end == -std::numeric_limits<float>::max() ? 0.0f : end;
}

const Animation& findAnimation(const Scene& scene, const std::string& nameOrIndex) {
    for (const Animation& animation : scene.animations)
        if (animation.name == nameOrIndex) return animation;
    const bool decimal = !nameOrIndex.empty() && nameOrIndex.size() <= 9 &&
        std::all_of(nameOrIndex.begin(), nameOrIndex.end(), [](char c) { return c >= '0' && c <= '9'; });
    if (decimal) {
        const size_t index = std::stoul(nameOrIndex);
        if (index < scene.animations.size()) return scene.animations[index];
    }
    std::string list;
    for (size_t i = 0; i < scene.animations.size(); ++i) {
        list += (i == 0 ? "" : ", ") + std::to_string(i) + " '" + anim::printable(scene.animations[i].name) + "'";
    }
    throw Error(scene.sourcePath.string() + ": no animation named '" + anim::printable(nameOrIndex) + "' (" +
                (list.empty() ? std::string("the scene has no animations") : "animations: " + list) + ")");
}

}  // namespace preskin
