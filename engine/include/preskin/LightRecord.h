// A scene light as the GPU record the shaders read (shared/light.h: GpuLight, evaluated by
// preskin/lights.glsl): the one conversion the renderer, the light grid, the diffusion reference
// and a host's own forward pass use.
#pragma once

#include <preskin/Export.h>
#include <preskin/Scene.h>

#include <shared/gpu_types.h>

#include <vector>

namespace preskin {

// Sphere, tube, rectangle or disc (lights with a size).
PRESKIN_API bool isAreaLight(LightType type);

// An area light's frame (world, unit vectors): the normal it emits along (rectangle, disc), its
// width or tube axis (Light::axisWs, made perpendicular to the normal for a rectangle) and its
// height axis, cross(width, normal), so that cross(height, width) = normal.
struct AreaLightAxes {
    glm::vec3 normal{0.0f, 0.0f, -1.0f};
    glm::vec3 width{1.0f, 0.0f, 0.0f};
    glm::vec3 height{0.0f, 1.0f, 0.0f};
};
PRESKIN_API AreaLightAxes areaLightAxes(const Light& light);

// KHR_lights_punctual semantics: colour times intensity, range (0 = unlimited), and the spot's
// cone attenuation as saturate(cd * scale + offset)^2; area lights as shared/light.h lays them out.
// `shadowed`: this light owns the shadow map.
PRESKIN_API gpu::GpuLight toGpuLight(const Light& light, bool shadowed);

// A directional light narrower than this (angular radius, radians; the sun's is 0.0047) is shaded
// as a parallel light, its shadow still softened by its size: its cap would move the terminator
// by at most 2/255 (measured on the bundled head), at 2.5 times the forward pass's cost on a CPU
// driver.
inline constexpr float kCapShadingMinAngularRadius = 0.005f;

// Index of the light that gets the shadow map: the first directional light flagged castsShadow
// (the glTF loader flags the first directional light when a file says nothing); -1 when none.
PRESKIN_API int shadowLightIndex(const std::vector<Light>& lights);

}  // namespace preskin
