// Deterministic many-light scenes for tests, benchmarks and demos.
#pragma once

#include <preskin/Export.h>
#include <preskin/Scene.h>

#include <cstdint>
#include <vector>

namespace preskin {

// `count` coloured point and spot lights (every third is a spot aimed at the bounds' centre)
// scattered in the bounds grown by half their size, each with a finite range. The same
// (bounds, count, seed) gives the same lights on every platform (mt19937, bit-exact mapping).
PRESKIN_API std::vector<Light> scatterLights(const Bounds& bounds, uint32_t count, uint32_t seed);

}  // namespace preskin
