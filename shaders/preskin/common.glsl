// preskin/common.glsl: constants and small helpers shared by every preskin include.
#ifndef PRESKIN_COMMON_GLSL
#define PRESKIN_COMMON_GLSL

#include "shared/constants.h"

const float PRESKIN_PI = kPi;

float preskinSaturate(float x) { return clamp(x, 0.0, 1.0); }
vec3 preskinSaturate(vec3 x) { return clamp(x, vec3(0.0), vec3(1.0)); }
float preskinLuminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

#endif
