// One light as the shaders read it (KHR_lights_punctual: directional, point, spot; and the area
// lights of PRESKIN_lights_area: sphere, tube, rectangle, disc),
// shared by C++ (<preskin/LightRecord.h>) and GLSL (preskin/lights.glsl, which needs nothing
// else, so a host can fill its own light buffer with this struct).
#ifndef PRESKIN_SHARED_LIGHT_H
#define PRESKIN_SHARED_LIGHT_H

#include "shared/common.h"

PRESKIN_GPU_BEGIN

PRESKIN_CONST(uint, kLightDirectional, 0)
PRESKIN_CONST(uint, kLightPoint, 1)
PRESKIN_CONST(uint, kLightSpot, 2)
PRESKIN_CONST(uint, kLightSphere, 3)
PRESKIN_CONST(uint, kLightTube, 4)
PRESKIN_CONST(uint, kLightRectangle, 5)
PRESKIN_CONST(uint, kLightDisc, 6)

// One light. Directional lights are not clustered; they are evaluated for every pixel. Area
// lights (world metres):
//   sphere:    spotScaleOffset.x radius;
//   tube:      directionType.xyz the axis times half the length, spotScaleOffset.x radius;
//   rectangle: directionType.xyz the width axis times half the width, spotScaleOffset.xyz the
//              height axis times half the height; it emits along cross(height, width);
//   disc:      directionType.xyz the unit normal it emits along, spotScaleOffset.x radius.
// Directional lights: spotScaleOffset.z the sine of their angular radius (0: parallel light).
struct GpuLight {
    vec4 positionRange;      // xyz position (world, m), w range (m); 0 = unlimited
    vec4 directionType;      // xyz direction the light travels (world; area lights above), w type (kLight*)
    vec4 colorIntensity;     // rgb linear colour * intensity (lux or candela), w shadow index (-1: none)
    vec4 spotScaleOffset;    // x,y: KHR_lights_punctual cone attenuation scale and offset (area lights above)
};
PRESKIN_CHECK_SIZE(GpuLight, 64)

PRESKIN_GPU_END

#endif
