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
PRESKIN_CONST(uint, kSkinAll, 63u)

PRESKIN_GPU_END

#endif
