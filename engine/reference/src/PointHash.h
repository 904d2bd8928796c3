// Hashes the diffusion reference draws its per-point sample rotations from, so that a result
// depends only on the point, never on threads.
#pragma once

#include "ReferenceMesh.h"

#include <cstdint>
#include <functional>

namespace preskin::reference {

// SplitMix64: a well-mixed 64-bit hash of the key.
inline uint64_t splitMix64(uint64_t x) {
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

// A hash's top 53 bits as a number in [0, 1).
inline double unitInterval(uint64_t h) { return double(h >> 11) * (1.0 / 9007199254740992.0); }

// A key for a surface point: its triangle and barycentric place.
inline uint64_t pointKey(const SurfacePoint& p) {
    return (uint64_t(p.triangle) << 32) ^ std::hash<double>{}(p.bary.x * 3.0 + p.bary.y);
}

}  // namespace preskin::reference
