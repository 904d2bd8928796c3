// preskin/skin.glsl: pre-integrated skin shading for one fragment of a forward pass.
//
// Models (sources in DESIGN notes and README):
//  - diffuse: Penner & Borshukov's pre-integrated ring scattering (GPU Pro 2, 2011): per light
//    and per colour channel D_c(NoL_c, curvature) from the diffuse LUT replaces saturate(NoL);
//    NoL_c uses that channel's prefiltered normal;
//  - per-channel normal prefiltering (same source; d'Eon & Luebke, GPU Gems 3 ch. 14): the normal
//    map sampled three times with a mip LOD bias per channel, red blurred most; the bias comes
//    from the profile's scattering width per channel and the map's texel density (C++ side);
//    specular keeps the unbiased normal;
//  - penumbra scattering (Penner): the filtered shadow and the shadow filter's width on the
//    receiver index the penumbra LUT, giving an RGB shadow whose red bleeds into the dark side;
//  - ambient: L2 SH radiance convolved per channel with the skin's zonal transfer A_l(curvature)
//    instead of Lambert's (pi, 2pi/3, pi/4);
//  - transmission through thin parts (Jimenez et al., "Real-Time Realistic Skin Translucency",
//    IEEE CG&A 2010): thickness from the shadow map, T(thickness) from the profile, times a
//    saturate(0.3 - NoL) wrap on the side facing away from the light;
//  - specular: two GGX lobes (roughness multipliers and mix in the material) with F0 = 0.028
//    (IOR 1.4) times the specular map.
// Every technique can be switched off (kSkin* bits of shared/skin_features.h in `features`); off falls back to the
// standard equivalent, so with no bits set this equals the standard dielectric BRDF.
//
// Inputs are in world units (metres) except where named; the material's scatter scale
// converts them to profile millimetres. Includes preskin/brdf.glsl, preskin/lut.glsl,
// preskin/sh.glsl and preskin/skin_surface.glsl (building the surface from a host's textures);
// needs the four LUT array samplers and the fragment's profile mix (PreskinProfileMix of
// preskin/lut.glsl; preskinSingleProfile for one profile; see README, "Embedding").
// Limits: curvature and thickness are scalar per fragment; transmission only for the light that
// owns the shadow map; the ring model assumes locally spherical geometry (Penner).
#ifndef PRESKIN_SKIN_GLSL
#define PRESKIN_SKIN_GLSL

#include "preskin/brdf.glsl"
#include "preskin/lut.glsl"
#include "preskin/sh.glsl"
#include "preskin/skin_surface.glsl"
#include "shared/skin_features.h"

struct PreskinSkinSurface {
    vec3 albedo;             // linear diffuse colour
    vec3 normalR;            // prefiltered normals per channel (all equal without prefiltering)
    vec3 normalG;
    vec3 normalB;
    vec3 normalSpecular;     // unbiased normal for specular
    vec3 geometricNormal;    // interpolated vertex normal, facing the viewer
    float curvaturePerMm;    // profile units: world curvature (1/mm) / scatter scale
    float scatterScale;      // profile mm per world mm
    float roughness;         // perceptual
    vec3 F0;                 // 0.028 * intensity * specular map for skin
    vec4 lobes;              // x lobe-0 roughness multiplier, y lobe-1 multiplier, z lobe-1 weight
    vec3 transmissionTint;   // strength * colour
    float thicknessScale;
};

// Diffuse response per channel for one light direction (replaces saturate(NoL)).
vec3 preskinSkinDiffuseResponse(PreskinSkinSurface s, PreskinProfileMix m, sampler2DArray diffuseLut, vec3 L, uint features) {
    vec3 NoL = vec3(dot(s.normalR, L), dot(s.normalG, L), dot(s.normalB, L));
    if ((features & kSkinLutDiffuse) == 0u) return clamp(NoL, 0.0, 1.0);
    if ((features & kSkinNormalPrefilter) == 0u)
        return preskinDiffuseLut(m, diffuseLut, NoL.g, s.curvaturePerMm);
    return vec3(preskinDiffuseLut(m, diffuseLut, NoL.r, s.curvaturePerMm).r,
                preskinDiffuseLut(m, diffuseLut, NoL.g, s.curvaturePerMm).g,
                preskinDiffuseLut(m, diffuseLut, NoL.b, s.curvaturePerMm).b);
}

// Specular of one light: one or two GGX lobes with the unbiased normal (Fresnel shared).
vec3 preskinSkinSpecular(PreskinSkinSurface s, vec3 V, vec3 L, uint features) {
    vec3 N = s.normalSpecular;
    float NoL = dot(N, L);
    if (NoL <= 0.0) return vec3(0.0);
    vec3 H = normalize(L + V);
    float NoV = max(dot(N, V), 1e-4);
    float NoH = preskinSaturate(dot(N, H));
    vec3 F = preskinSchlickF(s.F0, preskinSaturate(dot(V, H)));
    if ((features & kSkinDualSpecular) == 0u) {
        float alpha = max(s.roughness * s.roughness, 1e-3);
        return F * (preskinGgxD(NoH, alpha) * preskinSmithV(NoL, NoV, alpha) * NoL);
    }
    float r0 = clamp(s.roughness * s.lobes.x, 0.03, 1.0);
    float r1 = clamp(s.roughness * s.lobes.y, 0.03, 1.0);
    float a0 = max(r0 * r0, 1e-3);
    float a1 = max(r1 * r1, 1e-3);
    float lobe0 = preskinGgxD(NoH, a0) * preskinSmithV(NoL, NoV, a0);
    float lobe1 = preskinGgxD(NoH, a1) * preskinSmithV(NoL, NoV, a1);
    return F * (mix(lobe0, lobe1, s.lobes.z) * NoL);
}

// Reflected radiance of one light. shadowRgb: per-channel visibility (penumbra LUT, or the plain
// filtered shadow in all channels); specularVisibility: the plain filtered shadow.
vec3 preskinSkinLight(PreskinSkinSurface s, PreskinProfileMix m, sampler2DArray diffuseLut, vec3 V, vec3 L, vec3 irradiance,
                      vec3 shadowRgb, float specularVisibility, uint features) {
    vec3 F = preskinSchlickF(s.F0, preskinSaturate(dot(V, normalize(L + V))));
    vec3 diffuse = (vec3(1.0) - F) * s.albedo / PRESKIN_PI * preskinSkinDiffuseResponse(s, m, diffuseLut, L, features);
    vec3 specular = preskinSkinSpecular(s, V, L, features);
    return (diffuse * shadowRgb + specular * specularVisibility) * irradiance;
}

// Per-channel shadow for skin: the penumbra LUT indexed by the filtered visibility and the
// filter's width on the receiver (the light-plane width stretched by the receiver's slope).
vec3 preskinSkinShadow(PreskinSkinSurface s, PreskinProfileMix m, sampler2DArray penumbraLut, float visibility,
                       float filterWidthLightM, vec3 L, uint features) {
    // Fully lit or fully shadowed: the LUT's end columns are exactly 1 and 0, skip the fetch.
    if ((features & kSkinPenumbra) == 0u || visibility <= 0.0 || visibility >= 1.0) return vec3(visibility);
    float slope = max(abs(dot(s.geometricNormal, L)), 0.2);
    float sigmaProfileMm = filterWidthLightM * 1000.0 / slope * s.scatterScale;
    return preskinPenumbraLut(m, penumbraLut, visibility, sigmaProfileMm);
}

// Light transmitted through the surface from a light behind it: thicknessM from the shadow
// map (metres), T(thickness) from the profile, wrap saturate(0.3 - NoL) (Jimenez et al. 2010).
vec3 preskinSkinTransmission(PreskinSkinSurface s, PreskinProfileMix m, sampler2DArray transmittanceLut, vec3 L,
                             vec3 irradiance, float thicknessM, uint features) {
    float wrap = preskinSaturate(kSkinTransmissionWrap - dot(s.geometricNormal, L));
    if ((features & kSkinTransmission) == 0u || wrap <= 0.0) return vec3(0.0);
    float thicknessMm = thicknessM * 1000.0 * s.thicknessScale * s.scatterScale;
    vec3 T = preskinTransmittanceLut(m, transmittanceLut, thicknessMm);
    return T * wrap * s.transmissionTint * s.albedo / PRESKIN_PI * irradiance;
}

// Diffuse ambient irradiance per channel from L2 SH radiance (multiply by albedo / pi).
vec3 preskinSkinAmbientIrradiance(PreskinSkinSurface s, PreskinProfileMix m, sampler2DArray shTransferLut, vec4 sh[9],
                                  uint features) {
    vec3 bandR = PRESKIN_SH_LAMBERT;
    vec3 bandG = PRESKIN_SH_LAMBERT;
    vec3 bandB = PRESKIN_SH_LAMBERT;
    if ((features & kSkinShAmbient) != 0u) {
        vec3 a0, a1, a2;
        preskinShTransferLut(m, shTransferLut, s.curvaturePerMm, a0, a1, a2);
        bandR = vec3(a0.r, a1.r, a2.r);
        bandG = vec3(a0.g, a1.g, a2.g);
        bandB = vec3(a0.b, a1.b, a2.b);
    }
    if ((features & kSkinNormalPrefilter) == 0u)  // one normal for all channels
        return max(preskinShEvaluateRgb(sh, s.normalG, bandR, bandG, bandB), vec3(0.0));
    return max(vec3(preskinShEvaluateChannel(sh, s.normalR, bandR, 0), preskinShEvaluateChannel(sh, s.normalG, bandG, 1),
                    preskinShEvaluateChannel(sh, s.normalB, bandB, 2)),
               vec3(0.0));
}

// Ambient light of the environment's L2 SH radiance: diffuse from the per-channel transfer
// (preskinSkinAmbientIrradiance times albedo / pi, less what the specular takes) plus specular
// from the cosine-convolved SH in the reflection direction, weighted by Karis's analytic split-sum
// environment BRDF. diffuseOut: the diffuse part alone. Multiply both by ambient occlusion.
vec3 preskinSkinAmbient(PreskinSkinSurface s, PreskinProfileMix m, sampler2DArray shTransferLut, vec4 sh[9], vec3 V,
                        uint features, out vec3 diffuseOut) {
    float NoV = max(dot(s.normalSpecular, V), 1e-4);
    vec3 envBrdf = preskinEnvBrdfApprox(s.F0, s.roughness, NoV);
    vec3 R = reflect(-V, s.normalSpecular);
    vec3 specularSh = max(preskinShEvaluate(sh, R, PRESKIN_SH_LAMBERT), vec3(0.0)) / PRESKIN_PI;
    diffuseOut = s.albedo * preskinSkinAmbientIrradiance(s, m, shTransferLut, sh, features) / PRESKIN_PI *
                 (vec3(1.0) - envBrdf);
    return diffuseOut + specularSh * envBrdf;
}

#endif
