#version 460
// shadow.vert: transform into the directional light's orthographic shadow map; depth only, and
// the UV for alpha-masked materials (shadow_mask.frag).
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"

layout(set = 0, binding = kBindingFrame) uniform Frame { FrameUniforms frame; };
layout(std430, set = 0, binding = kBindingInstances) readonly buffer Instances { GpuInstance instances[]; };
layout(push_constant) uniform Push { DrawPush draw; };

layout(location = kAttributePosition) in vec3 inPositionOs;
layout(location = kAttributeUv0) in vec2 inUv0;

layout(location = 0) out vec2 outUv0;

void main() {
    vec4 positionWs = instances[draw.indices.x].worldFromObject * vec4(inPositionOs, 1.0);
    gl_Position = frame.shadowClipFromWorld * positionWs;
    outUv0 = inUv0;
}
