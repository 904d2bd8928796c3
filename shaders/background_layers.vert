#version 460
// background_layers.vert: the backdrop's vertex stage as one instance per eye into array layer
// gl_Layer = eye (background_vertex.glsl; EyeDrawing in <preskin/Renderer.h>).
#extension GL_GOOGLE_include_directive : require
#extension GL_ARB_shader_viewport_layer_array : require
#define PRESKIN_EYE_INDEX gl_InstanceIndex
#define PRESKIN_WRITE_LAYER
#include "background_vertex.glsl"
