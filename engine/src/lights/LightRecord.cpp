// Scene lights as GPU light records (<preskin/LightRecord.h>) and as the light grid bounds them
// (lights/ClusterAssign.h).
#include <preskin/LightRecord.h>
#include <preskin/Limits.h>

#include "lights/ClusterAssign.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace preskin {

namespace {

glm::vec3 unitDirection(const Light& light) {
    return glm::length(light.directionWs) > 0.0f ? glm::normalize(light.directionWs) : glm::vec3(0.0f, 0.0f, -1.0f);
}

}  // namespace

bool isAreaLight(LightType type) {
    return type == LightType::Sphere || type == LightType::Tube || type == LightType::Rectangle ||
        type == LightType::Disc;
}

AreaLightAxes areaLightAxes(const Light& light) {
    AreaLightAxes a;
    a.normal = unitDirection(light);
    glm::vec3 w = light.axisWs;
    if (light.type == LightType::Rectangle) w -= glm::dot(w, a.normal) * a.normal;
    if (!(glm::length(w) > 1e-6f)) {  // no usable axis: any direction perpendicular to the normal
        w = glm::cross(a.normal,
                       std::abs(a.normal.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f));
    }
    a.width = glm::normalize(w);
    a.height = glm::cross(a.width, a.normal);  // cross(height, width) = normal
    return a;
}

gpu::GpuLight toGpuLight(const Light& light, bool shadowed) {
    gpu::GpuLight g{};
    const glm::vec3 dir = unitDirection(light);
    uint32_t type = gpu::kLightDirectional;
    if (light.type == LightType::Point) type = gpu::kLightPoint;
    if (light.type == LightType::Spot) type = gpu::kLightSpot;
    g.positionRange = glm::vec4(light.positionWs, std::max(light.range, 0.0f));
    g.directionType = glm::vec4(dir, float(type));
    g.colorIntensity = glm::vec4(light.color * light.intensity, shadowed ? 0.0f : -1.0f);
    const float cosOuter = std::cos(light.outerConeAngle);
    const float cosInner = std::cos(std::min(light.innerConeAngle, light.outerConeAngle));
    const float scale = 1.0f / std::max(1e-3f, cosInner - cosOuter);
    g.spotScaleOffset = glm::vec4(scale, -cosOuter * scale, 0.0f, 0.0f);
    if (light.type == LightType::Directional)
        g.spotScaleOffset.z = std::sin(std::clamp(light.angularRadius, 0.0f, 0.25f * std::numbers::pi_v<float>));
    if (!isAreaLight(light.type)) return g;
    // Area lights: shared/light.h's layout; the width axis made perpendicular to the normal. Sizes
    // below limits::kMinAreaLightSizeM are taken at it: the shaders square them (a 1e-30 m side
    // would vanish), and below a thousandth of the distance they compute any size at that anyway.
    const AreaLightAxes axes = areaLightAxes(light);
    const auto size = [](float v) { return std::max(v, float(limits::kMinAreaLightSizeM)); };
    g.spotScaleOffset = glm::vec4(size(light.radius), 0.0f, 0.0f, 0.0f);
    if (light.type == LightType::Sphere) g.directionType = glm::vec4(0.0f, 0.0f, 0.0f, float(gpu::kLightSphere));
    if (light.type == LightType::Tube)
        g.directionType = glm::vec4(axes.width * (0.5f * size(light.length)), float(gpu::kLightTube));
    if (light.type == LightType::Disc) g.directionType = glm::vec4(axes.normal, float(gpu::kLightDisc));
    if (light.type == LightType::Rectangle) {
        g.directionType = glm::vec4(axes.width * (0.5f * size(light.width)), float(gpu::kLightRectangle));
        g.spotScaleOffset = glm::vec4(axes.height * (0.5f * size(light.height)), 0.0f);
    }
    return g;
}

ClusterLight clusterLight(const Light& light, uint32_t index) {
    ClusterLight c;
    c.positionWs = light.positionWs;
    c.rangeM = std::max(light.range, 0.0f);
    c.directionWs = unitDirection(light);
    c.spot = light.type == LightType::Spot;
    c.cosOuter = c.spot ? std::cos(light.outerConeAngle) : -1.0f;
    c.index = index;
    return c;
}

uint32_t frameLightRecords(std::span<const Light> lights, int shadowLight, std::vector<gpu::GpuLight>& records,
                           std::vector<ClusterLight>& local) {
    constexpr size_t kChunk = 4096;
    const size_t chunks = (lights.size() + kChunk - 1) / kChunk;
    // Per chunk of lights: its directional lights, then where its local lights start.
    std::vector<size_t> directionalIn(chunks, 0);
    std::vector<size_t> localStart(chunks + 1, 0);
    tbb::parallel_for(size_t(0), chunks, [&](size_t c) {
        const size_t end = std::min(lights.size(), (c + 1) * kChunk);
        for (size_t i = c * kChunk; i < end; ++i) {
            const bool directional = lights[i].type == LightType::Directional;
            directionalIn[c] += directional ? 1 : 0;
            localStart[c + 1] += directional ? 0 : 1;
        }
    });
    for (size_t c = 0; c < chunks; ++c) localStart[c + 1] += localStart[c];
    records.clear();
    if (shadowLight >= 0) records.push_back(toGpuLight(lights[size_t(shadowLight)], true));
    for (size_t c = 0; c < chunks; ++c)
        for (size_t i = c * kChunk; directionalIn[c] > 0 && i < std::min(lights.size(), (c + 1) * kChunk); ++i)
            if (lights[i].type == LightType::Directional && int(i) != shadowLight)
                records.push_back(toGpuLight(lights[i], false));
    const auto directional = static_cast<uint32_t>(records.size());
    records.resize(directional + localStart[chunks]);
    local.resize(localStart[chunks]);
    tbb::parallel_for(size_t(0), chunks, [&](size_t c) {
        size_t k = localStart[c];
        const size_t end = std::min(lights.size(), (c + 1) * kChunk);
        for (size_t i = c * kChunk; i < end; ++i) {
            if (lights[i].type == LightType::Directional) continue;
            local[k] = clusterLight(lights[i], directional + static_cast<uint32_t>(k));
            records[directional + k] = toGpuLight(lights[i], false);
            ++k;
        }
    });
    return directional;
}

int shadowLightIndex(const std::vector<Light>& lights) {
    for (size_t i = 0; i < lights.size(); ++i)
        if (lights[i].type == LightType::Directional && lights[i].castsShadow) return static_cast<int>(i);
    return -1;
}

}  // namespace preskin
