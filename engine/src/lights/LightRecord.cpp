// Scene lights as GPU light records; see <preskin/LightRecord.h>.
#include <preskin/LightRecord.h>

#include <algorithm>
#include <cmath>

namespace preskin {

gpu::GpuLight toGpuLight(const Light& light, bool shadowed) {
    gpu::GpuLight g{};
    const glm::vec3 dir = glm::length(light.directionWs) > 0.0f ? glm::normalize(light.directionWs)
                                                                 : glm::vec3(0.0f, 0.0f, -1.0f);
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
    return g;
}

int shadowLightIndex(const std::vector<Light>& lights) {
    for (size_t i = 0; i < lights.size(); ++i)
        if (lights[i].type == LightType::Directional && lights[i].castsShadow) return static_cast<int>(i);
    return -1;
}

}  // namespace preskin
