// Conversion of a scene light to the GPU light record the forward pass and the light grid read.
#pragma once

#include <preskin/Scene.h>

#include "shared/gpu_types.h"

#include <vector>

namespace preskin {

// KHR_lights_punctual semantics: colour times intensity, range (0 = unlimited), and the spot's
// cone attenuation as saturate(cd * scale + offset)^2. `shadowed`: this light owns the shadow map.
gpu::GpuLight toGpuLight(const Light& light, bool shadowed);

// Index of the light that gets the shadow map: the first directional light flagged castsShadow
// (the glTF loader flags the first directional light when a file says nothing); -1 when none.
int shadowLightIndex(const std::vector<Light>& lights);

}  // namespace preskin
