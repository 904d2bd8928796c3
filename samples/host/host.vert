#version 460
// host.vert: the host sample's vertex stage. World position, normal and tangent of preskin's
// interleaved Vertex (<preskin/Scene.h>, locations of shared/constants.h), the per-vertex
// curvature scaled from object to world units, and from the normal basis (second vertex stream,
// preskin::computeNormalBasis) the skin's per-channel prefiltered normals and the neighbours that
// face the vertex across a gap (the opposing light). The shadow pass draws with it too (its
// camera the light's clipFromWorld, no fragment stage).
#extension GL_GOOGLE_include_directive : require
#include "preskin/skin_vertex.glsl"

layout(set = 0, binding = 6) uniform Camera {
    mat4 clipFromWorld;
    vec4 normalBasisWeights[3];  // preskin::normalBasisWeights(profile, scatter scale): red, green, blue
} camera;
layout(push_constant) uniform Draw {
    mat4 worldFromObject;
    vec4 normalFromObject[3];  // columns of the inverse transpose; [0].w: 1 / the uniform scale
} draw;

layout(location = kAttributePosition) in vec3 inPositionOs;
layout(location = kAttributeNormal) in vec3 inNormalOs;
layout(location = kAttributeTangent) in vec4 inTangentOs;
layout(location = kAttributeUv0) in vec2 inUv0;
layout(location = kAttributeCurvature) in float inCurvature;
layout(location = kAttributeNormalBasis) in vec3 inNormalBasis[kNormalBasisCount];
layout(location = kAttributeOpposing) in vec3 inOpposing[kNormalBasisCount];
layout(location = kAttributeOpposingCentroid) in vec3 inOpposingCentroid;

layout(location = 0) out vec3 outPositionWs;
layout(location = 1) out vec3 outNormalWs;
layout(location = 2) out vec4 outTangentWs;
layout(location = 3) out vec2 outUv0;
layout(location = 4) out float outCurvaturePerM;
layout(location = 5) out vec3 outNormalRedWs;
layout(location = 6) out vec3 outNormalGreenWs;
layout(location = 7) out vec3 outNormalBlueWs;
layout(location = 8) out vec3 outOpposingRedWs;  // per channel, not unit length: the share of the light they pass on
layout(location = 9) out vec3 outOpposingGreenWs;
layout(location = 10) out vec3 outOpposingBlueWs;
layout(location = 11) out vec3 outOpposingCentroidWs;  // their centroid, from the vertex

void main() {
    vec4 positionWs = draw.worldFromObject * vec4(inPositionOs, 1.0);
    mat3 normalFromObject = mat3(draw.normalFromObject[0].xyz, draw.normalFromObject[1].xyz, draw.normalFromObject[2].xyz);
    outPositionWs = positionWs.xyz;
    outNormalWs = normalFromObject * inNormalOs;
    outTangentWs = vec4(mat3(draw.worldFromObject) * inTangentOs.xyz, inTangentOs.w);
    outUv0 = inUv0;
    outCurvaturePerM = inCurvature * draw.normalFromObject[0].w;
    outNormalRedWs = normalFromObject * preskinPrefilteredNormal(inNormalOs, inNormalBasis, camera.normalBasisWeights[0]);
    outNormalGreenWs = normalFromObject * preskinPrefilteredNormal(inNormalOs, inNormalBasis, camera.normalBasisWeights[1]);
    outNormalBlueWs = normalFromObject * preskinPrefilteredNormal(inNormalOs, inNormalBasis, camera.normalBasisWeights[2]);
    // The opposing sums keep their length (a share of the light), not the transform's scale.
    vec3 opposing[3];
    for (int c = 0; c < 3; ++c) {
        vec3 os = preskinOpposingNormal(inOpposing, camera.normalBasisWeights[c]);
        vec3 ws = normalFromObject * os;
        opposing[c] = length(ws) > 0.0 ? ws * (length(os) / length(ws)) : vec3(0.0);
    }
    outOpposingRedWs = opposing[0];
    outOpposingGreenWs = opposing[1];
    outOpposingBlueWs = opposing[2];
    outOpposingCentroidWs = mat3(draw.worldFromObject) * inOpposingCentroid;
    gl_Position = camera.clipFromWorld * positionWs;
}
