#version 460
// fullscreen.vert: a full-viewport triangle with multiview (fullscreen_vertex.glsl).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_multiview : require
#define PRESKIN_EYE_INDEX gl_ViewIndex
#include "fullscreen_vertex.glsl"
