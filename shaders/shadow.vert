#version 460
// shadow.vert: depth-only transform into the directional light's orthographic shadow map.
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"

layout(set = 0, binding = kBindingFrame) uniform Frame { FrameUniforms frame; };
layout(std430, set = 0, binding = kBindingInstances) readonly buffer Instances { GpuInstance instances[]; };
layout(push_constant) uniform Push { DrawPush draw; };

layout(location = kAttributePosition) in vec3 inPositionOs;

void main() {
    vec4 positionWs = instances[draw.indices.x].worldFromObject * vec4(inPositionOs, 1.0);
    gl_Position = frame.shadowClipFromWorld * positionWs;
}
