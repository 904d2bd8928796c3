// Light sets for the light-grid tests: points and spots with random positions, ranges and cones
// (std::mt19937 with a fixed seed), after one directional light that is never clustered.
#pragma once

#include <preskin/Scene.h>

#include <glm/glm.hpp>

#include <random>
#include <vector>

namespace preskin::test {

inline float uniform(std::mt19937& rng, float lo, float hi) {
    return std::uniform_real_distribution<float>(lo, hi)(rng);
}

inline glm::vec3 randomDirection(std::mt19937& rng) {
    for (;;) {
        const glm::vec3 v(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
        const float len = glm::length(v);
        if (len > 0.1f && len <= 1.0f) return v / len;
    }
}

// The one shadow-casting directional light, travelling along `travelDirection`.
inline Light shadowedDirectionalLight(const glm::vec3& travelDirection, float intensity) {
    Light l;
    l.type = LightType::Directional;
    l.directionWs = glm::normalize(travelDirection);
    l.intensity = intensity;
    l.castsShadow = true;
    return l;
}

inline Light pointLight(const glm::vec3& p, float rangeM, const glm::vec3& color = glm::vec3(1.0f),
                        float intensity = 1.0f) {
    Light l;
    l.type = LightType::Point;
    l.positionWs = p;
    l.range = rangeM;
    l.color = color;
    l.intensity = intensity;
    return l;
}

inline Light spotLight(const glm::vec3& p, const glm::vec3& dir, float rangeM, float outerAngle,
                       float intensity = 1.0f) {
    Light l = pointLight(p, rangeM, glm::vec3(1.0f), intensity);
    l.type = LightType::Spot;
    l.directionWs = glm::normalize(dir);
    l.outerConeAngle = outerAngle;
    l.innerConeAngle = 0.6f * outerAngle;
    return l;
}

// A directional light, then `count` points and spots (two in five) in x [-3, 3], y [-2, 3],
// z [-7, zMaxM] with ranges 0.08 .. 1.3 m: around and inside a view, some behind its camera
// (zMaxM past the camera) and some beyond its far slices.
inline std::vector<Light> randomLights(uint32_t count, uint32_t seed, float zMaxM) {
    std::mt19937 rng(seed);
    std::vector<Light> lights(1);
    lights[0].type = LightType::Directional;
    lights[0].directionWs = glm::vec3(0.0f, -1.0f, 0.0f);
    for (uint32_t i = 0; i < count; ++i) {
        const glm::vec3 p(uniform(rng, -3.0f, 3.0f), uniform(rng, -2.0f, 3.0f), uniform(rng, -7.0f, zMaxM));
        const float range = uniform(rng, 0.08f, 1.3f);
        if (rng() % 5 < 2)
            lights.push_back(spotLight(p, randomDirection(rng), range, uniform(rng, 0.08f, 1.45f)));
        else
            lights.push_back(pointLight(p, range));
    }
    return lights;
}

}  // namespace preskin::test
