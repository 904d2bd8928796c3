#version 460
// host.frag: a host engine's own forward shader with preskin's skin: base colour, normal and
// specular maps, every light of a small list, one of them with the host's shadow map (penumbra
// scattering, transmission, the opposing neighbours' light), L2 SH ambient, tone mapping. All skin
// work comes from the GLSL library (glslangValidator -I<preskin_SHADER_DIR>).
// Limits: no wide shadow map (red's scattering stays within the shadow filter's reach), no
// texture transforms, one material.
#extension GL_GOOGLE_include_directive : require
#define PRESKIN_PROFILE_MIX_MAX 1  // one profile per fragment: the blend's lookups compile out
#include "preskin/lights.glsl"
#include "preskin/skin.glsl"  // with preskin/shadow.glsl and preskin/skin_vertex.glsl
#include "preskin/tonemap.glsl"

layout(constant_id = 0) const uint kFeatures = kSkinQualityHigh;  // or kSkinQualityMedium, kSkinQualityLow

layout(set = 0, binding = 0) uniform Frame {
    LutMapping lut;             // preskin::lutMapping(luts)
    vec4 sh[9];                 // Environment::radianceSh()
    vec4 cameraPositionWs;
    vec4 skin;                  // x scatter scale, y roughness, z specular intensity, w normal scale
    vec4 lodBias;               // rgb: normalLodBias(), w: normalLevelCount()
    vec4 lobes;                 // SkinMaterial lobeRoughness0, lobeRoughness1, lobeMix
    vec4 transmission;          // rgb SkinMaterial transmission x transmissionColor, w thicknessScale
    mat4 shadowClipFromWorld;   // the shadow light's orthographic map: x, y in [-1, 1], depth 0 near .. 1 far
    vec4 shadowParams;          // texel size (m), filter sigma (texels), depth range (m), map size (texels)
    uvec4 lightCount;           // x lights, y the shadow light's index, z 1 with a shadow map
    GpuLight lights[8];
} frame;
layout(set = 0, binding = 1) uniform sampler2D baseColorMap;
layout(set = 0, binding = 2) uniform sampler2D normalMap;
layout(set = 0, binding = 3) uniform sampler2D specularMap;
layout(set = 0, binding = 4) uniform sampler2DArray diffuseLut;     // channel planes; a layer per diffusion profile
layout(set = 0, binding = 5) uniform sampler2DArray shTransferLut;
layout(set = 0, binding = 7) uniform sampler2D shadowMap;           // depth, unfiltered (the library gathers)
layout(set = 0, binding = 8) uniform sampler2DArray penumbraLut;
layout(set = 0, binding = 9) uniform sampler2DArray transmittanceLut;

layout(location = 0) in vec3 inPositionWs;
layout(location = 1) in vec3 inNormalWs;
layout(location = 2) in vec4 inTangentWs;
layout(location = 3) in vec2 inUv0;
layout(location = 4) in float inCurvaturePerM;
layout(location = 5) in vec3 inNormalRedWs;  // the skin's per-channel prefiltered geometric normals
layout(location = 6) in vec3 inNormalGreenWs;
layout(location = 7) in vec3 inNormalBlueWs;
layout(location = 8) in vec3 inOpposingRedWs;  // the neighbours facing the point across a gap
layout(location = 9) in vec3 inOpposingGreenWs;
layout(location = 10) in vec3 inOpposingBlueWs;
layout(location = 11) in vec3 inOpposingCentroidWs;
layout(location = 0) out vec4 outColor;

void main() {
    float facing = gl_FrontFacing ? 1.0 : -1.0;
    vec3 geometricN = normalize(inNormalWs) * facing;
    PreskinNormalMaps maps = PreskinNormalMaps(frame.skin.w, false, 1.0, 0.0, frame.lodBias.rgb, int(frame.lodBias.w), false);
    PreskinSkinSurface s;
    s.geometricNormal = geometricN;
    s.geometricNormalR = normalize(inNormalRedWs) * facing;
    s.geometricNormalG = normalize(inNormalGreenWs) * facing;
    s.geometricNormalB = normalize(inNormalBlueWs) * facing;
    preskinSkinNormals(normalMap, normalMap, maps, inUv0, geometricN, s.geometricNormalR, s.geometricNormalG,
                       s.geometricNormalB, inTangentWs, kFeatures, s.normalSpecular, s.normalR, s.normalG, s.normalB);
    s.albedo = texture(baseColorMap, inUv0).rgb;
    s.scatterScale = frame.skin.x;
    s.curvaturePerMm = preskinCurvatureProfilePerMm(inCurvaturePerM, s.scatterScale);
    // The principal curvatures about the mean (each light's diffuse LUT row; uniform control flow).
    preskinSkinCurvatureSpread(geometricN, s.curvaturePerMm, s.scatterScale, dFdx(inPositionWs), dFdy(inPositionWs),
                               dFdx(geometricN), dFdy(geometricN), s.curvatureAxis, s.curvatureSpreadPerMm);
    s.roughness = frame.skin.y;
    s.F0 = preskinSkinF0(frame.skin.z, texture(specularMap, inUv0).r);
    s.specularWeight = 1.0;
    s.lobes = frame.lobes;
    s.transmissionTint = frame.transmission.rgb;
    s.thicknessScale = frame.transmission.w;

    vec3 V = normalize(frame.cameraPositionWs.xyz - inPositionWs);
    vec3 ambientDiffuse;
    PreskinProfileMix profile = preskinSingleProfile(frame.lut, 0.0);
    vec3 color = preskinSkinAmbient(s, profile, shTransferLut, frame.sh, V, kFeatures, ambientDiffuse);
    PreskinSkinLighting lighting = preskinSkinLighting(s, profile, diffuseLut, V, kFeatures);  // shared by the lights
    vec3 R = reflect(-V, s.normalSpecular);
    for (uint i = 0; i < frame.lightCount.x; ++i) {  // punctual or area lights (preskin/lights.glsl; specular of area lights at their representative point: no LTC table bound)
        PreskinLightSample l = preskinLightSample(frame.lights[i], inPositionWs, s.normalSpecular, R);
        vec3 shadowRgb = vec3(1.0);
        float visibility = 1.0;
        // The shadow light's features (preskinShadowLightFeatures: its diffuse LUT where the tier reads
        // it); without a shadow map no light is told apart, and every light gets them.
        bool shadowLight = frame.lightCount.z != 0u && i == frame.lightCount.y;
        uint features = shadowLight || frame.lightCount.z == 0u ? preskinShadowLightFeatures(kFeatures) : kFeatures;
        if (shadowLight) {
            // The shadow map read above the local patch near the terminator (its self-shadowing is
            // the diffuse LUT's), then per channel through the penumbra LUT.
            vec3 L = l.L;
            vec3 shadowAt = preskinSkinShadowPosition(inPositionWs, geometricN, L,
                                                      preskinSkinShadowLift(s.curvaturePerMm, s.scatterScale, profile));
            PreskinShadowFilter shadowFilter = preskinSkinShadowFilter(kFeatures, 0.0, s.curvaturePerMm, s.scatterScale,
                                                                       dot(geometricN, L), frame.shadowParams.x);
            PreskinShadowSample shadow = preskinSampleShadow(shadowMap, frame.shadowClipFromWorld, frame.shadowParams,
                                                             shadowAt, geometricN, shadowFilter);
            shadowRgb = preskinSkinShadow(s, profile, penumbraLut, shadow, L, kFeatures);
            visibility = shadow.visibility;
            // Light through the skin from the lit surface the light reaches first (behind a thin
            // part, or an occluder within the profile's reach), and from the neighbours across a gap.
            float coverage;
            PreskinShadowOccluder occluder = preskinSkinOccluder(s, profile, shadowMap, frame.shadowClipFromWorld,
                                                                 frame.shadowParams, inPositionWs, shadow, L, kFeatures, coverage);
            vec3 sphereT = preskinSkinSphereTransmittance(profile, transmittanceLut, s.curvaturePerMm, geometricN, L, kFeatures);
            vec3 transmitted = preskinSkinTransmission(s, profile, transmittanceLut, L, l.irradiance, occluder, sphereT,
                                                       visibility, coverage, kFeatures);
            color += max(transmitted, preskinSkinOpposingLight(s, shadowMap, frame.shadowClipFromWorld, frame.shadowParams,
                                                               inPositionWs, inOpposingCentroidWs, inOpposingRedWs,
                                                               inOpposingGreenWs, inOpposingBlueWs, L, l.irradiance, kFeatures));
        }
        color += preskinSkinLight(s, lighting, profile, diffuseLut, V, l, shadowRgb, visibility, features, vec4(0.0));
    }
    outColor = vec4(preskinTonemapNeutral(max(color, vec3(0.0))), 1.0);
}
