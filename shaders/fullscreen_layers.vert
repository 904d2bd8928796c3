#version 460
// fullscreen_layers.vert: a full-viewport triangle as one instance per eye into array layer
// gl_Layer = eye (fullscreen_vertex.glsl; EyeDrawing in <preskin/Renderer.h>).
#extension GL_GOOGLE_include_directive : require
#extension GL_ARB_shader_viewport_layer_array : require
#define PRESKIN_EYE_INDEX gl_InstanceIndex
#define PRESKIN_WRITE_LAYER
#include "fullscreen_vertex.glsl"
