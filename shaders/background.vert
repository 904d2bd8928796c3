#version 460
// background.vert: the backdrop's vertex stage with multiview (background_vertex.glsl).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_multiview : require
#define PRESKIN_EYE_INDEX gl_ViewIndex
#include "background_vertex.glsl"
