#version 460
// fullscreen_single.vert: a full-viewport triangle into one layer, without multiview
// (fullscreen_vertex.glsl; the texture-space baseline's blur passes).
#extension GL_GOOGLE_include_directive : require
#define PRESKIN_EYE_INDEX 0
#include "fullscreen_vertex.glsl"
