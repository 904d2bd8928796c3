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

// Texel density of an image of width x height on a primitive's TEXCOORD_0 layout, in texels per
// world millimetre: sqrt(texel area / surface area), the surface transformed by worldFromObject
// (scene units: metres). Accumulates into uvArea / surfaceAreaMm2 so several primitives sharing
// a material combine; density = sqrt(uvArea * width * height / surfaceAreaMm2).
PRESKIN_API void accumulateTexelDensity(const Primitive& primitive, const glm::mat4& worldFromObject, double& uvArea,
                                        double& surfaceAreaMm2);
PRESKIN_API float texelsPerMm(double uvArea, double surfaceAreaMm2, uint32_t width, uint32_t height);

}  // namespace preskin
