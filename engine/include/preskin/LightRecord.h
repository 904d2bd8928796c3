// A scene light as the GPU record the shaders read (shared/light.h: GpuLight, evaluated by
// preskin/lights.glsl): the one conversion the renderer, the light grid, the diffusion reference
// and a host's own forward pass use.
#pragma once

#include <preskin/Export.h>
#include <preskin/Scene.h>

#include <shared/gpu_types.h>

#include <vector>

namespace preskin {

// KHR_lights_punctual semantics: colour times intensity, range (0 = unlimited), and the spot's
// cone attenuation as saturate(cd * scale + offset)^2. `shadowed`: this light owns the shadow map.
PRESKIN_API gpu::GpuLight toGpuLight(const Light& light, bool shadowed);

// Index of the light that gets the shadow map: the first directional light flagged castsShadow
// (the glTF loader flags the first directional light when a file says nothing); -1 when none.
PRESKIN_API int shadowLightIndex(const std::vector<Light>& lights);

}  // namespace preskin
