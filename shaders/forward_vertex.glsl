// forward_vertex.glsl: the forward pass's vertex stage, shared by its two entry points, which
// differ only in where the eye comes from (see <preskin/Renderer.h>, EyeDrawing):
//   forward.vert         multiview: the eye is gl_ViewIndex (one view per eye);
//   forward_layers.vert  instanced layers: one instance per eye, the eye is gl_InstanceIndex and
//                        the vertex is sent to array layer gl_Layer = eye.
// Transforms one mesh instance into the eye's clip space; passes the world-space tangent frame,
// TEXCOORD_0, per-vertex curvature (object units -> 1/m in world space), which are the same for
// every eye, and the eye index for the fragment stage; for skin, the geometric normal prefiltered
// per colour channel from the normal basis (vertex binding 1). Skin pipelines with per-vertex curvature
// also find the skin terms that depend on curvature alone (preskin/skin_vertex.glsl: the SH
// transfer, the shadow lookup's lift, the diffuse row's smoothed ramp, the sphere transmittance; see forward_specialization.glsl
// for when), which the fragment stage interpolates instead of finding them per fragment. The
// including file defines PRESKIN_EYE_INDEX (and PRESKIN_WRITE_LAYER for layered drawing).
#include "forward_material.glsl"

layout(set = 0, binding = kBindingFrame) uniform Frame { FrameUniforms frame; };
layout(std430, set = 0, binding = kBindingInstances) readonly buffer Instances { GpuInstance instances[]; };
layout(set = 0, binding = kBindingDiffuseLut) uniform sampler2DArray diffuseLut;
layout(set = 0, binding = kBindingShTransferLut) uniform sampler2DArray shTransferLut;
layout(set = 0, binding = kBindingTransmittanceLut) uniform sampler2DArray transmittanceLut;
layout(push_constant) uniform Push { DrawPush draw; };
layout(set = 1, binding = kBindingProfileWeightTexture) uniform sampler2D profileWeightTexture;
layout(set = 1, binding = kBindingCurvatureTexture) uniform sampler2D curvatureTexture;

#include "preskin/skin_vertex.glsl"

// The forward pass's depth prepass draws opaque meshes with this stage alone (no fragment stage,
// Renderer::Impl::recordForwardPass): their positions must come out bit for bit the same in both,
// so what computes them is precise (no fused or reordered arithmetic that either compile could
// choose differently).
precise gl_Position;

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
layout(location = 5) flat out uint outEye;
layout(location = 6) out vec3 outShTransferRed;
layout(location = 7) out vec3 outShTransferGreen;
layout(location = 8) out vec3 outShTransferBlue;
layout(location = 9) out vec2 outShadowLift;               // kSkinLiftPerVertex: preskinSkinShadowLift
layout(location = 10) out vec3 outSphereTransmittance;     // kSkinSphereTransmittancePerVertex
layout(location = 11) out vec3 outNormalRedWs;             // skin: the per-channel prefiltered geometric normals
layout(location = 12) out vec3 outNormalGreenWs;
layout(location = 13) out vec3 outNormalBlueWs;
layout(location = 14) out vec3 outOpposingFacing;          // skin: the opposing neighbours' light's lookup for
layout(location = 15) out vec3 outOpposingShadowUvZ;       // the shadow light (preskinSkinOpposingLookup)
layout(location = 16) out vec2 outOpposingDzPerTexel;
layout(location = 17) out vec3 outRowFitScale;             // kSkinRowFitPerVertex: preskinDiffuseFit
layout(location = 18) out vec3 outRowFitWidth;

void main() {
    uint eye = uint(PRESKIN_EYE_INDEX);
    GpuInstance instance = instances[draw.indices.x];
    vec4 positionWs = instance.worldFromObject * vec4(inPositionOs, 1.0);
    outPositionWs = positionWs.xyz;
    outNormalWs = mat3(instance.normalWorldFromObject) * inNormalOs;
    outTangentWs = vec4(mat3(instance.worldFromObject) * inTangentOs.xyz, inTangentOs.w);
    outUv0 = inUv0;
    outNormalRedWs = outNormalWs;
    outNormalGreenWs = outNormalWs;
    outNormalBlueWs = outNormalWs;
    outOpposingFacing = kPreskinOpposingNone.facing;
    outOpposingShadowUvZ = kPreskinOpposingNone.shadowUvZ;
    outOpposingDzPerTexel = kPreskinOpposingNone.dzPerTexel;
    // The material's profile mix at this vertex, as the fragment stage finds it at its texel.
    PreskinProfileMix profile = materialProfileMix(
        materialBlendedProfiles() > 0 ? textureLod(profileWeightTexture, inUv0, 0.0).rgb : vec3(0.0));
    if (kMaterialModel == kModelSkin && (kSkinFeatures & kSkinNormalPrefilter) != 0u) {
        // The basis weights of the mix's profiles, weighted.
        vec4 weights[3];
        for (int c = 0; c < 3; ++c) {
            weights[c] = profile.weight.x * material.skinNormalBasis[c];
            if (kProfileMix > 1u)
                weights[c] += profile.weight.y * material.skinNormalBasis[3 + c] +
                              profile.weight.z * material.skinNormalBasis[6 + c] +
                              profile.weight.w * material.skinNormalBasis[9 + c];
        }
        mat3 normalWorldFromObject = mat3(instance.normalWorldFromObject);
        outNormalRedWs = normalWorldFromObject * preskinPrefilteredNormal(inNormalOs, inNormalBasis, weights[0]);
        outNormalGreenWs = normalWorldFromObject * preskinPrefilteredNormal(inNormalOs, inNormalBasis, weights[1]);
        outNormalBlueWs = normalWorldFromObject * preskinPrefilteredNormal(inNormalOs, inNormalBasis, weights[2]);
        // The opposing sums keep their length (a share of the light), not the transform's scale.
        if ((kSkinFeatures & kSkinOpposingLight) != 0u && frame.shadowDirectionWs.w > 0.5) {
            vec3 o[3] = vec3[3](preskinOpposingNormal(inOpposing, weights[0]),
                                preskinOpposingNormal(inOpposing, weights[1]),
                                preskinOpposingNormal(inOpposing, weights[2]));
            for (int c = 0; c < 3; ++c) {
                vec3 ws = normalWorldFromObject * o[c];
                float len = length(ws);
                o[c] = len > 0.0 ? ws * (length(o[c]) / len) : vec3(0.0);
            }
            PreskinOpposingLookup lookup = preskinSkinOpposingLookup(
                frame.shadowClipFromWorld, frame.shadowParams, positionWs.xyz,
                mat3(instance.worldFromObject) * inOpposingCentroid, o[0], o[1], o[2], -frame.shadowDirectionWs.xyz,
                material.skinScatter.x);
            outOpposingFacing = lookup.facing;
            outOpposingShadowUvZ = lookup.shadowUvZ;
            outOpposingDzPerTexel = lookup.dzPerTexel;
        }
    }
    outCurvaturePerM = inCurvature * instance.params.x;
    outEye = eye;
    // Skin's per-vertex terms (preskin/skin_vertex.glsl), for the vertex's profile mix.
    // The curvature the per-vertex terms are found at: a curvature map's at the vertex.
    float termsCurvaturePerM = outCurvaturePerM;
    if (kSkinCurvatureSource == kCurvatureSourceTexture)
        termsCurvaturePerM = (textureLod(curvatureTexture, transformUv(material.uv[0], inUv0), 0.0).r - material.skinScatter.y) *
                             material.skinScatter.z;
    float curvaturePerMm = preskinCurvatureProfilePerMm(termsCurvaturePerM, material.skinScatter.x);
    PreskinShTransfer t = PreskinShTransfer(vec3(0.0), vec3(0.0), vec3(0.0));
    if (kSkinShPerVertex) t = preskinShTransfer(profile, shTransferLut, curvaturePerMm);
    outShTransferRed = t.red;
    outShTransferGreen = t.green;
    outShTransferBlue = t.blue;
    outShadowLift = vec2(0.0);
    if (kSkinLiftPerVertex)
        outShadowLift = preskinSkinShadowLift(curvaturePerMm, material.skinScatter.x, profile);
    PreskinDiffuseFit fit = kPreskinDiffuseFitLambert;
    if (kSkinRowFitPerVertex) fit = preskinDiffuseFit(profile, diffuseLut, curvaturePerMm);
    outRowFitScale = fit.scale;
    outRowFitWidth = fit.width;
    outSphereTransmittance = vec3(0.0);
    if (kSkinSphereTransmittancePerVertex && frame.shadowDirectionWs.w > 0.5)
        outSphereTransmittance = preskinSkinSphereTransmittance(profile, transmittanceLut, curvaturePerMm,
                                                                normalize(outNormalWs), -frame.shadowDirectionWs.xyz,
                                                                kSkinFeatures);
#ifdef PRESKIN_UV_SPACE
    // The texture-space baseline's irradiance pass (texture_irradiance.vert): the mesh laid out by
    // its TEXCOORD_0 over the irradiance texture.
    gl_Position = vec4(inUv0 * 2.0 - 1.0, 0.5, 1.0);
#else
    gl_Position = frame.eyes[eye].clipFromWorld * positionWs;
#endif
#ifdef PRESKIN_WRITE_LAYER
    gl_Layer = int(eye);
#endif
}
