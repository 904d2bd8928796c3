#version 460
// forward.vert: transforms one mesh instance for the forward pass into the eye of this
// multiview view (gl_ViewIndex); passes the world-space tangent frame, TEXCOORD_0 and per-vertex
// curvature (object units -> 1/m in world space), which are the same for every eye.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_multiview : require
#include "shared/gpu_types.h"

layout(set = 0, binding = kBindingFrame) uniform Frame { FrameUniforms frame; };
layout(std430, set = 0, binding = kBindingInstances) readonly buffer Instances { GpuInstance instances[]; };
layout(push_constant) uniform Push { DrawPush draw; };

layout(location = 0) in vec3 inPositionOs;
layout(location = 1) in vec3 inNormalOs;
layout(location = 2) in vec4 inTangentOs;
layout(location = 3) in vec2 inUv0;
layout(location = 4) in float inCurvature;

layout(location = 0) out vec3 outPositionWs;
layout(location = 1) out vec3 outNormalWs;
layout(location = 2) out vec4 outTangentWs;
layout(location = 3) out vec2 outUv0;
layout(location = 4) out float outCurvaturePerM;

void main() {
    GpuInstance instance = instances[draw.indices.x];
    vec4 positionWs = instance.worldFromObject * vec4(inPositionOs, 1.0);
    outPositionWs = positionWs.xyz;
    outNormalWs = mat3(instance.normalWorldFromObject) * inNormalOs;
    outTangentWs = vec4(mat3(instance.worldFromObject) * inTangentOs.xyz, inTangentOs.w);
    outUv0 = inUv0;
    outCurvaturePerM = inCurvature * instance.params.x;
    gl_Position = frame.eyes[gl_ViewIndex].clipFromWorld * positionWs;
}
