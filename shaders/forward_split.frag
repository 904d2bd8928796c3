#version 460
// forward_split.frag: the forward pass's fragment stage for the screen-space baseline: skin's
// diffuse light to its own attachment (forward_fragment.glsl, PRESKIN_SPLIT_DIFFUSE).
#extension GL_GOOGLE_include_directive : require
#define PRESKIN_SPLIT_DIFFUSE
#include "forward_fragment.glsl"
