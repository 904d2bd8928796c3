#version 460
// forward.frag: the one forward pass. Standard glTF metal-rough materials and (kModelSkin)
// pre-integrated skin, for every light of the fragment's light list, plus L2 SH ambient and
// emissive; tone-mapped here when the target is an 8-bit display format. Everything skin needs
// happens in this shader: no extra passes, no extra render targets.
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"

layout(constant_id = kSpecMaterialModel) const uint kMaterialModel = kModelStandard;
layout(constant_id = kSpecOutputMode) const uint kOutputMode = kOutputTonemapped;
layout(constant_id = kSpecDebugView) const uint kDebugView = kDebugNone;
layout(constant_id = kSpecAlphaMode) const uint kAlphaMode = 0;
layout(constant_id = kSpecSkinFeatures) const uint kSkinFeatures = kSkinAll;
layout(constant_id = kSpecLightLoop) const uint kLightLoop = kLightLoopAll;

layout(set = 0, binding = kBindingFrame) uniform Frame { FrameUniforms frame; };
layout(std430, set = 0, binding = kBindingLights) readonly buffer Lights { GpuLight lights[]; };
layout(set = 0, binding = kBindingShadowMap) uniform sampler2D shadowMap;
layout(std430, set = 0, binding = kBindingClusterRanges) readonly buffer ClusterRanges { uvec2 clusterRanges[]; };
layout(std430, set = 0, binding = kBindingClusterIndices) readonly buffer ClusterIndices { uint clusterIndices[]; };

layout(set = 1, binding = kBindingMaterial) uniform Material { MaterialUniforms material; };
layout(set = 1, binding = kBindingBaseColorTexture) uniform sampler2D baseColorTexture;
layout(set = 1, binding = kBindingMetallicRoughnessTexture) uniform sampler2D metallicRoughnessTexture;
layout(set = 1, binding = kBindingNormalTexture) uniform sampler2D normalTexture;
layout(set = 1, binding = kBindingOcclusionTexture) uniform sampler2D occlusionTexture;
layout(set = 1, binding = kBindingEmissiveTexture) uniform sampler2D emissiveTexture;

#include "preskin/brdf.glsl"
#include "preskin/lights.glsl"
#include "preskin/shadow.glsl"
#include "preskin/sh.glsl"
#include "preskin/tonemap.glsl"

layout(location = 0) in vec3 inPositionWs;
layout(location = 1) in vec3 inNormalWs;
layout(location = 2) in vec4 inTangentWs;
layout(location = 3) in vec2 inUv0;
layout(location = 4) in float inCurvaturePerM;

layout(location = 0) out vec4 outColor;

vec2 transformUv(GpuUvTransform t, vec2 uv) {
    vec3 p = vec3(uv, 1.0);
    return vec2(dot(t.row0.xyz, p), dot(t.row1.xyz, p));
}

// Tangent-space normal map sample -> world space (glTF convention: +Y up in the map).
vec3 perturbNormal(vec3 mapValue, float scale, vec3 N, vec4 T) {
    vec3 n = mapValue * 2.0 - 1.0;
    n.xy *= scale;
    vec3 t = T.xyz - N * dot(N, T.xyz);
    if (dot(t, t) < 1e-12) return N;
    t = normalize(t);
    vec3 b = cross(N, t) * (T.w < 0.0 ? -1.0 : 1.0);
    return normalize(t * n.x + b * n.y + N * max(n.z, 1e-4));
}

// Index range of the lights this fragment iterates after the directional ones.
void localLightRange(out uint first, out uint count, out bool indirect) {
    uint directional = frame.lightCounts.y;
    if (kLightLoop == kLightLoopClustered) {
        vec2 tile = gl_FragCoord.xy * frame.clusterScale.xy;
        float viewDepth = max(-(frame.viewFromWorld * vec4(inPositionWs, 1.0)).z, 1e-6);
        float slice = log2(viewDepth) * frame.clusterScale.z + frame.clusterScale.w;
        uvec3 c = uvec3(clamp(ivec3(ivec2(tile), int(floor(slice))), ivec3(0), ivec3(frame.clusterDims.xyz) - 1));
        uint cluster = (c.z * frame.clusterDims.y + c.y) * frame.clusterDims.x + c.x;
        uvec2 range = clusterRanges[cluster];
        first = range.x;
        count = range.y;
        indirect = true;
    } else {
        first = directional;
        count = frame.lightCounts.x - directional;
        indirect = false;
    }
}

void main() {
    vec2 uvBase = transformUv(material.uv[0], inUv0);
    vec4 baseColor = material.baseColorFactor * texture(baseColorTexture, uvBase);
    if (kAlphaMode == 1 && baseColor.a < material.emissiveAlphaCutoff.w) discard;

    vec4 mr = texture(metallicRoughnessTexture, transformUv(material.uv[1], inUv0));
    float metallic = clamp(material.pbr.x * mr.b, 0.0, 1.0);
    float roughness = clamp(material.pbr.y * mr.g, 0.03, 1.0);
    float occlusion = 1.0 + material.pbr.w * (texture(occlusionTexture, transformUv(material.uv[3], inUv0)).r - 1.0);
    vec3 emissive = material.emissiveAlphaCutoff.rgb * texture(emissiveTexture, transformUv(material.uv[4], inUv0)).rgb;

    vec3 geometricN = normalize(inNormalWs);
    if (!gl_FrontFacing) geometricN = -geometricN;
    vec3 N = geometricN;
    if (material.textureFlags.w > 0.5)
        N = perturbNormal(texture(normalTexture, transformUv(material.uv[2], inUv0)).rgb, material.pbr.z, geometricN,
                          inTangentWs);
    vec3 V = normalize(frame.cameraPositionWs.xyz - inPositionWs);

    PreskinStandardSurface surface;
    surface.diffuseColor = baseColor.rgb * (1.0 - metallic);
    surface.F0 = mix(vec3(0.04), baseColor.rgb, metallic);
    surface.roughness = roughness;

    PreskinShadowSample shadow;
    shadow.visibility = 1.0;
    shadow.thicknessM = 0.0;
    shadow.kernelWidthM = 0.0;
    if (frame.shadowDirectionWs.w > 0.5)
        shadow = preskinSampleShadow(shadowMap, frame.shadowClipFromWorld, frame.shadowParams, inPositionWs, geometricN);

    vec3 color = vec3(0.0);
    for (uint i = 0; i < frame.lightCounts.y; ++i) {
        GpuLight light = lights[i];
        vec3 L;
        vec3 irradiance;
        preskinLightIncidence(light, inPositionWs, L, irradiance);
        float visibility = light.colorIntensity.w >= 0.0 ? shadow.visibility : 1.0;
        color += preskinStandardLight(surface, N, V, L, irradiance * visibility);
    }
    uint first;
    uint count;
    bool indirect;
    localLightRange(first, count, indirect);
    for (uint i = 0; i < count; ++i) {
        GpuLight light = lights[indirect ? clusterIndices[first + i] : first + i];
        vec3 L;
        vec3 irradiance;
        preskinLightIncidence(light, inPositionWs, L, irradiance);
        color += preskinStandardLight(surface, N, V, L, irradiance);
    }

    // Ambient: SH irradiance for diffuse; for specular the cosine-convolved SH in the
    // reflection direction, exact for rough surfaces and too blurry for glossy ones.
    float NoV = max(dot(N, V), 1e-4);
    vec3 irradianceSh = max(preskinShEvaluate(frame.shRadiance, N, PRESKIN_SH_LAMBERT), vec3(0.0));
    vec3 R = reflect(-V, N);
    vec3 specularSh = max(preskinShEvaluate(frame.shRadiance, R, PRESKIN_SH_LAMBERT), vec3(0.0)) / PRESKIN_PI;
    vec3 envBrdf = preskinEnvBrdfApprox(surface.F0, roughness, NoV);
    color += (surface.diffuseColor * irradianceSh / PRESKIN_PI * (vec3(1.0) - envBrdf) + specularSh * envBrdf) * occlusion;
    color += emissive;

    if (kDebugView == kDebugNormals) color = N * 0.5 + 0.5;
    else if (kDebugView == kDebugShadow) color = vec3(shadow.visibility);
    else if (kDebugView == kDebugShAmbient) color = surface.diffuseColor * irradianceSh / PRESKIN_PI;
    else if (kDebugView == kDebugLightCount) {
        float t = clamp(float(count) / 32.0, 0.0, 1.0);
        color = vec3(smoothstep(0.3, 0.7, t), sin(t * PRESKIN_PI), smoothstep(0.6, 0.2, t)) * (count > 0 ? 1.0 : 0.1);
    }

    color *= (kDebugView == kDebugNone) ? frame.cameraPositionWs.w : 1.0;
    float alpha = kAlphaMode == 2 ? baseColor.a : 1.0;
    outColor = vec4(kOutputMode == kOutputTonemapped ? preskinTonemapNeutral(max(color, vec3(0.0))) : color, alpha);
}
