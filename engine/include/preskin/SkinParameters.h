// Per-material quantities the skin shader needs that are derived rather than authored: the
// normal map's per-channel mip LOD bias (from the profile's scattering width and the map's
// texel density) and that texel density itself.
#pragma once

#include <preskin/Export.h>
#include <preskin/Scene.h>

#include <preskin/Glm.h>

namespace preskin {

// Mip LOD bias per channel of a normal map: how many mip levels the profile's scattering width
// spans on the surface, log2(1 + widthMm / scatterScale * texelsPerMm). Red scatters furthest
// and gets the largest bias; a bias of 0 leaves that channel unfiltered.
PRESKIN_API glm::vec3 normalLodBias(const glm::vec3& widthMm, float scatterScale, float texelsPerMm);

// How many whole mip levels the shader blends into the three biased normal samples
// (PreskinNormalMaps::levelCount, preskinSampleLevels in preskin/mip_levels.glsl): from the
// level at or below the lowest biased level of detail to the one above the highest,
// ceil(max(bias) - min(bias)) + 2, and never more than the map has (mipLevels; with a detail
// map, the larger of the two maps' counts). withUnbiased: the span includes bias 0 too
// (PreskinNormalMaps::specularFromLevels).
PRESKIN_API int normalLevelCount(const glm::vec3& lodBias, uint32_t mipLevels, bool withUnbiased = false);

// Texel density of an image of width x height on a primitive's TEXCOORD_0 layout, in texels per
// world millimetre: sqrt(texel area / surface area), the surface transformed by worldFromObject
// (scene units: metres). Accumulates into uvArea / surfaceAreaMm2 so several primitives sharing
// a material combine; density = sqrt(uvArea * width * height / surfaceAreaMm2).
// The UV rule shared by texture-space diffusion and curvature bakes: a material's triangles have a
// TEXCOORD_0 layout when their summed UV area (accumulateTexelDensity's uvArea, in units of the
// unit square) exceeds 1e-9; none: no TEXCOORD_0 (every UV 0), or every UV the same.
inline constexpr double kMinUvLayoutArea = 1e-9;
inline bool hasUvLayout(double uvArea) { return uvArea > kMinUvLayoutArea; }

PRESKIN_API void accumulateTexelDensity(const Primitive& primitive, const glm::mat4& worldFromObject, double& uvArea,
                                        double& surfaceAreaMm2);
PRESKIN_API float texelsPerMm(double uvArea, double surfaceAreaMm2, uint32_t width, uint32_t height);

}  // namespace preskin
