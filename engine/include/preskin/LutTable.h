// LutTable: one baked 2D RGB lookup table and its two axes, plus a CPU bilinear sampler that
// returns what a GPU sampler with LINEAR filtering and CLAMP_TO_EDGE addressing returns for the
// same texture (Vulkan spec, "Texel Filtering": texel i's centre is at u = (i + 0.5) / size).
//
// Layout: rgb holds width * height RGB triples, row-major; row y (the y-th scanline, texture
// coordinate v = (y + 0.5) / height) holds axis-y node y; column x holds axis-x node x. Axis
// node i sits at a texel centre, node 0 at the range start and node size-1 at its end, so a
// lookup maps a value to the continuous node coordinate t in [0, size-1] and then to
// u = (t + 0.5) / size. Values are rounded to half precision when baked.
//
// Limits: GPUs quantise the bilinear weights to their sub-texel precision (Vulkan requires >= 4
// bits, lavapipe uses 8), so a GPU differs from sample() by up to |texel difference| / 2^bits.
#pragma once

#include <preskin/Export.h>

#include <preskin/Glm.h>

#include <cstdint>
#include <string>
#include <vector>

namespace preskin {

// How an axis value maps to its node coordinate t in [0, size-1] (N = size):
enum class AxisMapping {
    Linear,       // t = (N-1) (v - min) / (max - min)
    SplitLinear,  // NoL: node k = N/2 (integer division) sits at v = 0, exactly;
                  // t = k (v - min) / -min for v < 0, k + (N-1-k) v / max for v >= 0
    Sqrt,         // t = (N-1) sqrt((v - min) / (max - min))
    SplitSqrt,    // signed curvature: node k = N/2 sits at v = 0, exactly; min = -max;
                  // t = k (1 - sqrt(v / min)) for v < 0, k + (N-1-k) sqrt(v / max) for v >= 0
    Rational,     // t = (N-1) v / (v + 1), v in [0, inf): node N-1 is v = infinity
    Log1p,        // t = (N-1) ln(1 + v / scale) / ln(1 + max / scale), min = 0
    Index,        // t = v, an integer row (SH band, or the single row of a 1D table)
};

PRESKIN_API const char* axisMappingName(AxisMapping mapping);

struct PRESKIN_API LutAxis {
    std::string quantity;  // "NoL", "curvature", ...
    std::string unit;      // "1", "1/mm", "mm"
    AxisMapping mapping = AxisMapping::Linear;
    double min = 0.0;
    double max = 1.0;    // Rational: +infinity
    double scale = 1.0;  // Log1p only
    int size = 0;

    // The axis value at node i (Rational: +infinity at the last node).
    double valueAt(int node) const;
    // The continuous node coordinate of a value, clamped to [0, size-1].
    double nodeCoordinate(double value) const;
    // Human-readable mapping formula, as written into the manifest.
    std::string formula() const;
};

struct PRESKIN_API LutTable {
    std::string name;
    LutAxis x;
    LutAxis y;
    std::vector<float> rgb;

    int width() const { return x.size; }
    int height() const { return y.size; }
    glm::vec3 texel(int ix, int iy) const;
    // Bilinear, CLAMP_TO_EDGE, texel-centre convention; uv in texture coordinates [0, 1].
    glm::vec3 sample(glm::vec2 uv) const;
    // Half-float bits, RGBA (alpha = 1), row-major: ready for a R16G16B16A16_SFLOAT image.
    std::vector<uint16_t> rgba16f() const;
    // The table as channel planes, as shaders read it (see lutPlanes below).
    std::vector<float> planes() const;
    // "fnv1a64:<16 hex digits>" over the half-float bits of the RGB values, row-major.
    std::string contentHash() const;
};

// Channel planes of an RGBA half-float image (width x height, row-major): a (3 width) x height
// single-channel float image (R32_SFLOAT) with the red, green and blue planes side by side:
// texel (c * width + x, y) holds channel c of texel (x, y), exactly (half values are floats).
// shaders/preskin/lut.glsl reads every skin table this way: one textureGather per channel gives
// the 2x2 texels a bilinear lookup of that channel needs, and the shader filters by hand, like
// LINEAR filtering with CLAMP_TO_EDGE of the table itself (without a GPU's coarse sub-texel weights).
PRESKIN_API std::vector<float> lutPlanes(const std::vector<uint16_t>& rgba16f, int width, int height);

}  // namespace preskin
