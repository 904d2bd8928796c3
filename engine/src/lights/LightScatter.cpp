#include <preskin/LightScatter.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace preskin {

namespace {

// [0, 1) from the top 24 bits of one mt19937 draw: identical on every standard library.
float unit(std::mt19937& rng) { return float(rng() >> 8) * (1.0f / 16777216.0f); }

glm::vec3 hueToRgb(float h) {
    const glm::vec3 k(0.0f, 2.0f / 3.0f, 1.0f / 3.0f);
    glm::vec3 c = glm::abs(glm::fract(glm::vec3(h) + k) * 6.0f - 3.0f) - 1.0f;
    return glm::clamp(c, 0.0f, 1.0f);
}

}  // namespace

std::vector<Light> scatterLights(const Bounds& bounds, uint32_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    const glm::vec3 center = bounds.empty() ? glm::vec3(0.0f) : bounds.center();
    const glm::vec3 extent = bounds.empty() ? glm::vec3(1.0f) : glm::max(bounds.extent(), glm::vec3(1e-3f));
    const float radius = 0.5f * glm::length(extent);
    std::vector<Light> lights;
    lights.reserve(count);
    for (uint32_t i = 0; i < count; ++i) {
        Light l;
        l.name = "scattered" + std::to_string(i);
        l.type = (i % 3 == 2) ? LightType::Spot : LightType::Point;
        l.positionWs = center + (glm::vec3(unit(rng), unit(rng), unit(rng)) - 0.5f) * extent * 2.0f;
        l.color = glm::mix(glm::vec3(1.0f), hueToRgb(unit(rng)), 0.7f);
        l.range = radius * (0.15f + 0.25f * unit(rng));
        // About 0.5 lux at half the range, whatever the scene's scale.
        l.intensity = 0.5f * 0.25f * l.range * l.range;
        if (l.type == LightType::Spot) {
            const glm::vec3 toCenter = center - l.positionWs;
            l.directionWs = glm::length(toCenter) > 1e-6f ? glm::normalize(toCenter) : glm::vec3(0.0f, -1.0f, 0.0f);
            l.outerConeAngle = 0.35f + 0.45f * unit(rng);
            l.innerConeAngle = l.outerConeAngle * 0.6f;
            l.range *= 1.5f;
            l.intensity *= 2.25f;
        }
        lights.push_back(l);
    }
    return lights;
}

}  // namespace preskin
