// The split-sum environment BRDF (Karis, "Real Shading in Unreal Engine 4", SIGGRAPH 2013
// course notes): for GGX with height-correlated Smith visibility and Schlick Fresnel (the BRDF
// of preskin/brdf.glsl), the directional albedo splits into F0 * A + B, tabulated over (NoV,
// perceptual roughness). Entry (i, j) holds NoV = i / (size - 1), roughness = j / (size - 1), so
// both ends are entries; a bilinear lookup reads (x, y) at texture coordinates (x (size - 1) +
// 0.5) / size (preskinDfg in preskin/ibl.glsl).
#pragma once

#include <preskin/Glm.h>

#include <cstdint>
#include <vector>

namespace preskin::env {

// A and B at one (NoV, roughness): the midpoint rule over the GGX half-vector distribution's
// inverse CDF (heightSteps) and the half-turn of azimuth the integrand is symmetric over
// (turnSteps). The horizon (NoL = 0) cuts the domain, so the error falls as 1 / heightSteps:
// about 1e-3 at 512.
glm::vec2 dfgIntegral(float NoV, float roughness, uint32_t heightSteps = 512, uint32_t turnSteps = 16);

// size x size entries, row j (roughness) after row j - 1.
std::vector<glm::vec2> dfgTable(uint32_t size, uint32_t heightSteps = 512, uint32_t turnSteps = 16);

inline constexpr uint32_t kDfgTableSize = 32;
// The renderer's table (kDfgTableSize, default steps), made once per process.
const std::vector<glm::vec2>& defaultDfgTable();

}  // namespace preskin::env
