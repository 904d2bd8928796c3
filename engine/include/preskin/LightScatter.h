// Deterministic many-light scenes for tests, benchmarks and demos.
#pragma once

#include <preskin/Export.h>
#include <preskin/Scene.h>

#include <cstdint>
#include <vector>

namespace preskin {

// `count` coloured point and spot lights (every third is a spot aimed at the bounds' centre)
// scattered uniformly in the bounds grown by half their size, each with a finite range of the
// scene's size times (0.15 + 0.25 u) (spots 1.5 times that, cones of 20 to 46 degrees half-angle).
// `lightsPerPoint` > 0 sets the density instead, as engines place lights: every range is scaled
// so that a point of the scattered volume lies, on average, in that many lights' volumes (range
// spheres, spot cones), whatever `count` is, so the lights a pixel shades stay the same as
// `count` grows (points near the volume's faces see fewer); 0 keeps the ranges of the scene's
// size. Each light's intensity gives about 0.5 lux at half its range either way. The same
// arguments give the same lights on every platform (mt19937, bit-exact mapping).
PRESKIN_API std::vector<Light> scatterLights(const Bounds& bounds, uint32_t count, uint32_t seed,
                                             float lightsPerPoint = 0.0f);

// The range scale scatterLights uses for `lightsPerPoint` (its ranges are this times
// (0.15 + 0.25 u), spots' 1.5 times that): the cube root of lightsPerPoint * volume / (count *
// the mean volume of one light per unit scale).
PRESKIN_API float scatterRangeScale(const Bounds& bounds, uint32_t count, float lightsPerPoint);

}  // namespace preskin
