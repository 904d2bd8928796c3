// Conversion of a scene light to the GPU light record the forward pass and the light grid read.
#pragma once

#include <preskin/Scene.h>

#include "shared/gpu_types.h"

namespace preskin {

// KHR_lights_punctual semantics: colour times intensity, range (0 = unlimited), and the spot's
// cone attenuation as saturate(cd * scale + offset)^2. `shadowed`: this light owns the shadow map.
gpu::GpuLight toGpuLight(const Light& light, bool shadowed);

}  // namespace preskin
