// Bits of the skin technique mask, shared by C++ (SkinFeatures::mask) and GLSL (skin.glsl).
#ifndef PRESKIN_SHARED_SKIN_FEATURES_H
#define PRESKIN_SHARED_SKIN_FEATURES_H

#include "shared/common.h"

PRESKIN_GPU_BEGIN

PRESKIN_CONST(uint, kSkinLutDiffuse, 1u)
PRESKIN_CONST(uint, kSkinNormalPrefilter, 2u)
PRESKIN_CONST(uint, kSkinPenumbra, 4u)
PRESKIN_CONST(uint, kSkinShAmbient, 8u)
PRESKIN_CONST(uint, kSkinTransmission, 16u)
PRESKIN_CONST(uint, kSkinDualSpecular, 32u)
PRESKIN_CONST(uint, kSkinOpposingLight, 64u)
// With kSkinNormalPrefilter: the normal map read at each channel's level of detail (red blurred
// most); without it the map is read once and each channel's geometric normal carries that sample.
PRESKIN_CONST(uint, kSkinNormalMapLevels, 128u)
// With kSkinPenumbra: skin's wide shadow map (a reduction pass and the wide filter), which carries
// red's scattering past the shadow map's own filter; without it the penumbra LUT acts within the
// shadow filter's reach only.
PRESKIN_CONST(uint, kSkinWidePenumbra, 256u)
// The bits that read the wide shadow map (and record its reduction pass): both must be set.
PRESKIN_CONST(uint, kSkinWideShadowBits, 260u)  // kSkinPenumbra | kSkinWidePenumbra
// With kSkinLutDiffuse: the diffuse LUT read for the lights other than the shadow light (three
// gathers per light, the only technique whose cost grows with the light count). Without it those
// lights get the fragment's row as a smoothed ramp (preskinDiffuseRowFit of preskin/skin.glsl),
// fitted once per vertex or per fragment (preskinDiffuseFit of preskin/skin_vertex.glsl): ALU
// per light, no fetch. No tier has it: with kSkinAll every light reads the table (the renderer
// adds it to a frame without a shadow map, which has no shadow light to tell the key by).
PRESKIN_CONST(uint, kSkinLutOtherLights, 512u)
// Skin's shadow filter over 8 x 8 texels of the shadow map (16 gathers, the standard material's);
// without it 6 x 6 (9 gathers: preskinSkinShadowFilter of preskin/skin.glsl), the Gaussian of
// the same sigma windowed at 3 texels instead of 4 (narrower where sigma exceeds about 1.2), for a
// parallel light (a light with a size keeps 8 x 8: its penumbra is the filter's width). The
// standard material's filter: the mask of standard shading keeps it (SkinFeatures::none()).
PRESKIN_CONST(uint, kSkinFullShadowFilter, 1024u)
// With kSkinLutDiffuse: the diffuse LUT read for the shadow light (without it, the row's fit),
// where the terminator and the penumbra the shadow map draws are.
PRESKIN_CONST(uint, kSkinLutShadowLight, 2048u)
// With kSkinLutDiffuse: each light's diffuse LUT row read at convex skin's curvature along that
// light near the terminator (preskinSkinLightCurvaturePerMm of preskin/skin.glsl; the principal
// curvatures from the normal's screen derivatives) instead of at the mean curvature: a cylinder,
// an ear's rim, a nose's bridge lit across them scatter past the terminator as a sphere of their
// curvature across, not of half of it. ALU per light that reads the table, no fetch.
PRESKIN_CONST(uint, kSkinLightCurvature, 4096u)
PRESKIN_CONST(uint, kSkinAll, 8191u)

// Quality tiers (SkinQuality, `--skin-quality`, PRESKIN_SKIN_QUALITY in a host shader): the
// techniques each compiles in, chosen by what each costs and buys in docs/skin-cost-table.md
// (instructions per frame against compare's error on the head). High is every technique but the
// table for the lights besides the shadow light, which get the row's fit (4 % of the frame;
// compare's views are lit by the shadow light alone; kSkinAll adds it); Medium leaves out
// transmission (5 % of the skin frame; it lights thin parts from behind, which the front views
// do not show) and the second specular lobe; Low also the wide shadow map (its reduction pass and
// nine gathers per fragment, 12 % of the frame; the penumbra LUT stays, within the shadow
// filter's reach, for 2 %) and the normal map's per-channel levels (4 %: a distant face's map
// detail is already under its own mip level), keeping the pre-integrated diffuse, the
// per-channel geometric normals, the SH transfer and the opposing neighbours' light (1 %, the
// largest gain per instruction), shading the shadow light by the row's fit too (1.5 % of the
// high frame; on compare's views 0.002 of Lambert's error, mostly in the terminator band) and
// filtering the shadow map over 6 x 6 texels instead of 8 x 8 (4 % of the low frame; 0.02 of
// Lambert's error, near cast-shadow edges).
PRESKIN_CONST(uint, kSkinQualityLow, 79u)       // kSkinLutDiffuse | kSkinNormalPrefilter | kSkinPenumbra | kSkinShAmbient | kSkinOpposingLight
PRESKIN_CONST(uint, kSkinQualityMedium, 7631u)  // Low | kSkinNormalMapLevels | kSkinWidePenumbra | kSkinFullShadowFilter | kSkinLutShadowLight | kSkinLightCurvature
PRESKIN_CONST(uint, kSkinQualityHigh, 7679u)    // Medium | kSkinTransmission | kSkinDualSpecular (kSkinAll but kSkinLutOtherLights)

PRESKIN_GPU_END

#endif
