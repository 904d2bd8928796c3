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
PRESKIN_CONST(uint, kSkinAll, 127u)

// Quality tiers (SkinQuality, `--skin-quality`, PRESKIN_SKIN_QUALITY in a host shader): the
// techniques each compiles in, chosen by what each costs and buys (docs/skin-cost.md). High is
// every technique; Medium leaves out the opposing neighbours' light and the second specular
// lobe; Low keeps the pre-integrated diffuse, the SH transfer and the per-channel normals.
PRESKIN_CONST(uint, kSkinQualityLow, 11u)     // kSkinLutDiffuse | kSkinNormalPrefilter | kSkinShAmbient
PRESKIN_CONST(uint, kSkinQualityMedium, 31u)  // Low | kSkinPenumbra | kSkinTransmission
PRESKIN_CONST(uint, kSkinQualityHigh, 127u)   // kSkinAll

PRESKIN_GPU_END

#endif
