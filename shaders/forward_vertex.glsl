// forward_vertex.glsl: the forward pass's vertex stage, shared by its two entry points, which
// differ only in where the eye comes from (see <preskin/Renderer.h>, EyeDrawing):
//   forward.vert         multiview: the eye is gl_ViewIndex (one view per eye);
//   forward_layers.vert  instanced layers: one instance per eye, the eye is gl_InstanceIndex and
//                        the vertex is sent to array layer gl_Layer = eye.
// Transforms one mesh instance into the eye's clip space; passes the world-space tangent frame,
// TEXCOORD_0, per-vertex curvature (object units -> 1/m in world space), which are the same for
// every eye, and the eye index for the fragment stage. Skin pipelines with per-vertex curvature
// also find the skin terms that depend on curvature alone (preskin/skin_vertex.glsl: the SH
// transfer, the shadow lookup's lift, the sphere transmittance; see forward_specialization.glsl
// for when), which the fragment stage interpolates instead of finding them per fragment. The
// including file defines PRESKIN_EYE_INDEX (and PRESKIN_WRITE_LAYER for layered drawing).
#include "forward_material.glsl"

layout(set = 0, binding = kBindingFrame) uniform Frame { FrameUniforms frame; };
layout(std430, set = 0, binding = kBindingInstances) readonly buffer Instances { GpuInstance instances[]; };
layout(set = 0, binding = kBindingShTransferLut) uniform sampler2DArray shTransferLut;
layout(set = 0, binding = kBindingTransmittanceLut) uniform sampler2DArray transmittanceLut;
layout(push_constant) uniform Push { DrawPush draw; };

#include "preskin/skin_vertex.glsl"

layout(location = kAttributePosition) in vec3 inPositionOs;
layout(location = kAttributeNormal) in vec3 inNormalOs;
layout(location = kAttributeTangent) in vec4 inTangentOs;
layout(location = kAttributeUv0) in vec2 inUv0;
layout(location = kAttributeCurvature) in float inCurvature;

layout(location = 0) out vec3 outPositionWs;
layout(location = 1) out vec3 outNormalWs;
layout(location = 2) out vec4 outTangentWs;
layout(location = 3) out vec2 outUv0;
layout(location = 4) out float outCurvaturePerM;
layout(location = 5) flat out uint outEye;
layout(location = 6) out vec3 outShTransferRed;
layout(location = 7) out vec3 outShTransferGreen;
layout(location = 8) out vec3 outShTransferBlue;
layout(location = 9) out vec2 outShadowLift;               // kSkinLiftPerVertex: preskinSkinShadowLift
layout(location = 10) out vec3 outSphereTransmittance;     // kSkinSphereTransmittancePerVertex

void main() {
    uint eye = uint(PRESKIN_EYE_INDEX);
    GpuInstance instance = instances[draw.indices.x];
    vec4 positionWs = instance.worldFromObject * vec4(inPositionOs, 1.0);
    outPositionWs = positionWs.xyz;
    outNormalWs = mat3(instance.normalWorldFromObject) * inNormalOs;
    outTangentWs = vec4(mat3(instance.worldFromObject) * inTangentOs.xyz, inTangentOs.w);
    outUv0 = inUv0;
    outCurvaturePerM = inCurvature * instance.params.x;
    outEye = eye;
    // Skin's per-vertex terms (preskin/skin_vertex.glsl), for the material's own profile.
    PreskinProfileMix profile = preskinSingleProfile(materialLutMapping(0), material.skinProfileLayers.x);
    float curvaturePerMm = preskinCurvatureProfilePerMm(outCurvaturePerM, material.skinScatter.x);
    PreskinShTransfer t = PreskinShTransfer(vec3(0.0), vec3(0.0), vec3(0.0));
    if (kSkinShPerVertex) t = preskinShTransfer(profile, shTransferLut, curvaturePerMm);
    outShTransferRed = t.red;
    outShTransferGreen = t.green;
    outShTransferBlue = t.blue;
    outShadowLift = vec2(0.0);
    if (kSkinLiftPerVertex)
        outShadowLift = preskinSkinShadowLift(curvaturePerMm, material.skinScatter.x, materialLutMapping(0));
    outSphereTransmittance = vec3(0.0);
    if (kSkinSphereTransmittancePerVertex && frame.shadowDirectionWs.w > 0.5)
        outSphereTransmittance = preskinSkinSphereTransmittance(profile, transmittanceLut, curvaturePerMm,
                                                                normalize(outNormalWs), -frame.shadowDirectionWs.xyz,
                                                                kSkinFeatures);
    gl_Position = frame.eyes[eye].clipFromWorld * positionWs;
#ifdef PRESKIN_WRITE_LAYER
    gl_Layer = int(eye);
#endif
}
