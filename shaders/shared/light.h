// One punctual light as the shaders read it (KHR_lights_punctual: directional, point, spot),
// shared by C++ (<preskin/LightRecord.h>) and GLSL (preskin/lights.glsl, which needs nothing
// else, so a host can fill its own light buffer with this struct).
#ifndef PRESKIN_SHARED_LIGHT_H
#define PRESKIN_SHARED_LIGHT_H

#include "shared/common.h"

PRESKIN_GPU_BEGIN

PRESKIN_CONST(uint, kLightDirectional, 0)
PRESKIN_CONST(uint, kLightPoint, 1)
PRESKIN_CONST(uint, kLightSpot, 2)

// One punctual light. Directional lights are not clustered; they are evaluated for every pixel.
struct GpuLight {
    vec4 positionRange;      // xyz position (world, m), w range (m); 0 = unlimited
    vec4 directionType;      // xyz direction the light travels (world), w type (kLight*)
    vec4 colorIntensity;     // rgb linear colour * intensity (lux or candela), w shadow index (-1: none)
    vec4 spotScaleOffset;    // x,y: KHR_lights_punctual cone attenuation scale and offset
};
PRESKIN_CHECK_SIZE(GpuLight, 64)

PRESKIN_GPU_END

#endif
