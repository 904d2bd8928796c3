#version 460
// forward.frag: the one forward pass's fragment stage (forward_fragment.glsl).
#extension GL_GOOGLE_include_directive : require
#include "forward_fragment.glsl"
