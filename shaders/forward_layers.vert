#version 460
// forward_layers.vert: the forward pass's vertex stage drawing every eye as one instance per eye
// into array layer gl_Layer = eye, for devices whose multiview is unsound (EyeDrawing in
// <preskin/Renderer.h>). The stage itself is forward_vertex.glsl.
#extension GL_GOOGLE_include_directive : require
#extension GL_ARB_shader_viewport_layer_array : require
#define PRESKIN_EYE_INDEX gl_InstanceIndex
#define PRESKIN_WRITE_LAYER
#include "forward_vertex.glsl"
