#version 460
// texture_irradiance.frag: the texture-space baseline's irradiance pass: skin's diffuse light for
// a white albedo and the surface's stretch, per texel (forward_fragment.glsl,
// PRESKIN_TEXTURE_IRRADIANCE).
#extension GL_GOOGLE_include_directive : require
#define PRESKIN_TEXTURE_IRRADIANCE
#include "forward_fragment.glsl"
