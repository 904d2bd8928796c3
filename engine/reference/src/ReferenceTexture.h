// ReferenceTexture: a scene image sampled on the CPU the way the renderer's Vulkan sampler sees
// it: 8-bit texels decoded (sRGB to linear where the renderer uploads an sRGB format), a mip
// chain of 2x2 box averages in linear values (what a linear blit of an sRGB image produces),
// the glTF sampler's wrap modes and filters, and the level of detail from the texture-space
// footprint of a pixel (Vulkan specification, "Level-of-Detail Operation": the larger of the
// two screen-axis scale factors, isotropic), trilinear between levels.
// Limits: no anisotropic filtering (the renderer enables none on lavapipe); odd-sized levels
// round down like the blit but average 2x2 texels; sRGB decoding is exact (lavapipe's is an
// approximation, up to 0.7 % off at dark codes).
#pragma once

#include <preskin/Scene.h>

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace preskin::reference {

class ReferenceTexture {
public:
    ReferenceTexture(const Image& image, const Sampler& sampler, bool srgb);

    // Filtered RGBA at uv (glTF: (0, 0) is the image's top-left corner) for a pixel footprint
    // duvDx, duvDy in uv units per pixel (zero: the finest level).
    glm::dvec4 sample(const glm::dvec2& uv, const glm::dvec2& duvDx, const glm::dvec2& duvDy) const;

private:
    struct Level {
        uint32_t width = 0;
        uint32_t height = 0;
        std::vector<glm::vec4> texels;
    };
    glm::dvec4 bilinear(const Level& level, const glm::dvec2& uv) const;
    glm::dvec4 nearest(const Level& level, const glm::dvec2& uv) const;
    glm::dvec4 texel(const Level& level, int64_t x, int64_t y) const;

    std::vector<Level> levels_;
    Sampler sampler_;
};

// The sRGB transfer function's inverse (IEC 61966-2-1), 8-bit code to linear.
double srgbToLinear(double encoded);

}  // namespace preskin::reference
