// forward_fragment.glsl: the fragment stage of the one forward pass (forward.frag), and of the
// baselines' variants: forward_split.frag (screen-space, PRESKIN_SPLIT_DIFFUSE),
// texture_irradiance.frag and forward_texture.frag (texture-space, PRESKIN_TEXTURE_IRRADIANCE and
// PRESKIN_TEXTURE_DIFFUSION). Standard glTF metal-rough materials and (kModelSkin)
// pre-integrated skin, for every light of the fragment's light list, plus the environment (L2 SH
// diffuse, prefiltered specular: preskin/ibl.glsl) and emissive; tone-mapped here when the target
// is an 8-bit display format. Everything skin needs happens in this shader: no extra passes, no
// extra render targets. Each eye (inEye, from the vertex stage) has its own camera position
// (view vector, specular); the light grid is shared by all eyes and found by projecting the
// fragment's world position with the grid's camera.
// The derivative curvature fallback (preskinCurvatureFromDerivatives) is per eye: screen-space
// derivatives differ between the eyes, per-vertex and texture curvature do not.
// With PRESKIN_SPLIT_DIFFUSE (forward_split.frag: RenderSettings::diffusion ScreenSpace) skin's
// diffuse light is not added to the colour but written to outDiffuse for the screen-space
// passes to scatter (shaders/screen_diffusion.frag), with every opaque surface's view depth and
// skin's material in outSurface; skin then shades as Lambert (the pipeline's skin features).
// With PRESKIN_TEXTURE_IRRADIANCE (texture_irradiance.frag, drawn in the mesh's UV layout by
// texture_irradiance.vert) skin writes its diffuse light for a white albedo (irradiance times
// (1 - F) / pi, ambient and transmission included) and the surface's metres per texel along u
// and v; with PRESKIN_TEXTURE_DIFFUSION (forward_texture.frag) skin's diffuse light is its albedo
// times that irradiance blurred by its profile (render/TextureDiffusion.h), read at TEXCOORD_0.
#extension GL_EXT_control_flow_attributes : require
#define PRESKIN_UNROLL [[unroll]]  // the shadow filter's loops (preskin/common.glsl)
#include "forward_material.glsl"

layout(set = 0, binding = kBindingFrame) uniform Frame { FrameUniforms frame; };
layout(std430, set = 0, binding = kBindingLights) readonly buffer Lights { GpuLight lights[]; };
layout(set = 0, binding = kBindingShadowMap) uniform sampler2D shadowMap;
layout(set = 0, binding = kBindingDiffuseLut) uniform sampler2DArray diffuseLut;
layout(set = 0, binding = kBindingPenumbraLut) uniform sampler2DArray penumbraLut;
layout(set = 0, binding = kBindingShTransferLut) uniform sampler2DArray shTransferLut;
layout(set = 0, binding = kBindingTransmittanceLut) uniform sampler2DArray transmittanceLut;
layout(std430, set = 0, binding = kBindingClusterRanges) readonly buffer ClusterRanges { uvec2 clusterRanges[]; };
layout(std430, set = 0, binding = kBindingClusterIndices) readonly buffer ClusterIndices { uint clusterIndices[]; };
layout(set = 0, binding = kBindingWideShadowMap) uniform sampler2D wideShadowMap;
layout(set = 0, binding = kBindingPrefilteredEnvironment) uniform samplerCube prefilteredEnvironment;
layout(set = 0, binding = kBindingDfgTable) uniform sampler2D dfgTable;

layout(set = 1, binding = kBindingBaseColorTexture) uniform sampler2D baseColorTexture;
layout(set = 1, binding = kBindingMetallicRoughnessTexture) uniform sampler2D metallicRoughnessTexture;
layout(set = 1, binding = kBindingNormalTexture) uniform sampler2D normalTexture;
layout(set = 1, binding = kBindingOcclusionTexture) uniform sampler2D occlusionTexture;
layout(set = 1, binding = kBindingEmissiveTexture) uniform sampler2D emissiveTexture;
layout(set = 1, binding = kBindingSpecularTexture) uniform sampler2D specularTexture;
layout(set = 1, binding = kBindingDetailNormalTexture) uniform sampler2D detailNormalTexture;
layout(set = 1, binding = kBindingCurvatureTexture) uniform sampler2D curvatureTexture;
layout(set = 1, binding = kBindingProfileWeightTexture) uniform sampler2D profileWeightTexture;

#include "preskin/brdf.glsl"
#include "preskin/ibl.glsl"
#include "preskin/lights.glsl"
#include "preskin/shadow.glsl"
#include "preskin/sh.glsl"
#include "preskin/skin.glsl"
#include "preskin/tonemap.glsl"
#include "shared/cluster_lookup.h"

layout(location = 0) in vec3 inPositionWs;
// The normals at the centroid of the pixel's covered samples: with MSAA the pixel's centre can lie
// outside a small triangle, where the interpolated normal runs past its corners' (single-pixel
// highlights on the head at MSAA 4x). Without MSAA the centroid is the centre.
layout(location = 1) centroid in vec3 inNormalWs;
layout(location = 2) in vec4 inTangentWs;
layout(location = 3) in vec2 inUv0;
layout(location = 4) in float inCurvaturePerM;
layout(location = 5) flat in uint inEye;
layout(location = 6) in vec3 inShTransferRed;  // kSkinShPerVertex: the vertex stage's PreskinShTransfer
layout(location = 7) in vec3 inShTransferGreen;
layout(location = 8) in vec3 inShTransferBlue;
layout(location = 9) in vec2 inShadowLift;               // kSkinLiftPerVertex: preskinSkinShadowLift
layout(location = 10) in vec3 inSphereTransmittance;     // kSkinSphereTransmittancePerVertex
layout(location = 11) centroid in vec3 inNormalRedWs;             // skin: per-channel prefiltered geometric normals
layout(location = 12) centroid in vec3 inNormalGreenWs;
layout(location = 13) centroid in vec3 inNormalBlueWs;
layout(location = 14) in vec3 inOpposingFacing;  // skin: the vertex stage's PreskinOpposingLookup
layout(location = 15) in vec3 inOpposingShadowUvZ;
layout(location = 16) in vec2 inOpposingDzPerTexel;
layout(location = 17) in vec3 inRowFitScale;  // kSkinRowFitPerVertex: the vertex stage's PreskinDiffuseFit
layout(location = 18) in vec3 inRowFitWidth;

layout(location = 0) out vec4 outColor;
#ifdef PRESKIN_TEXTURE_IRRADIANCE
layout(location = 1) out vec2 outStretch;  // metres per texel along u, v
#endif
#ifdef PRESKIN_TEXTURE_DIFFUSION
layout(set = 0, binding = kBindingDiffusionTexture) uniform sampler2DArray diffusionTexture;
layout(push_constant) uniform Push { DrawPush draw; };  // indices.z: the draw's layer of diffusionTexture
#endif
#ifdef PRESKIN_SPLIT_DIFFUSE
layout(location = 1) out vec4 outDiffuse;  // skin: diffuse radiance (exposed), alpha 1; others 0
layout(location = 2) out vec2 outSurface;  // view depth (m); skin: its material index + 1, others 0
layout(push_constant) uniform Push { DrawPush draw; };
#endif

// Tangent-space normal map sample -> world space (glTF convention: +Y up in the map).
vec3 perturbNormal(vec3 mapValue, float scale, vec3 N, vec4 T) {
    vec3 n = mapValue * 2.0 - 1.0;
    n.xy *= scale;
    mat3 tbn = preskinTangentFrame(N, T);
    if (tbn[0] == vec3(0.0)) return N;
    return normalize(tbn * vec3(n.xy, max(n.z, 1e-4)));
}

// Index range of the lights this fragment iterates after the directional ones.
void localLightRange(out uint first, out uint count, out bool indirect) {
    uint directional = frame.lightCounts.y;
    if (kLightLoop == kLightLoopClustered) {
        // The grid's camera holds every eye (shared/cluster_lookup.h, ClusterGrid::froxelAt on the CPU).
        uint cluster = preskinFroxelIndex(frame.clusterFromWorld, frame.clusterScale, frame.clusterDims, inPositionWs);
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

// The shadow light's direction and irradiance (lights[0], directional) from the frame's uniforms:
// a CPU driver (lavapipe) reads a storage buffer lane by lane, and would evaluate a light of
// unknown type's attenuation under a mask.
void shadowLightIncidence(out vec3 L, out vec3 irradiance) {
    L = -frame.shadowDirectionWs.xyz;
    irradiance = frame.shadowIrradiance.rgb;
}

// Light i of the loop after the shadow light: the other directional lights, then the
// fragment's local lights (localLightRange).
GpuLight unshadowedLight(uint i, uint shadowLights, uint first, bool indirect) {
    uint directional = frame.lightCounts.y - shadowLights;
    uint index;
    if (i < directional) index = shadowLights + i;
    else if (indirect) index = clusterIndices[first + (i - directional)];
    else index = first + (i - directional);
    return lights[index];
}

vec3 curvatureHeat(float curvaturePerMm) {
    float t = clamp(sqrt(curvaturePerMm / 0.5), 0.0, 1.0);  // 0 .. 0.5 / mm (radius 2 mm)
    return vec3(smoothstep(0.25, 0.75, t), sin(t * PRESKIN_PI), smoothstep(0.5, 0.0, t));
}

void main() {
    vec2 uvBase = transformUv(material.uv[0], inUv0);
    vec4 baseColor = material.baseColorFactor;
    if (material.hasTextures.x > 0.5) baseColor *= texture(baseColorTexture, uvBase);
    // Alpha mask: without MSAA, discard below the cutoff. With MSAA, alpha-to-coverage: alpha
    // sharpened to a one-pixel ramp around the cutoff, so the coverage mask follows the edge.
    float maskCoverage = 1.0;
    if (kAlphaMode == kAlphaMask) {
        float cutoff = material.emissiveAlphaCutoff.w;
        if (kAlphaToCoverage != 0u)
            maskCoverage = clamp((baseColor.a - cutoff) / max(fwidth(baseColor.a), 1e-4) + 0.5, 0.0, 1.0);
        else if (baseColor.a < cutoff)
            discard;
    }

    vec4 mr = material.hasTextures.y > 0.5 ? texture(metallicRoughnessTexture, transformUv(material.uv[1], inUv0))
                                           : vec4(1.0);
    float metallic = clamp(material.pbr.x * mr.b, 0.0, 1.0);
    float roughness = clamp(material.pbr.y * mr.g, 0.03, 1.0);
    float occlusion = 1.0;
    if (material.hasTextures.z > 0.5)
        occlusion += material.pbr.w * (texture(occlusionTexture, transformUv(material.uv[3], inUv0)).r - 1.0);
    vec3 emissive = material.emissiveAlphaCutoff.rgb;
    if (material.hasTextures.w > 0.5) emissive *= texture(emissiveTexture, transformUv(material.uv[4], inUv0)).rgb;

#ifdef PRESKIN_TEXTURE_IRRADIANCE
    float facingSign = 1.0;  // the mesh's own side: the UV layout's winding says nothing of the view
#else
    float facingSign = gl_FrontFacing ? 1.0 : -1.0;
#endif
    vec3 geometricN = facingSign * normalize(inNormalWs);
    vec2 uvNormal = transformUv(material.uv[2], inUv0);
    bool hasNormalMap = material.textureFlags.w > 0.5;
    // Skin reads its normal maps itself (preskinSkinNormals), the standard model here.
    vec3 N = geometricN;
    if (kMaterialModel != kModelSkin && hasNormalMap)
        N = perturbNormal(texture(normalTexture, uvNormal).rgb, material.pbr.z, geometricN, inTangentWs);
    vec3 V = normalize(frame.eyes[inEye].positionWs.xyz - inPositionWs);
    float NoV = max(dot(N, V), 1e-4);

    PreskinShadowSample shadow;
    shadow.visibility = 1.0;
    shadow.kernelWidthM = 0.0;
    shadow.penumbraWidthM = 0.0;
    shadow.blockerDistanceM = 0.0;
    shadow.gradientWs = vec3(0.0);
    PreskinShadowSample wideShadow = shadow;  // skin with penumbra scattering: the wide map's
    // Skin's signed curvature in profile 1/mm (the shadow lookup and the skin surface use it).
    float skinCurvaturePerMm = 0.0;
    // Skin's diffusion profile, or its profiles blended by the weight texture.
    PreskinProfileMix profiles;
    if (kMaterialModel == kModelSkin) {
        profiles = materialProfileMix(materialBlendedProfiles() > 0 ? texture(profileWeightTexture, inUv0).rgb : vec3(0.0));
        skinCurvaturePerMm = preskinCurvatureProfilePerMm(
            preskinSkinCurvaturePerM(kSkinCurvatureSource, inCurvaturePerM, curvatureTexture, uvBase,
                                     material.skinScatter.y, material.skinScatter.z, geometricN, inPositionWs),
            material.skinScatter.x);
    }
    vec3 shadowPositionWs = inPositionWs;
    if (kMaterialModel == kModelSkin && (kSkinFeatures & kSkinLutDiffuse) != 0u) {
        vec2 lift = inShadowLift;
        if (!kSkinLiftPerVertex) lift = preskinSkinShadowLift(skinCurvaturePerMm, material.skinScatter.x, profiles);
        shadowPositionWs = preskinSkinShadowPosition(inPositionWs, geometricN, -frame.shadowDirectionWs.xyz, lift);
    }
    // The shadow map's transform, read once here, outside the branches that use it: a CPU driver
    // (lavapipe) reads uniform buffers lane by lane, and reads in separate branches are not shared.
    mat4 shadowClipFromWorld = frame.shadowClipFromWorld;
    vec4 shadowParams = frame.shadowParams;
    if (frame.shadowDirectionWs.w > 0.5) {
        float shadowNoL = dot(geometricN, frame.shadowDirectionWs.xyz);  // sign aside: the filters' rise takes |N.L|
        if (kSkinWideShadow) {
            // Skin's wide map (shaders/shadow_reduce.comp: its texels hold their blocks' nearest
            // depths), for red's scattering past the shadow map's filter. Concave skin rises towards
            // the light within the wide kernel's reach of 3 wide texels (preskinSkinConcaveRiseM).
            vec4 wideParams = vec4(frame.wideShadow.z, 1.0, shadowParams.z, frame.wideShadow.y);
            float riseM = preskinSkinConcaveRiseM(skinCurvaturePerMm, material.skinScatter.x, shadowNoL,
                                                  3.0 * frame.wideShadow.z);
            wideShadow = preskinSampleShadow(wideShadowMap, preskinScaledShadowClip(shadowClipFromWorld, frame.wideShadow.x),
                                             wideParams, shadowPositionWs, geometricN,
                                             PreskinShadowFilter(3, 0.75, riseM, frame.wideShadow.w));
        }
        float penumbraPerM = 0.0;
        if (kSizedShadowLight) {
            // A sun's disc seen past an edge d away is tan(sigma) d in radius; the Gaussian closest
            // to its edge's profile (least squares) has 0.545 that as its standard deviation.
            float sinSigma = lights[0].spotScaleOffset.z;
            penumbraPerM = 0.545 * sinSigma * inversesqrt(max(1.0 - sinSigma * sinSigma, 1e-6));
        }
        PreskinShadowFilter shadowFilter = kPreskinShadowMapFilter;
        if (kMaterialModel == kModelSkin)
            shadowFilter = preskinSkinShadowFilter(kSkinFeatures, penumbraPerM, skinCurvaturePerMm, material.skinScatter.x,
                                                   shadowNoL, shadowParams.x);
        shadow = preskinSampleShadow(shadowMap, shadowClipFromWorld, shadowParams, shadowPositionWs, geometricN,
                                     shadowFilter, penumbraPerM);
    }

    uint first;
    uint count;
    bool indirect;
    localLightRange(first, count, indirect);
    uint lightTotal = frame.lightCounts.y + count;
    // The shadow light (lights[0] when there is a shadow map) is shaded on its own, every other
    // light in one loop; the loop is a do-while because a CPU driver (lavapipe) runs a while
    // loop's body once more under an empty lane mask.
    bool hasShadowLight = frame.shadowDirectionWs.w > 0.5;
    uint shadowLights = hasShadowLight ? 1u : 0u;
    uint loopCount = lightTotal - shadowLights;

    PreskinIbl ibl = PreskinIbl(frame.environment.xy, frame.environment.z);
    vec3 color = vec3(0.0);
    vec3 skinDiffuse = vec3(0.0);  // skin's diffuse light (kept apart for PRESKIN_SPLIT_DIFFUSE)
    vec3 debugColor = vec3(0.0);
    vec3 diffuseColor;
    vec3 ambientDiffuse;
    if (kMaterialModel == kModelSkin) {
        // Pre-integrated skin (preskin/skin.glsl). Skin is a dielectric: metallic is ignored.
        const uint features = kSkinFeatures;
        PreskinSkinSurface skin;
#ifdef PRESKIN_TEXTURE_IRRADIANCE
        skin.albedo = vec3(1.0);  // the albedo is applied after the blur (post-scatter)
#else
        skin.albedo = baseColor.rgb;
#endif
        skin.geometricNormal = geometricN;
        // The geometric normal seen through each channel's profile (the vertex stage's normal basis).
        skin.geometricNormalR = facingSign * normalize(inNormalRedWs);
        skin.geometricNormalG = facingSign * normalize(inNormalGreenWs);
        skin.geometricNormalB = facingSign * normalize(inNormalBlueWs);
        if (hasNormalMap) {
            PreskinNormalMaps maps;
            maps.scale = material.pbr.z;
            maps.hasDetail = kSkinDetailNormals;
            maps.detailUvScale = material.textureFlags.y;
            maps.detailScale = material.textureFlags.x;
            maps.lodBias = materialNormalLodBias(profiles);
            maps.levelCount = int(kSkinNormalLevels);
            maps.specularFromLevels = kSkinSpecularFromLevels;
            preskinSkinNormals(normalTexture, detailNormalTexture, maps, uvNormal, geometricN, skin.geometricNormalR,
                               skin.geometricNormalG, skin.geometricNormalB, inTangentWs, features,
                               skin.normalSpecular, skin.normalR, skin.normalG, skin.normalB);
        } else {
            skin.normalSpecular = geometricN;
            skin.normalR = skin.geometricNormalR;
            skin.normalG = skin.geometricNormalG;
            skin.normalB = skin.geometricNormalB;
        }
        N = skin.normalSpecular;
        NoV = max(dot(N, V), 1e-4);
        skin.scatterScale = material.skinScatter.x;
        skin.curvaturePerMm = skinCurvaturePerMm;
        // The principal curvatures about the mean, for each light's row (uniform control flow here).
        skin.curvatureAxis = vec3(0.0);
        skin.curvatureSpreadPerMm = 0.0;
        if ((features & kSkinLightCurvature) != 0u)
            preskinSkinCurvatureSpread(geometricN, skinCurvaturePerMm, skin.scatterScale, dFdx(inPositionWs),
                                       dFdy(inPositionWs), dFdx(geometricN), dFdy(geometricN), skin.curvatureAxis,
                                       skin.curvatureSpreadPerMm);
        skin.roughness = roughness;
        // The specular map, or its copy in an opaque base colour's unused alpha (one read fewer;
        // the material's alpha factor is then 1, GpuScene::uniformsFor).
        float specularMap = kSkinSpecularInBaseAlpha ? baseColor.a
                            : kSkinSpecularMap       ? texture(specularTexture, uvBase).r
                                                     : 1.0;
        skin.F0 = preskinSkinF0(material.skinSpecular.x, specularMap);
        skin.specularWeight = kSpecularWeight;
        skin.lobes = material.skinSpecular.yzww;
        skin.transmissionTint = material.skinScatter.w * material.skinTransmission.rgb;
        skin.thicknessScale = material.skinTransmission.w;

        PreskinSkinLighting lighting;
        if (kSkinRowFitPerVertex)
            lighting = preskinSkinLighting(skin, profiles, diffuseLut, V, features,
                                           PreskinDiffuseFit(inRowFitScale, inRowFitWidth));
        else
            lighting = preskinSkinLighting(skin, profiles, diffuseLut, V, features);
        // Lights with a size (preskin/lights.glsl); their specular from the lobes' linearly
        // transformed cosines.
        vec3 R = reflect(-V, skin.normalSpecular);
        PreskinLtc ltc = PreskinLtc(mat3(1.0), mat3(1.0), vec4(0.0));
        if (kAreaLightShapes != 0u) {
            vec2 lobeRoughness = (features & kSkinDualSpecular) != 0u ? clamp(roughness * skin.lobes.xy, 0.03, 1.0)
                                                                      : vec2(roughness);
            ltc = preskinLtc(dfgTable, skin.normalSpecular, V, lobeRoughness);
        }
        vec3 transmitted = vec3(0.0);
        vec3 penumbra = vec3(1.0);
        if (hasShadowLight) {
            vec3 L;
            vec3 irradiance;
            shadowLightIncidence(L, irradiance);
            penumbra = preskinSkinShadow(skin, profiles, penumbraLut, shadow, wideShadow, frame.wideShadow.z, L, features);
            // The lit surface the light reaches first, from where it scatters to this point
            // through the skin: behind it where the skin faces away (transmission), or above it
            // where a nearby occluder shadows skin facing the light.
            float coverage;
            PreskinShadowOccluder occluder = preskinSkinOccluder(skin, profiles, shadowMap, shadowClipFromWorld, shadowParams,
                                                                 inPositionWs, shadow, L, features, coverage);
            vec3 sphereT = inSphereTransmittance;
            if (!kSkinSphereTransmittancePerVertex)
                sphereT = preskinSkinSphereTransmittance(profiles, transmittanceLut, skin.curvaturePerMm, geometricN, L,
                                                         features);
            transmitted = preskinSkinTransmission(skin, profiles, transmittanceLut, L, irradiance, occluder, sphereT,
                                                  shadow.visibility, coverage, features);
            // The neighbours facing this point across a gap, a contact or a thin part: the same
            // light as transmission's where both see the same surface, so the larger of the two.
            PreskinOpposingLookup opposing =
                PreskinOpposingLookup(inOpposingFacing, inOpposingShadowUvZ, inOpposingDzPerTexel);
            transmitted = max(transmitted, preskinSkinOpposingLight(skin, shadowMap, shadowParams, opposing, irradiance,
                                                                    features));
            PreskinSkinLightParts lit;
            if (kCapShadowLight)
                lit = preskinSkinLightParts(skin, lighting, profiles, diffuseLut, V,
                                            preskinLightSample(lights[0], inPositionWs, skin.normalSpecular, R, ltc, true),
                                            penumbra, shadow.visibility, preskinShadowLightFeatures(features), ltc.dfg);
            else
                lit = preskinSkinLightParts(skin, lighting, profiles, diffuseLut, V, L, irradiance, penumbra,
                                            shadow.visibility, preskinShadowLightFeatures(features));
            skinDiffuse += lit.diffuse;
            color += lit.specular;
        }
        if (loopCount > 0u) {
            uint i = 0u;
            if (kAreaLightShapes == 0u) {
                do {
                    vec3 L;
                    vec3 irradiance;
                    preskinLightIncidence(unshadowedLight(i, shadowLights, first, indirect), inPositionWs, L, irradiance);
                    PreskinSkinLightParts lit = preskinSkinLightParts(skin, lighting, profiles, diffuseLut, V, L,
                                                                      irradiance, vec3(1.0), 1.0, features);
                    skinDiffuse += lit.diffuse;
                    color += lit.specular;
                } while (++i < loopCount);
            } else {
                do {
                    PreskinLightSample l = preskinLightSample(unshadowedLight(i, shadowLights, first, indirect),
                                                              inPositionWs, skin.normalSpecular, R, ltc, true);
                    PreskinSkinLightParts lit =
                        preskinSkinLightParts(skin, lighting, profiles, diffuseLut, V, l, vec3(1.0), 1.0, features, ltc.dfg);
                    skinDiffuse += lit.diffuse;
                    color += lit.specular;
                } while (++i < loopCount);
            }
        }
        skinDiffuse += transmitted;
        diffuseColor = skin.albedo;
        PreskinShTransfer shTransfer;
        if (kSkinShPerVertex) shTransfer = PreskinShTransfer(inShTransferRed, inShTransferGreen, inShTransferBlue);
        else shTransfer = preskinSkinShTransfer(profiles, shTransferLut, skin.curvaturePerMm, features);
        vec3 ambient;
        if (kSpecular == kSpecularIbl)
            ambient = preskinSkinAmbient(skin, shTransfer, frame.shRadiance, prefilteredEnvironment, dfgTable, ibl, V,
                                         features, ambientDiffuse);
        else
            ambient = preskinSkinAmbient(skin, shTransfer, frame.shRadiance, V, features, ambientDiffuse);
        color += (ambient - ambientDiffuse) * occlusion;
        ambientDiffuse *= occlusion;
        skinDiffuse += ambientDiffuse;
        if (kDebugView == kDebugCurvature) debugColor = curvatureHeat(abs(skin.curvaturePerMm));
        else if (kDebugView == kDebugNormals)
            debugColor = vec3(skin.normalR.x, skin.normalG.y, skin.normalB.z) * 0.5 + 0.5;
        else if (kDebugView == kDebugPenumbra) debugColor = penumbra;
        else if (kDebugView == kDebugTransmission) debugColor = transmitted;
    } else {
        PreskinStandardSurface surface;
        surface.diffuseColor = baseColor.rgb * (1.0 - metallic);
        surface.F0 = mix(vec3(0.04), baseColor.rgb, metallic);
        surface.roughness = roughness;
        surface.specularWeight = kSpecularWeight;
        vec3 R = reflect(-V, N);
        PreskinLtc ltc = PreskinLtc(mat3(1.0), mat3(1.0), vec4(0.0));
        if (kAreaLightShapes != 0u) ltc = preskinLtc(dfgTable, N, V, vec2(roughness));
        if (hasShadowLight) {
            if (kCapShadowLight) {
                PreskinLightSample l = preskinLightSample(lights[0], inPositionWs, N, R, ltc, true);
                l.irradiance *= shadow.visibility;
                l.radiance *= shadow.visibility;
                color += preskinStandardLight(surface, N, V, l, ltc.dfg.xy);
            } else {
                vec3 L;
                vec3 irradiance;
                shadowLightIncidence(L, irradiance);
                color += preskinStandardLight(surface, N, V, L, irradiance * shadow.visibility);
            }
        }
        if (loopCount > 0u) {
            uint i = 0u;
            if (kAreaLightShapes == 0u) {
                do {
                    vec3 L;
                    vec3 irradiance;
                    preskinLightIncidence(unshadowedLight(i, shadowLights, first, indirect), inPositionWs, L, irradiance);
                    color += preskinStandardLight(surface, N, V, L, irradiance);
                } while (++i < loopCount);
            } else {
                do {
                    PreskinLightSample l =
                        preskinLightSample(unshadowedLight(i, shadowLights, first, indirect), inPositionWs, N, R, ltc, true);
                    color += preskinStandardLight(surface, N, V, l, ltc.dfg.xy);
                } while (++i < loopCount);
            }
        }
        // Ambient: SH irradiance for diffuse; specular from the prefiltered environment by the
        // split sum (preskin/ibl.glsl), or (kSpecularSh) the cosine-convolved SH in the reflection
        // direction with the analytic environment BRDF.
        vec3 irradianceSh = max(preskinShEvaluate(frame.shRadiance, N, PRESKIN_SH_LAMBERT), vec3(0.0));
        vec3 envBrdf;
        vec3 specularIbl;
        if (kSpecular == kSpecularIbl) {
            vec2 ab = preskinDfg(dfgTable, NoV, roughness);
            envBrdf = (surface.F0 * ab.x + ab.y) * surface.specularWeight;
            specularIbl = preskinPrefilteredRadiance(prefilteredEnvironment, ibl, R, roughness);
        } else {
            envBrdf = preskinEnvBrdfApprox(surface.F0, roughness, NoV) * surface.specularWeight;
            specularIbl = max(preskinShEvaluate(frame.shRadiance, R, PRESKIN_SH_LAMBERT), vec3(0.0)) / PRESKIN_PI;
        }
        diffuseColor = surface.diffuseColor;
        ambientDiffuse = surface.diffuseColor * irradianceSh / PRESKIN_PI * (vec3(1.0) - envBrdf) * occlusion;
        color += ambientDiffuse + specularIbl * envBrdf * occlusion;
        if (kDebugView == kDebugCurvature) debugColor = curvatureHeat(abs(inCurvaturePerM) * 0.001);
        else if (kDebugView == kDebugNormals) debugColor = N * 0.5 + 0.5;
        else if (kDebugView == kDebugPenumbra) debugColor = vec3(shadow.visibility);
    }
    color += emissive;

    if (kDebugView == kDebugShadow) debugColor = vec3(shadow.visibility);
    else if (kDebugView == kDebugShAmbient) debugColor = ambientDiffuse;
    else if (kDebugView == kDebugLightCount) {
        if (kOutputMode == kOutputLinear) {
            // Raw values for tools (preskin bench): local lights in this fragment's list, all
            // lights evaluated (directional ones included), view depth in metres.
            float viewDepthM = dot(frame.eyes[inEye].viewDepthFromWorld, vec4(inPositionWs, 1.0));
            debugColor = vec3(float(count), float(lightTotal), viewDepthM);
        } else {
            // Heat map on a log scale: 1 light 0.14, 7 lights 0.43, 31 lights 0.71, 127 or more 1.
            float t = clamp(log2(1.0 + float(lightTotal)) / 7.0, 0.0, 1.0);
            debugColor = vec3(smoothstep(0.3, 0.7, t), sin(t * PRESKIN_PI), smoothstep(0.6, 0.2, t)) *
                         (lightTotal > 0u ? 1.0 : 0.1);
        }
    }
#ifdef PRESKIN_SPLIT_DIFFUSE
    // Skin's diffuse light to the screen-space passes; every opaque surface's depth and material
    // (skin's index + 1) for them. Blended materials leave both attachments alone (write masks).
    bool splitSkin = kMaterialModel == kModelSkin && kDebugView == kDebugNone;
    outDiffuse = splitSkin ? vec4(skinDiffuse * frame.params.x, 1.0) : vec4(0.0);
    outSurface = vec2(dot(frame.eyes[inEye].viewDepthFromWorld, vec4(inPositionWs, 1.0)),
                      splitSkin ? float(draw.indices.y + 1u) : 0.0);
    if (!splitSkin) color += skinDiffuse;
#elif defined(PRESKIN_TEXTURE_IRRADIANCE)
    outColor = vec4(skinDiffuse, 1.0);
    outStretch = vec2(length(dFdx(inPositionWs)), length(dFdy(inPositionWs)));
    return;
#elif defined(PRESKIN_TEXTURE_DIFFUSION)
    if (kMaterialModel == kModelSkin && kDebugView == kDebugNone) {
        // The sum holds the covered texels' light and, in alpha, their coverage: its filtered read
        // divided by the filtered coverage averages the covered texels only (no dark fringe where
        // an island's border meets empty texels).
        vec4 sum = textureLod(diffusionTexture, vec3(inUv0, float(draw.indices.z)), 0.0);
        skinDiffuse = baseColor.rgb * sum.rgb / max(sum.a, 1e-4);
    }
    color += skinDiffuse;
#else
    color += skinDiffuse;
#endif
    if (kDebugView != kDebugNone) color = debugColor;

    color *= (kDebugView == kDebugNone) ? frame.params.x : 1.0;
    float alpha = kAlphaMode == kAlphaBlend ? baseColor.a : (kAlphaMode == kAlphaMask ? maskCoverage : 1.0);
    outColor = vec4(kOutputMode == kOutputTonemapped ? preskinTonemapNeutral(max(color, vec3(0.0))) : color, alpha);
}
