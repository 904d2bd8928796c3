#version 460
// forward.vert: the forward pass's vertex stage drawing every eye with multiview: the eye is
// gl_ViewIndex. The stage itself is forward_vertex.glsl.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_multiview : require
#define PRESKIN_EYE_INDEX gl_ViewIndex
#include "forward_vertex.glsl"
