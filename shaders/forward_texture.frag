#version 460
// forward_texture.frag: the forward pass's fragment stage for the texture-space baseline: skin's
// diffuse light read from its blurred irradiance texture (forward_fragment.glsl,
// PRESKIN_TEXTURE_DIFFUSION).
#extension GL_GOOGLE_include_directive : require
#define PRESKIN_TEXTURE_DIFFUSION
#include "forward_fragment.glsl"
