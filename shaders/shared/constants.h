// Numbers that C++ and GLSL must agree on, written once: pi, the Lambert and SH basis constants,
// the skin model's fixed constants, vertex attribute locations and the codes of enums the shaders
// branch on (the C++ enums are checked against these with static_assert in engine/src/render).
// Float literals carry an `f` suffix so they read the same in both languages.
#ifndef PRESKIN_SHARED_CONSTANTS_H
#define PRESKIN_SHARED_CONSTANTS_H

#include "shared/common.h"

PRESKIN_GPU_BEGIN

PRESKIN_CONST(float, kPi, 3.14159265358979323846f)

// Lambert's zonal coefficients of bands 0, 1, 2: the clamped cosine's convolution of L2 SH
// radiance into irradiance (Ramamoorthi & Hanrahan 2001).
PRESKIN_CONST(float, kShLambert0, kPi)
PRESKIN_CONST(float, kShLambert1, 2.0f * kPi / 3.0f)
PRESKIN_CONST(float, kShLambert2, kPi / 4.0f)

// Real SH basis normalisation constants, Y_lm = k * polynomial(direction):
// Y00 = kShY00; Y1m = kShY1 * (y, z, x); Y2,-2 / Y2,-1 / Y2,1 = kShY2 * (xy, yz, xz);
// Y20 = kShY20 * (3 z^2 - 1); Y22 = kShY22 * (x^2 - y^2).
PRESKIN_CONST(float, kShY00, 0.282095f)
PRESKIN_CONST(float, kShY1, 0.488603f)
PRESKIN_CONST(float, kShY2, 1.092548f)
PRESKIN_CONST(float, kShY20, 0.315392f)
PRESKIN_CONST(float, kShY22, 0.546274f)

// Skin: F0 of a dielectric of IOR 1.4 ((1.4 - 1)^2 / (1.4 + 1)^2), times the material's
// specular intensity and map; the depth (profile mm) below the surface from which transmission
// measures the thickness through the shadow map (after Jimenez et al. 2010's shrink).
PRESKIN_CONST(float, kSkinF0, 0.028f)
PRESKIN_CONST(float, kSkinThicknessShrinkMm, 2.0f)
// Skin's light from opposing neighbours (preskinSkinOpposingLight of preskin/skin.glsl), profile
// mm: the shadow lookup at their centroid is lifted this far towards the shaded point and ignores
// occluders nearer than the relief distance along the light (on the head's `lips` view, skin's
// error over Lambert's 0.661 with 3 mm, 0.622 with 6, 0.541 with 15, 0.535 with no shadow lookup
// at all: the relief that forms a gap shadows the gap, not its lit rims).
PRESKIN_CONST(float, kSkinOpposingLiftMm, 0.5f)
PRESKIN_CONST(float, kSkinOpposingReliefMm, 15.0f)

// The shadow pass's depth bias (vkCmdSetDepthBias): the constant factor and the slope factor,
// which moves each texel's stored depth away from the light by that many times its depth slope
// per texel (transmission adds it back to the thickness it reads).
PRESKIN_CONST(float, kShadowDepthBiasConstant, 1.0f)
PRESKIN_CONST(float, kShadowDepthBiasSlope, 1.5f)

// Vertex attribute locations of the forward and shadow passes (Vertex of <preskin/Scene.h>).
PRESKIN_CONST(uint, kAttributePosition, 0)
PRESKIN_CONST(uint, kAttributeNormal, 1)
PRESKIN_CONST(uint, kAttributeTangent, 2)
PRESKIN_CONST(uint, kAttributeUv0, 3)
PRESKIN_CONST(uint, kAttributeCurvature, 4)
// The skin's normal basis (<preskin/NormalBasis.h>), a second vertex stream (binding 1): the mesh
// normals averaged by kNormalBasisCount Gaussians, one vec3 each at consecutive locations; then
// the opposing neighbours' normal integrals (as many) and their centroid's offset.
PRESKIN_CONST(uint, kNormalBasisCount, 4)
PRESKIN_CONST(uint, kAttributeNormalBasis, 5)
PRESKIN_CONST(uint, kAttributeOpposing, 9)
PRESKIN_CONST(uint, kAttributeOpposingCentroid, 13)

// preskin::AlphaMode (<preskin/Scene.h>).
PRESKIN_CONST(uint, kAlphaOpaque, 0)
PRESKIN_CONST(uint, kAlphaMask, 1)
PRESKIN_CONST(uint, kAlphaBlend, 2)

// preskin::CurvatureSource (<preskin/SkinMaterial.h>).
PRESKIN_CONST(uint, kCurvatureSourceVertex, 0)
PRESKIN_CONST(uint, kCurvatureSourceTexture, 1)
PRESKIN_CONST(uint, kCurvatureSourceDerivatives, 2)

// preskin::DebugView (<preskin/Renderer.h>).
PRESKIN_CONST(uint, kDebugNone, 0)
PRESKIN_CONST(uint, kDebugCurvature, 1)
PRESKIN_CONST(uint, kDebugNormals, 2)
PRESKIN_CONST(uint, kDebugShadow, 3)
PRESKIN_CONST(uint, kDebugPenumbra, 4)
PRESKIN_CONST(uint, kDebugLightCount, 5)
PRESKIN_CONST(uint, kDebugShAmbient, 6)
PRESKIN_CONST(uint, kDebugTransmission, 7)

PRESKIN_GPU_END

#endif
