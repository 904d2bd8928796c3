// The display mapping of tone-mapped output (shaders/preskin/tonemap.glsl) on the CPU: Khronos
// PBR Neutral (Khronos 3D Commerce, 2024), linear radiance times exposure in, display-linear
// colour in [0, 1] out (sRGB encoding follows).
#pragma once

#include <preskin/Export.h>
#include <preskin/Glm.h>

namespace preskin {

PRESKIN_API glm::dvec3 tonemapNeutral(glm::dvec3 color);

// The colour tonemapNeutral maps to `display` (each channel clamped to [0, 0.999]; the mapping
// approaches 1 only at infinity), found by Newton steps per channel: within 1e-9 of `display`
// after mapping. What a pass that tone-maps everything it is given must be given so that a
// colour meant for the display (a clear colour) comes out unchanged.
PRESKIN_API glm::dvec3 tonemapNeutralInverse(glm::dvec3 display);

}  // namespace preskin
