#version 460
// texture_irradiance.vert: the texture-space baseline's irradiance pass: a skin mesh laid out
// by its TEXCOORD_0 (forward_vertex.glsl, PRESKIN_UV_SPACE), lit as eye 0 sees it.
#extension GL_GOOGLE_include_directive : require
#define PRESKIN_EYE_INDEX 0
#define PRESKIN_UV_SPACE
#include "forward_vertex.glsl"
