// preskin/skin.glsl: pre-integrated skin shading for one fragment of a forward pass.
//
// Models (sources in DESIGN notes and README):
//  - diffuse: pre-integrated scattering after Penner & Borshukov (GPU Pro 2, 2011), integrated
//    over the sphere of the signed mean curvature (engine/src/skin/SphereScatter.h): per light
//    and per colour channel D_c(NoL_c, curvature) from the diffuse LUT replaces saturate(NoL);
//    NoL_c uses that channel's prefiltered normal; concave skin (negative curvature) reads the
//    LUT's concave half, where the local patch shadows itself and no light passes the terminator;
//    the lights other than the shadow light read the table with kSkinLutOtherLights, the shadow
//    light with kSkinLutShadowLight; a light without it gets the fragment's row as a smoothed ramp
//    (preskinDiffuseRowFit), fitted once per vertex or per fragment; with kSkinLightCurvature a
//    light that reads the table reads the row of convex skin's curvature along it near the
//    terminator (preskinSkinLightCurvaturePerMm: a cylinder lit across falls off as the sphere of
//    its curvature across);
//  - self-shadowing apart from cast shadows: the shadow map is looked up above the local patch
//    near the terminator (preskinSkinShadowPosition), so it does not remove the light the diffuse
//    LUT scatters past the terminator;
//  - per-channel normal prefiltering (same source; d'Eon & Luebke, GPU Gems 3 ch. 14): the normal
//    map sampled three times with a mip LOD bias per channel, red blurred most; the bias comes
//    from the profile's scattering width per channel and the map's texel density (C++ side);
//    specular keeps the unbiased normal;
//  - penumbra scattering (Penner): the filtered shadow and the shadow filter's width on the
//    receiver index the penumbra LUT, giving an RGB shadow whose red bleeds into the dark side;
//  - ambient: L2 SH radiance convolved per channel with the skin's zonal transfer A_l(curvature)
//    instead of Lambert's (pi, 2pi/3, pi/4);
//  - transmission through thin parts (Jimenez et al., "Real-Time Realistic Skin Translucency",
//    IEEE CG&A 2010): on the side facing away from the light, the profile's integral over the
//    lit surface behind it (found in the shadow map: its distance and its slope), less what the
//    diffuse LUT already holds (the light through the osculating sphere); and the same from a
//    nearby occluder's lit side into skin it shadows;
//  - specular: two GGX lobes (roughness multipliers and mix in the material) with F0 = 0.028
//    (IOR 1.4) times the specular map.
// Every technique can be switched off (kSkin* bits of shared/skin_features.h in `features`); off falls back to the
// standard equivalent, so with no bits set but kSkinFullShadowFilter (the standard material's
// filter) this equals the standard dielectric BRDF. The quality
// tiers are such masks: kSkinQualityHigh (every technique but the table for the lights besides
// the shadow light; kSkinAll has it), kSkinQualityMedium, kSkinQualityLow
// (shared/skin_features.h; docs/skin-cost.md gives each one's cost and fidelity); a host passes
// one as a specialization constant, so what a tier leaves out is compiled out.
//
// Inputs are in world units (metres) except where named; the material's scatter scale
// converts them to profile millimetres. Includes preskin/brdf.glsl, preskin/lut.glsl,
// preskin/sh.glsl, preskin/shadow.glsl and preskin/skin_surface.glsl (building the surface from
// a host's textures); needs the four LUT array samplers and the fragment's profile mix
// (PreskinProfileMix of preskin/lut.glsl; preskinSingleProfile for one profile; see README, "Embedding").
// Limits: thickness is scalar per fragment; transmission only for the light that
// owns the shadow map; the diffuse LUT assumes locally spherical geometry (of the mean curvature,
// or near the terminator of the curvature along the light, from the interpolated normal's screen
// derivatives: constant over a triangle, aliased where triangles are smaller than a pixel quad; the
// row fit of the lights without the table keeps the mean's); the concave patch's extent is a model constant (LutSet::localPatchMm).
#ifndef PRESKIN_SKIN_GLSL
#define PRESKIN_SKIN_GLSL

#include "preskin/brdf.glsl"
#include "preskin/ibl.glsl"
#include "preskin/lut.glsl"
#include "preskin/sh.glsl"
#include "preskin/shadow.glsl"
#include "preskin/skin_surface.glsl"
#include "preskin/skin_vertex.glsl"
#include "shared/skin_features.h"

struct PreskinSkinSurface {
    vec3 albedo;             // linear diffuse colour
    vec3 normalR;            // prefiltered normals per channel (all equal without prefiltering)
    vec3 normalG;
    vec3 normalB;
    vec3 normalSpecular;     // unbiased normal for specular
    vec3 geometricNormal;    // interpolated vertex normal, facing the viewer
    vec3 geometricNormalR;   // with kSkinNormalPrefilter: each channel's prefiltered geometric normal (the
    vec3 geometricNormalG;   // normal basis stream's, facing the viewer; normalR/G/B before the normal map),
    vec3 geometricNormalB;   // whose N.L falls short of the point's own where neighbours face away (preskinSkinNoL)
    float curvaturePerMm;    // signed mean curvature in profile units (world 1/mm / scatter scale), < 0 concave
    vec3 curvatureAxis;      // with kSkinLightCurvature: the tangent of the larger principal curvature and half
    float curvatureSpreadPerMm;  // the principal curvatures' difference, profile 1/mm (preskinSkinCurvatureSpread; 0: the mean's row)
    float scatterScale;      // profile mm per world mm
    float roughness;         // perceptual
    vec3 F0;                 // 0.028 * intensity * specular map for skin
    float specularWeight;    // 1: specular with Fresnel; 0: diffuse only (no specular, no Fresnel on diffuse)
    vec4 lobes;              // x lobe-0 roughness multiplier, y lobe-1 multiplier, z lobe-1 weight
    vec3 transmissionTint;   // strength * colour
    float thicknessScale;
};

// What every light of one fragment shares: the diffuse LUT rows at its curvature, the specular
// lobes' alphas and their Smith view terms. A loop over lights finds it once
// (preskinSkinLighting) and passes it to each preskinSkinLight.
struct PreskinSkinLighting {
    PreskinDiffuseRows diffuseRows;
    PreskinDiffuseFit rowFit;  // the row as a smoothed ramp (preskinDiffuseFit; read by the lights without the table)
    float NoV;
    vec2 alpha;      // lobe 0, lobe 1 (lobe 0 twice without dual specular)
    vec2 viewTerm;   // preskinSmithViewTerm of each lobe
};

// The technique mask the shadow light is shaded with (its diffuse LUT read by
// kSkinLutShadowLight; the per-light functions test kSkinLutOtherLights).
uint preskinShadowLightFeatures(uint features) {
    return (features & kSkinLutShadowLight) != 0u ? features | kSkinLutOtherLights : features & ~kSkinLutOtherLights;
}

// Whether some light gets the diffuse row's fit instead of the table (kSkinLutDiffuse without
// one of kSkinLutOtherLights, kSkinLutShadowLight).
bool preskinSkinNeedsRowFit(uint features) {
    const uint lut = kSkinLutDiffuse | kSkinLutOtherLights | kSkinLutShadowLight;
    return (features & kSkinLutDiffuse) != 0u && (features & lut) != lut;
}

// fit: the row's smoothed ramp where the caller found it (the vertex stage, preskin/skin_vertex.glsl),
// read only by the lights without the table (preskinSkinDiffuseRow).
PreskinSkinLighting preskinSkinLighting(PreskinSkinSurface s, PreskinProfileMix m, sampler2DArray diffuseLut, vec3 V,
                                        uint features, PreskinDiffuseFit fit) {
    PreskinSkinLighting k;
    k.rowFit = fit;
    if ((features & kSkinLutDiffuse) != 0u) k.diffuseRows = preskinDiffuseRows(m, diffuseLut, s.curvaturePerMm);
    k.NoV = max(dot(s.normalSpecular, V), 1e-4);
    if ((features & kSkinDualSpecular) == 0u) {
        k.alpha = vec2(max(s.roughness * s.roughness, 1e-3));
    } else {
        vec2 r = clamp(s.roughness * s.lobes.xy, 0.03, 1.0);
        k.alpha = max(r * r, vec2(1e-3));
    }
    k.viewTerm = vec2(preskinSmithViewTerm(k.NoV, k.alpha.x), preskinSmithViewTerm(k.NoV, k.alpha.y));
    return k;
}

// The same, the fit found here from the fragment's row.
PreskinSkinLighting preskinSkinLighting(PreskinSkinSurface s, PreskinProfileMix m, sampler2DArray diffuseLut, vec3 V,
                                        uint features) {
    PreskinSkinLighting k = preskinSkinLighting(s, m, diffuseLut, V, features, kPreskinDiffuseFitLambert);
    if (preskinSkinNeedsRowFit(features))
        k.rowFit = preskinDiffuseFit(m, k.diffuseRows, diffuseLut);
    return k;
}

// A diffuse LUT row D(x), x = N.L, as a smoothed ramp per channel: s (x + sqrt(x^2 + c^2)) / 2, the
// hyperbola whose asymptotes are 0 and s x, through the row's values at x = 0 and 1
// (preskinDiffuseFit of preskin/skin_vertex.glsl). A convex row is the ramp max(x, 0) blurred by the profile over the
// osculating sphere: its light past the terminator, its softened knee and its lit side's lower
// slope (red's light moved into the shadow) are what the fit keeps; within the LUT's own accuracy
// where the row is nearly Lambert's, off by a tenth to a fifth of Lambert's error on red's rows
// of face curvatures and a fifth to a half on green's and blue's. A concave row's self-shadowed
// band past N.L = sin(patch / 2r) it does not hold: there the fit is Lambert's but for red.
vec3 preskinDiffuseRowFit(vec3 NoL, PreskinDiffuseFit fit) {
    return fit.scale * (0.5 * (NoL + sqrt(NoL * NoL + fit.width * fit.width)));
}

// The curvature (profile 1/mm) of the diffuse LUT's row for light L (kSkinLightCurvature). The
// LUT integrates the profile over the sphere of the mean curvature H, where N.L falls off along
// the surface at k sqrt(1 - N.L^2) per unit length for the sphere's k. On any surface it falls
// off along the direction S t at |S t| sqrt(1 - N.L^2), t the unit tangent direction of L and S the
// shape operator, so the sphere that falls off as fast has k_L = |S t| = sqrt(k1^2 cos^2 theta +
// k2^2 sin^2 theta), k1 >= k2 the principal curvatures and theta t's angle from the axis of k1
// (preskinSkinCurvatureSpread): a cylinder lit across its axis is the sphere of its curvature
// across, one lit along its axis a flat surface, and on a saddle k_L stays positive. Over a
// cylinder lit across (d'Eon's red profile integrated numerically at radii 2 to 16 mm,
// docs/fidelity.md) that sphere matches at N.L <= 0.2 and the mean's nearly on the lit side
// (N.L >= 0.6, where neighbours across the falloff's direction count as much): the row is read at
// H + w (k_L - H), w = 1 there, 0.2 here. Concave skin and a zero spread keep H.
float preskinSkinLightCurvaturePerMm(PreskinSkinSurface s, vec3 L) {
    if (s.curvatureSpreadPerMm <= 0.0) return s.curvaturePerMm;
    float c = dot(s.geometricNormal, L);
    float t = dot(s.curvatureAxis, L);
    float tangent2 = 1.0 - c * c;  // |L's tangent part|^2; below 1e-3 (L along N) theta's part fades out
    float cos2Theta = clamp((2.0 * t * t - tangent2) / max(tangent2, 1e-3), -1.0, 1.0);
    float cosTheta2 = 0.5 + 0.5 * cos2Theta;
    float k1 = s.curvaturePerMm + s.curvatureSpreadPerMm, k2 = s.curvaturePerMm - s.curvatureSpreadPerMm;
    float kL = sqrt(k1 * k1 * cosTheta2 + k2 * k2 * (1.0 - cosTheta2));
    float w = mix(1.0, 0.2, smoothstep(0.2, 0.6, c));
    return s.curvaturePerMm + w * (kL - s.curvaturePerMm);
}

// The diffuse LUT's rows for light L: at the curvature along it (kSkinLightCurvature), or the
// fragment's rows at its mean curvature.
PreskinDiffuseRows preskinSkinLightRows(PreskinSkinSurface s, PreskinSkinLighting k, PreskinProfileMix m,
                                        sampler2DArray diffuseLut, vec3 L, uint features) {
    if ((features & kSkinLightCurvature) == 0u) return k.diffuseRows;
    return preskinDiffuseRows(m, diffuseLut, preskinSkinLightCurvaturePerMm(s, L));
}

// The diffuse row at NoL per channel: the LUT's `rows` (preskinSkinLightRows), or without
// kSkinLutOtherLights the fragment's row's fit. The per-light functions below test that bit; the
// shadow light is shaded with preskinShadowLightFeatures(features), which sets it from
// kSkinLutShadowLight.
vec3 preskinSkinDiffuseRow(PreskinSkinLighting k, PreskinDiffuseRows rows, PreskinProfileMix m,
                           sampler2DArray diffuseLut, vec3 NoL, uint features) {
    if ((features & kSkinLutOtherLights) == 0u) return preskinDiffuseRowFit(NoL, k.rowFit);
    return preskinDiffuseLut(m, rows, diffuseLut, NoL);
}

// Each channel's N.L for light L (kSkinNormalPrefilter: its own normal). A channel's prefiltered
// geometric normal is the profile-weighted mean of its neighbours' normals (<preskin/NormalBasis.h>),
// so its N.L is the mean of their N.L. Where that falls below the point's own N.L, the mean took
// in neighbours turned further from the light: a crease's far wall facing away, at its negative
// N.L where the diffusion integral counts its light as none, or the surface's own curve, whose
// falloff the diffuse LUT's row already holds (it integrates the neighbours' N.L over the
// osculating sphere). There the channel reads the point's own geometric N.L, the normal map's
// detail kept (the shortfall is added back); where it rises above (light from neighbours the
// sphere does not have), the channel's. On compare's head views against the diffusion
// reference: the four bundled views' error 0.555 -> 0.532 of Lambert's, every head view closer
// (docs/fidelity.md).
vec3 preskinSkinNoL(PreskinSkinSurface s, vec3 L, uint features) {
    vec3 NoL = vec3(dot(s.normalR, L), dot(s.normalG, L), dot(s.normalB, L));
    if ((features & kSkinNormalPrefilter) == 0u) return NoL;
    vec3 geometric = vec3(dot(s.geometricNormalR, L), dot(s.geometricNormalG, L), dot(s.geometricNormalB, L));
    return NoL + max(vec3(dot(s.geometricNormal, L)) - geometric, 0.0);
}

// Diffuse response per channel for one light direction (replaces saturate(NoL)).
vec3 preskinSkinDiffuseResponse(PreskinSkinSurface s, PreskinSkinLighting k, PreskinProfileMix m,
                                sampler2DArray diffuseLut, vec3 L, uint features) {
    vec3 NoL = preskinSkinNoL(s, L, features);
    if ((features & kSkinLutDiffuse) == 0u) return clamp(NoL, 0.0, 1.0);
    // without prefiltering the three are equal
    return preskinSkinDiffuseRow(k, preskinSkinLightRows(s, k, m, diffuseLut, L, features), m, diffuseLut, NoL, features);
}

// The same for a light with a size, the cap of directions of `l` (preskin/light_sample.glsl):
// Lambert's horizon-clipped term of the cap (plus the sample's correction to the light's exact
// shape: a rectangle's clipped form factor at the shading normal) and what scattering adds to
// it, D_c(c) - max(c, 0) of each channel's LUT averaged over the cap at four nodes of
// c = N_c . omega (preskinCapNodes), so a sphere of the skin's curvature under the cap gets the
// diffusion profile's response to it. The result multiplies l.irradiance.
vec3 preskinSkinDiffuseResponse(PreskinSkinSurface s, PreskinSkinLighting k, PreskinProfileMix m,
                                sampler2DArray diffuseLut, PreskinLightSample l, uint features) {
    if (l.cosSigma >= 1.0) return preskinSkinDiffuseResponse(s, k, m, diffuseLut, l.L, features);
    vec3 NoL = preskinSkinNoL(s, l.L, features);
    if ((features & kSkinLutDiffuse) == 0u)
        return vec3(preskinCapLambert(NoL.r, l.cosSigma, l.sinSigma), preskinCapLambert(NoL.g, l.cosSigma, l.sinSigma),
                    preskinCapLambert(NoL.b, l.cosSigma, l.sinSigma)) + l.lambertCorrection;
    PreskinDiffuseRows rows = k.diffuseRows;
    if ((features & kSkinLutOtherLights) != 0u) rows = preskinSkinLightRows(s, k, m, diffuseLut, l.L, features);
    vec4 cR, wR, cG, wG, cB, wB;
    preskinCapNodes(NoL.r, l.cosSigma, l.sinSigma, cR, wR);
    preskinCapNodes(NoL.g, l.cosSigma, l.sinSigma, cG, wG);
    preskinCapNodes(NoL.b, l.cosSigma, l.sinSigma, cB, wB);
    // What scattering adds to Lambert, averaged over the cap at the nodes, on top of Lambert's
    // exact term: the nodes' error in Lambert's part cancels.
    vec3 sum = vec3(preskinCapLambert(NoL.r, l.cosSigma, l.sinSigma), preskinCapLambert(NoL.g, l.cosSigma, l.sinSigma),
                    preskinCapLambert(NoL.b, l.cosSigma, l.sinSigma)) + l.lambertCorrection;
    for (int i = 0; i < 4; ++i) {
        vec3 c = vec3(cR[i], cG[i], cB[i]);
        sum += vec3(wR[i], wG[i], wB[i]) * (preskinSkinDiffuseRow(k, rows, m, diffuseLut, c, features) - max(c, vec3(0.0)));
    }
    return max(sum, vec3(0.0));
}

// Specular of one light: one or two GGX lobes with the unbiased normal (Fresnel shared).
// lobeScale: each lobe's factor (preskinSpecularNormalization for a light with a size; 1 otherwise).
vec3 preskinSkinSpecular(PreskinSkinSurface s, PreskinSkinLighting k, vec3 V, vec3 L, uint features, vec2 lobeScale) {
    vec3 N = s.normalSpecular;
    float NoL = dot(N, L);
    if (NoL <= 0.0) return vec3(0.0);
    vec3 H = normalize(L + V);
    float NoH = preskinSaturate(dot(N, H));
    vec3 F = preskinSchlickF(s.F0, preskinSaturate(dot(V, H)));
    float lobe0 = lobeScale.x * preskinGgxD(NoH, k.alpha.x) * preskinSmithV(NoL, k.NoV, k.alpha.x, k.viewTerm.x);
    if ((features & kSkinDualSpecular) == 0u) return F * (lobe0 * NoL);
    float lobe1 = lobeScale.y * preskinGgxD(NoH, k.alpha.y) * preskinSmithV(NoL, k.NoV, k.alpha.y, k.viewTerm.y);
    return F * (mix(lobe0, lobe1, s.lobes.z) * NoL);
}

// Reflected radiance of one light, its diffuse and specular parts apart (a host that scatters
// the diffuse light itself, as the screen-space baseline does, keeps them apart).
struct PreskinSkinLightParts {
    vec3 diffuse;
    vec3 specular;
};

// One light's parts. shadowRgb: per-channel visibility (penumbra LUT, or the plain filtered
// shadow in all channels); specularVisibility: the plain filtered shadow.
PreskinSkinLightParts preskinSkinLightParts(PreskinSkinSurface s, PreskinSkinLighting k, PreskinProfileMix m,
                                            sampler2DArray diffuseLut, vec3 V, vec3 L, vec3 irradiance,
                                            vec3 shadowRgb, float specularVisibility, uint features) {
    vec3 F = s.specularWeight * preskinSchlickF(s.F0, preskinSaturate(dot(V, normalize(L + V))));
    vec3 diffuse = (vec3(1.0) - F) * s.albedo / PRESKIN_PI * preskinSkinDiffuseResponse(s, k, m, diffuseLut, L, features);
    vec3 specular = s.specularWeight * preskinSkinSpecular(s, k, V, L, features, vec2(1.0));
    return PreskinSkinLightParts(diffuse * shadowRgb * irradiance, specular * specularVisibility * irradiance);
}

// Reflected radiance of one light (the parts' sum).
vec3 preskinSkinLight(PreskinSkinSurface s, PreskinSkinLighting k, PreskinProfileMix m, sampler2DArray diffuseLut,
                      vec3 V, vec3 L, vec3 irradiance, vec3 shadowRgb, float specularVisibility, uint features) {
    PreskinSkinLightParts p =
        preskinSkinLightParts(s, k, m, diffuseLut, V, L, irradiance, shadowRgb, specularVisibility, features);
    return p.diffuse + p.specular;
}

// The same for any light (preskin/light_sample.glsl): diffuse over the light's cap; specular by
// each lobe's linearly transformed cosine (l.ltc; ltcDfg: PreskinLtc.dfg, both lobes' (A, B)) or
// at the representative point with Karis's normalisation per lobe.
PreskinSkinLightParts preskinSkinLightParts(PreskinSkinSurface s, PreskinSkinLighting k, PreskinProfileMix m,
                                            sampler2DArray diffuseLut, vec3 V, PreskinLightSample l, vec3 shadowRgb,
                                            float specularVisibility, uint features, vec4 ltcDfg) {
    if (l.cosSigma >= 1.0)
        return preskinSkinLightParts(s, k, m, diffuseLut, V, l.L, l.irradiance, shadowRgb, specularVisibility, features);
    vec3 F = s.specularWeight * preskinSchlickF(s.F0, preskinSaturate(dot(V, normalize(l.L + V))));
    vec3 diffuse = (vec3(1.0) - F) * s.albedo / PRESKIN_PI * preskinSkinDiffuseResponse(s, k, m, diffuseLut, l, features);
    vec2 lobeScale = vec2(preskinSpecularNormalization(k.alpha.x, l.specularAlphaAdd),
                          preskinSpecularNormalization(k.alpha.y, l.specularAlphaAdd));
    if (!l.ltc) {
        vec3 specular = s.specularWeight * preskinSkinSpecular(s, k, V, l.specularL, features, lobeScale);
        return PreskinSkinLightParts(diffuse * shadowRgb * l.irradiance, specular * specularVisibility * l.irradiance);
    }
    // Each lobe's linearly transformed cosine, blended with its representative point for lights
    // small against the lobe (preskinLtcWeight), where that is exact.
    vec2 t = vec2(preskinLtcWeight(l, k.alpha.x), preskinLtcWeight(l, k.alpha.y));
    vec3 ltc0 = t.x * preskinLtcSpecular(l, s.F0, ltcDfg.xy, l.specularFormFactor.x, V);
    vec3 ltc1 = t.y * preskinLtcSpecular(l, s.F0, ltcDfg.zw, l.specularFormFactor.y, V);
    vec3 ltcSpecular = (features & kSkinDualSpecular) != 0u ? mix(ltc0, ltc1, s.lobes.z) : ltc0;
    vec3 pointSpecular = preskinSkinSpecular(s, k, V, l.specularL, features, lobeScale * (vec2(1.0) - t));
    return PreskinSkinLightParts(diffuse * shadowRgb * l.irradiance,
                                 s.specularWeight * (ltcSpecular + pointSpecular * l.irradiance) * specularVisibility);
}

vec3 preskinSkinLight(PreskinSkinSurface s, PreskinSkinLighting k, PreskinProfileMix m, sampler2DArray diffuseLut,
                      vec3 V, PreskinLightSample l, vec3 shadowRgb, float specularVisibility, uint features,
                      vec4 ltcDfg) {
    PreskinSkinLightParts p =
        preskinSkinLightParts(s, k, m, diffuseLut, V, l, shadowRgb, specularVisibility, features, ltcDfg);
    return p.diffuse + p.specular;
}

// The same for a single light (finds the shared values on every call).
vec3 preskinSkinLight(PreskinSkinSurface s, PreskinProfileMix m, sampler2DArray diffuseLut, vec3 V, vec3 L,
                      vec3 irradiance, vec3 shadowRgb, float specularVisibility, uint features) {
    return preskinSkinLight(s, preskinSkinLighting(s, m, diffuseLut, V, features), m, diffuseLut, V, L, irradiance,
                            shadowRgb, specularVisibility, features);
}

// Each channel's width p (profile mm) when its response to a hard edge is taken as a Gaussian
// edge's, Phi(x / p): fitted to the penumbra LUT one reference width into the shadow, then, for
// channels that barely reach there, one narrowest width in. Depends on the profiles alone.
vec3 preskinPenumbraChannelWidths(PreskinProfileMix m, sampler2DArray penumbraLut) {
    float reference = 1.0 / m.mapping[0].penumbraWidth.x;
    vec3 r = clamp(preskinPenumbraLut(m, penumbraLut, preskinNormalCdf(-1.0), reference), 1e-4, 0.4999);
    vec3 p = -reference / vec3(preskinNormalQuantile(r.r), preskinNormalQuantile(r.g), preskinNormalQuantile(r.b));
    float narrow = min(p.r, min(p.g, p.b));
    vec3 near = clamp(preskinPenumbraLut(m, penumbraLut, preskinNormalCdf(-1.0), narrow), 1e-4, 0.4999);
    vec3 pNear = -narrow / vec3(preskinNormalQuantile(near.r), preskinNormalQuantile(near.g), preskinNormalQuantile(near.b));
    return mix(p, pNear, lessThan(r, vec3(0.02)));
}

// A hard edge's response `hard` (the penumbra LUT's, at x profile mm from the edge, > 0 lit) made
// that of a soft edge: the light's own penumbra, a Gaussian of standard deviation penumbraMm (a
// light with a size), blurs the edge before the skin scatters it. For a channel whose response
// to a hard edge is a Gaussian edge's, Phi(x / p) (p: preskinPenumbraChannelWidths), the soft
// edge's is Phi(x / sqrt(p^2 + penumbraMm^2)) (blurring adds variances); the result moves from
// the LUT's exact hard-edge response to that as the penumbra outgrows the channel's scattering
// (by penumbraMm^2 / (p^2 + penumbraMm^2)).
vec3 preskinSoftEdge(vec3 hard, float x, float penumbraMm, vec3 p) {
    vec3 v2 = penumbraMm * penumbraMm + p * p;
    vec3 soft = x * inversesqrt(v2);
    vec3 softEdge = vec3(preskinNormalCdf(soft.r), preskinNormalCdf(soft.g), preskinNormalCdf(soft.b));
    return mix(hard, softEdge, penumbraMm * penumbraMm / v2);
}

// Receiver millimetres per millimetre across a shadow edge in the light's image plane. The light
// projects the receiver's tangent plane onto its image plane, shortening only the direction in
// it that climbs towards the light, by N.L; a distance across an edge is stretched by
// 1 / sqrt(1 - (m . N)^2), m the unit direction across the edge in the image plane: 1 / N.L for
// an edge facing the light's approach, 1 for one running along it. m is along the visibility's
// gradient (PreskinShadowSample::gradientWs, any length); without one (no edge in the filter),
// the largest, 1 / N.L. Clamped to 5 near the terminator.
float preskinEdgeStretch(vec3 N, vec3 L, vec3 gradientWs) {
    float m2 = dot(gradientWs, gradientWs);
    float mN = dot(gradientWs, N);
    float c = m2 > 0.0 ? sqrt(max(1.0 - mN * mN / m2, 0.0)) : abs(dot(N, L));
    return 1.0 / max(c, 0.2);
}

// Per-channel shadow for skin given the channels' widths (preskinPenumbraChannelWidths; read only
// with a penumbra) and the receiver's profile mm per metre across the edge in the light's image
// plane, the two public forms' common part.
vec3 preskinSkinShadow(PreskinProfileMix m, sampler2DArray penumbraLut, float visibility, float filterWidthLightM,
                       float penumbraWidthLightM, vec3 channelWidthsMm, float toProfileMm, uint features) {
    // Fully lit or fully shadowed: the LUT's end columns are exactly 1 and 0, skip the fetch.
    if ((features & kSkinPenumbra) == 0u || visibility <= 0.0 || visibility >= 1.0) return vec3(visibility);
    float sigmaProfileMm = filterWidthLightM * toProfileMm;
    vec3 hard = preskinPenumbraLut(m, penumbraLut, visibility, sigmaProfileMm);
    if (penumbraWidthLightM <= 0.0) return hard;
    return preskinSoftEdge(hard, sigmaProfileMm * preskinNormalQuantile(visibility), penumbraWidthLightM * toProfileMm,
                           channelWidthsMm);
}

// How much of a shadow map's shadow at a skin point another surface casts (1) rather than the
// point's own surface (0), from the filter's occluders' distance along the light (Chiang, Li &
// Burley, "Taming the Shadow Terminator", SIGGRAPH 2019 Talks, on the terminator's
// self-shadowing). Past the terminator of convex skin the map shadows the receiver's own surface,
// whose light the diffuse LUT already holds, the light scattered past the terminator included
// (it integrates max(N.L, 0) of the neighbours over the osculating sphere); there the LUT's own
// falloff applies, unshadowed, penumbra scattering or not. The receiver's own surface can lie
// along the light within ownMm of it: one kernel width of the filter, plus past the terminator
// (N.L < 0) the chord to the osculating sphere's lit side, 2 a |N.L| (a = 1 / curvature). The
// light the LUT scattered there crossed the surface from the terminator, a |N.L| away (half the
// chord), so the chord is capped where that distance reaches the profile's reach (3 local
// patches, preskinMixPatchMm: farther, the LUT has no light left to lose), at 6 patches, which is
// also what flat and concave skin get (their LUT rows hold no light past the terminator, so
// nothing changes there but the per-channel normals' own), so that the share is continuous in
// the curvature. Occluders within ownMm are the receiver's own, beyond twice that
// another surface's (a nose, a lid over the eye, a crease's far wall), with a smooth step
// between. Occluding texels no nearer the light than the receiver (blockerDistanceM 0 with the
// visibility below 1) are its own surface, below the receiver plane the map extrapolates where
// the surface turns along the light (the inner rim of a torus lit along its axis): 0. Without the
// diffuse LUT (kSkinLutDiffuse off), or where the filter found no occluder, 1.
float preskinCastShadowShare(PreskinSkinSurface s, PreskinProfileMix m, PreskinShadowSample shadow, vec3 L,
                             uint features) {
    if ((features & kSkinLutDiffuse) == 0u || (shadow.blockerDistanceM <= 0.0 && shadow.visibility >= 1.0)) return 1.0;
    float c = dot(s.geometricNormal, L);
    float toMm = 1000.0 * s.scatterScale;
    float ownMm = max(shadow.kernelWidthM * toMm, 1e-6);
    if (c < 0.0) ownMm -= 2.0 * c / max(s.curvaturePerMm, -c / (3.0 * preskinMixPatchMm(m)));
    return smoothstep(ownMm, 2.0 * ownMm, shadow.blockerDistanceM * toMm);
}

// Per-channel shadow for skin: the penumbra LUT indexed by the filtered visibility and the
// filter's width on the receiver (its width in the light's image plane stretched across the edge,
// preskinEdgeStretch). The LUT takes the shadow as a hard edge that the filter blurred; a light
// with a size (shadow.penumbraWidthM > 0, preskinSampleShadow's) has a soft one (preskinSoftEdge).
// The receiver's own shadow at the terminator is lifted (preskinCastShadowShare).
vec3 preskinSkinShadow(PreskinSkinSurface s, PreskinProfileMix m, sampler2DArray penumbraLut,
                       PreskinShadowSample shadow, vec3 L, uint features) {
    vec3 widths = shadow.penumbraWidthM > 0.0 ? preskinPenumbraChannelWidths(m, penumbraLut) : vec3(0.0);
    float toProfileMm = 1000.0 * s.scatterScale * preskinEdgeStretch(s.geometricNormal, L, shadow.gradientWs);
    vec3 rgb = preskinSkinShadow(m, penumbraLut, shadow.visibility, shadow.kernelWidthM, shadow.penumbraWidthM, widths,
                                 toProfileMm, features);
    return mix(vec3(1.0), rgb, preskinCastShadowShare(s, m, shadow, L, features));
}

// The same with skin's wide shadow map (shaders/shadow_reduce.comp: each texel the nearest depth of
// a block of the shadow map, sampled by preskinSampleShadow with the wide map's parameters), which
// reaches past the shadow map's own filter: red scatters millimetres into a cast shadow. The
// edge's place x across it (profile mm, > 0 lit) comes from the shadow map's filter where that
// sees the edge (|Phi^-1(visibility)| < 2, blended out by 3) and from the wide map's filter
// beyond, moved half a wide texel into the shadow (the wide map's edges lie that far on the lit
// side on average); the penumbra LUT at the wide filter's width returns the profile's hard-edge
// response there; at the terminator (N.L from 0.1 down to 0.02) and where the wide map's
// occluders lie within red's reach of the receiver this fades to the shadow map's alone.
// wide: the wide map's sample; wideTexelM: its texel size (m). Where the shadow map's filter is as
// wide as the wide map's (a light with a size), the shadow map's alone.
vec3 preskinSkinShadowEdges(PreskinSkinSurface s, PreskinProfileMix m, sampler2DArray penumbraLut,
                            PreskinShadowSample shadow, PreskinShadowSample wide, float wideTexelM, vec3 L,
                            uint features) {
    float visibility = shadow.visibility;
    if ((features & kSkinPenumbra) == 0u) return vec3(visibility);
    bool fineEdge = visibility > 0.0 && visibility < 1.0;
    bool wideEdge = wide.visibility > 0.0 && wide.visibility < 1.0;
    if (!fineEdge && !wideEdge) return vec3(visibility);  // far from any edge (the wide map is never lit where this is not)
    // Across the edge both maps' filters see, the sharper one's gradient weighing most (their sum
    // turns smoothly from one to the other as either filter leaves the edge).
    float toProfileMm = 1000.0 * s.scatterScale *
                        preskinEdgeStretch(s.geometricNormal, L, shadow.gradientWs + wide.gradientWs);
    // At the terminator the wide kernel stretches over the skin by up to 1 / N.L and takes in the
    // receiver's own curve, which the diffuse LUT already holds: there the shadow map alone.
    // (Where that curve rises within red's reach it is also a near occluder, faded below; a fade
    // from N.L 0.35 lost red's reach on skin the light grazes, half of it at N.L 0.25.)
    float wideTrust = smoothstep(0.02, 0.1, dot(s.geometricNormal, L));
    wideTrust *= 1.0 - smoothstep(0.7, 1.0, shadow.kernelWidthM / max(wide.kernelWidthM, 1e-12));
    vec3 widths = shadow.penumbraWidthM > 0.0 ? preskinPenumbraChannelWidths(m, penumbraLut) : vec3(0.0);
    vec3 fineOnly = preskinSkinShadow(m, penumbraLut, visibility, shadow.kernelWidthM, shadow.penumbraWidthM, widths,
                                      toProfileMm, features);
    // An occluder within red's reach of the receiver along the light is the skin's own relief (a
    // crease's wall, an eyelid), not the far occluder over a plane that the penumbra LUT assumes:
    // the wide edge fades in as the occluders' distance grows from 1.5 to 3 RMS widths of the
    // widest profile.
    float widestMm = m.weight.x / m.mapping[0].penumbraWidth.x;  // the mix's, weighted
    if (int(PRESKIN_PROFILE_MIX_MAX) > 1) for (int i = 1; i < m.count; ++i) {
        if (m.weight[i] > 0.0) widestMm += m.weight[i] / preskinMixMapping(m, i).penumbraWidth.x;
    }
    wideTrust *= smoothstep(1.5 * widestMm, 3.0 * widestMm, wide.blockerDistanceM * 1000.0 * s.scatterScale);
    if (wideTrust <= 0.0) return fineOnly;
    float sigmaFine = shadow.kernelWidthM * toProfileMm;
    float sigmaWide = wide.kernelWidthM * toProfileMm;
    float x;
    if (fineEdge) {
        float q = preskinNormalQuantile(visibility);
        x = sigmaFine * q;
        if (wideEdge) {
            float xWide = sigmaWide * preskinNormalQuantile(wide.visibility) + 0.5 * wideTexelM * toProfileMm;
            x = mix(xWide, x, smoothstep(3.0, 2.0, abs(q)));
            x = clamp(x, sigmaFine * (q - 0.5), sigmaFine * (q + 0.5));  // where the fine filter puts it
        }
    } else {
        // The fine filter is saturated: the edge lies beyond its reach, 3 sigma, on the side it says.
        x = sigmaWide * preskinNormalQuantile(wide.visibility) + 0.5 * wideTexelM * toProfileMm;
        x = visibility >= 1.0 ? max(x, 3.0 * sigmaFine) : min(x, -3.0 * sigmaFine);
    }
    vec3 edge = preskinPenumbraLut(m, penumbraLut, preskinNormalCdf(x / sigmaWide), sigmaWide);
    if (shadow.penumbraWidthM > 0.0) edge = preskinSoftEdge(edge, x, shadow.penumbraWidthM * toProfileMm, widths);
    return mix(fineOnly, edge, wideTrust);
}

// The same with skin's wide map, the receiver's own shadow at the terminator lifted
// (preskinCastShadowShare): the forward pass's form.
vec3 preskinSkinShadow(PreskinSkinSurface s, PreskinProfileMix m, sampler2DArray penumbraLut,
                       PreskinShadowSample shadow, PreskinShadowSample wide, float wideTexelM, vec3 L,
                       uint features) {
    return mix(vec3(1.0), preskinSkinShadowEdges(s, m, penumbraLut, shadow, wide, wideTexelM, L, features),
               preskinCastShadowShare(s, m, shadow, L, features));
}

// Light that reaches the skin through the skin from a lit surface the light meets first
// (`occluder`, preskinShadowOccluder): the profile's integral over that surface, taken as its
// tangent plane, which lies (path along the light) x (its cosine to the light) from the point
// read: T(distance) (exact for Gaussian sums) times the plane's irradiance, its cosine.
//  - Where the skin faces away from the light: transmission through thin parts (after Jimenez et
//    al. 2010), the occluder read at preskinThicknessPointWs, the shrink depth added back. A sheet
//    lit obliquely scatters through its thickness, not through the light's longer path across it
//    (exact for a slab at any angle). Only light the diffuse LUT does not already hold is added:
//    the LUT integrates over the osculating sphere of convex skin, so the same term on that
//    sphere, sphereT (preskinSkinSphereTransmittance), is subtracted. On a sphere the two
//    cancel; a thin sheet (an ear) keeps T of the sheet.
//  - Where the skin faces the light but lies in a shadow cast from within the profile's reach
//    (a lid over the skin below it, a nostril's rim, a fold), the light the shadow takes lands on
//    the occluder's lit side and reaches the point the same way: the occluder read at the point,
//    its distanceM the shadow filter's mean distance to the occluding texels, times the shadowed
//    share 1 - visibility and the share of the plane the occluder covers around the plane's point
//    nearest the receiver (`coverage`, preskinOccluderCoverage). preskinSkinOccluder finds the
//    occluder and its coverage for either case. Occluders far beyond the profile's reach add
//    nothing (T vanishes); the light the receiver's own lit side sends across the shadow's edge
//    is the penumbra LUT's.
// A zero occluder distance adds nothing. Limits: sheets thinner than the shrink read as that
// thick; the occluder's slope is one texel's; the coverage is four taps.
vec3 preskinSkinTransmission(PreskinSkinSurface s, PreskinProfileMix m, sampler2DArray transmittanceLut, vec3 L,
                             vec3 irradiance, PreskinShadowOccluder occluder, vec3 sphereT, float visibility,
                             float coverage, uint features) {
    if ((features & kSkinTransmission) == 0u || occluder.distanceM <= 0.0) return vec3(0.0);
    bool facesAway = dot(s.geometricNormal, L) < 0.0;
    float distanceMm = occluder.distanceM * 1000.0 * s.thicknessScale * s.scatterScale * occluder.cosine +
                       (facesAway ? kSkinThicknessShrinkMm : 0.0);
    vec3 T = max(preskinTransmittanceLut(m, transmittanceLut, distanceMm) - (facesAway ? sphereT : vec3(0.0)),
                 vec3(0.0));
    float share = facesAway ? 1.0 : (1.0 - visibility) * coverage;
    return T * (occluder.cosine * share) * s.transmissionTint * s.albedo / PRESKIN_PI * irradiance;
}

// Light from the neighbours that face the point across an air gap or a contact, or from the
// other side of a thin part (the upper lip's underside facing the lit lower lip, a fold facing
// its wall, the far side of an ear): their profile-weighted normal integral per channel,
// opposing* = sum_b a_cb O_b (preskinOpposingNormal of preskin/skin_vertex.glsl, world space), dotted
// with L is the share of the light on them that reaches the point (for a sheet d thick, the
// profile's transmittance T(d) times the cosine). Whether the light reaches them: the shadow map
// at their centroid, one gather read bilinearly (preskinShadowVisibility2x2), occluders of the
// relief that forms the gap not counted (preskinSkinOpposingLookup of preskin/skin_vertex.glsl,
// `o`, found per vertex or per fragment). The light transmission takes from the far side of a
// thin part is also here: take the larger.
// Limits: one shadow lookup for the whole neighbourhood; neighbours on other meshes are not seen.
vec3 preskinSkinOpposingLight(PreskinSkinSurface s, sampler2D shadowMap, vec4 params, PreskinOpposingLookup o,
                              vec3 irradiance, uint features) {
    if ((features & kSkinOpposingLight) == 0u || max(max(o.facing.r, o.facing.g), o.facing.b) <= 0.0) return vec3(0.0);
    PreskinShadowReceiver r;
    r.uv = o.shadowUvZ.xy;
    r.z = o.shadowUvZ.z;
    r.dzPerTexel = o.dzPerTexel;
    r.inside = preskinShadowInside(r.uv, r.z);
    float visibility = preskinShadowVisibility2x2(shadowMap, params, r);
    return max(o.facing, vec3(0.0)) * visibility * s.transmissionTint * s.albedo / PRESKIN_PI * irradiance;
}

// The same, the lookup found here (centroidOffsetWs: the neighbours' centroid from positionWs).
vec3 preskinSkinOpposingLight(PreskinSkinSurface s, sampler2D shadowMap, mat4 shadowClipFromWorld, vec4 params,
                              vec3 positionWs, vec3 centroidOffsetWs, vec3 opposingR, vec3 opposingG,
                              vec3 opposingB, vec3 L, vec3 irradiance, uint features) {
    return preskinSkinOpposingLight(s, shadowMap, params,
                                    preskinSkinOpposingLookup(shadowClipFromWorld, params, positionWs, centroidOffsetWs,
                                                              opposingR, opposingG, opposingB, L, s.scatterScale),
                                    irradiance, features);
}

// The occluder preskinSkinTransmission takes for the light that owns the shadow map (towards L),
// and in `coverage` the share of its plane it covers: where the skin faces away from the light,
// read at preskinThicknessPointWs (coverage 1); where it faces the light inside the shadow
// (`shadow`, the shadow map's sample at the point: visibility below 1, occluders found), read at
// the point, its distance the filter's mean distance to the occluding texels (the slope bias
// added back), its coverage within the profiles' local patch (preskinOccluderCoverage);
// elsewhere none (distance 0).
PreskinShadowOccluder preskinSkinOccluder(PreskinSkinSurface s, PreskinProfileMix m, sampler2D shadowMap,
                                          mat4 shadowClipFromWorld, vec4 params, vec3 positionWs,
                                          PreskinShadowSample shadow, vec3 L, uint features, out float coverage) {
    coverage = 1.0;
    bool facesAway = preskinTransmissionGate(s.geometricNormal, L, features);
    bool shadowed = !facesAway && (features & kSkinTransmission) != 0u && shadow.visibility < 1.0 &&
                    shadow.blockerDistanceM > 0.0;
    if (!facesAway && !shadowed) return PreskinShadowOccluder(0.0, 1.0, vec2(0.0), vec2(0.0), 0.0);
    // One read for either case (a CPU driver runs both sides of a branch its lanes split over).
    vec3 readWs = facesAway ? preskinThicknessPointWs(positionWs, s.geometricNormal, s.scatterScale) : positionWs;
    PreskinShadowOccluder o = preskinShadowOccluder(shadowMap, shadowClipFromWorld, params, readWs);
    if (shadowed) {
        o.distanceM = shadow.blockerDistanceM + preskinShadowSlopeBiasM(o.slope, params);
        coverage = preskinOccluderCoverage(shadowMap, params, o,
                                           preskinShadowReceiverSlope(shadowClipFromWorld, s.geometricNormal, L),
                                           preskinMixPatchMm(m) * 0.001 / max(s.scatterScale, 1e-6));
    }
    return o;
}

// Transmission alone (the skin facing away from the light), the sphere's transmittance given.
vec3 preskinSkinTransmission(PreskinSkinSurface s, PreskinProfileMix m, sampler2DArray transmittanceLut, vec3 L,
                             vec3 irradiance, PreskinShadowOccluder occluder, vec3 sphereT, uint features) {
    return preskinSkinTransmission(s, m, transmittanceLut, L, irradiance, occluder, sphereT, 1.0, 0.0, features);
}

// Transmission alone, the sphere's transmittance found at the surface's curvature.
vec3 preskinSkinTransmission(PreskinSkinSurface s, PreskinProfileMix m, sampler2DArray transmittanceLut, vec3 L,
                             vec3 irradiance, PreskinShadowOccluder occluder, uint features) {
    vec3 sphereT = preskinSkinSphereTransmittance(m, transmittanceLut, s.curvaturePerMm, s.geometricNormal, L, features);
    return preskinSkinTransmission(s, m, transmittanceLut, L, irradiance, occluder, sphereT, features);
}

// Skin's SH band scales at one curvature (PreskinShTransfer of preskin/lut.glsl): the SH transfer
// table's, or Lambert's (pi, 2 pi / 3, pi / 4) in every channel without kSkinShAmbient.
PreskinShTransfer preskinSkinShTransfer(PreskinProfileMix m, sampler2DArray shTransferLut, float curvaturePerMm,
                                        uint features) {
    if ((features & kSkinShAmbient) != 0u) return preskinShTransfer(m, shTransferLut, curvaturePerMm);
    return PreskinShTransfer(PRESKIN_SH_LAMBERT, PRESKIN_SH_LAMBERT, PRESKIN_SH_LAMBERT);
}

// Diffuse ambient irradiance per channel from L2 SH radiance (multiply by albedo / pi).
vec3 preskinSkinAmbientIrradiance(PreskinSkinSurface s, PreskinShTransfer t, vec4 sh[9], uint features) {
    if ((features & kSkinNormalPrefilter) == 0u)  // one normal for all channels
        return max(preskinShEvaluateRgb(sh, s.normalG, t.red, t.green, t.blue), vec3(0.0));
    return max(vec3(preskinShEvaluateChannel(sh, s.normalR, t.red, 0), preskinShEvaluateChannel(sh, s.normalG, t.green, 1),
                    preskinShEvaluateChannel(sh, s.normalB, t.blue, 2)),
               vec3(0.0));
}

// The shadow map's filter for skin (preskinSampleShadow): 8 x 8 texels, the standard material's,
// with kSkinFullShadowFilter; without it 6 x 6 (9 gathers instead of 16), the Gaussian of the same
// sigma windowed at 3 texels, which narrows it where sigma exceeds about 1.2 texels (the filter
// reports the width it has, which the penumbra LUT reads).
PreskinShadowFilter preskinSkinShadowFilter(uint features) {
    if ((features & kSkinFullShadowFilter) != 0u) return kPreskinShadowMapFilter;
    return PreskinShadowFilter(3, 0.0, 0.0, 1.0);
}

// How far concave skin rises towards the light within a shadow filter's reach (m; the filter's
// riseM), which its own walls must not shadow: a crease of mean curvature H (1 / m; curvaturePerMm
// in profile mm as preskinCurvatureProfilePerMm gives it, negative where concave) bends by 2H
// across, k r^2 / 2 at the kernel's reach r (reachM on the map, r / N.L on the skin), seen along
// the light by N.L (NoL: the geometric normal's with the light, held at 0.3 or more).
float preskinSkinConcaveRiseM(float curvaturePerMm, float scatterScale, float NoL, float reachM) {
    float concavePerM = max(-curvaturePerMm / max(scatterScale, 1e-6), 0.0) * 1000.0;
    return concavePerM * reachM * reachM / max(abs(NoL), 0.3);
}

// Skin's filter for the shadow light at a fragment. A light with a size (penumbraPerM > 0,
// preskinSampleShadow) keeps the 8 x 8 filter whatever the features: its penumbra is the filter's
// width, which the 6 x 6 window would cut (a 1-degree sun over a skin plane: skin's error 1.03 of
// Lambert's with 6 x 6, 0.90 with 8 x 8, the low tier,
// SunShadow.SkinPenumbraIsCloserToTheReferenceThanLambert). Concave skin (curvaturePerMm < 0)
// gets the depth its walls rise within the filter's window (preskinSkinConcaveRiseM; texelM the
// shadow map's texel, NoL the geometric normal's with the light): on the head's views against the
// diffusion reference, concave skin away from cast shadows 0.805 -> 0.786 of Lambert's error
// (mean of the four views; twice the rise, 0.774), no region farther.
PreskinShadowFilter preskinSkinShadowFilter(uint features, float penumbraPerM, float curvaturePerMm,
                                            float scatterScale, float NoL, float texelM) {
    PreskinShadowFilter f = penumbraPerM > 0.0 ? kPreskinShadowMapFilter : preskinSkinShadowFilter(features);
    f.riseM = preskinSkinConcaveRiseM(curvaturePerMm, scatterScale, NoL, float(f.gathersPerAxis) * texelM);
    return f;
}

// Where skin looks up the shadow map for the light towards L: near the terminator, the point
// lifted along its normal by the sagitta of its osculating sphere (radius 1 / |curvature|) over
// the local patch (radius rho = m.diffuseNoL.w profile mm, LutSet::localPatchMm),
// h = (1 - cos(rho |k|)) / |k|. From there the patch itself cannot occlude the light, so the
// shadow map carries cast shadows only: on a closed surface the terminator's self-shadowing is
// left to the diffuse LUT, which already holds it (max(N.L, 0) of every neighbour) together with
// the light scattered past it. The lift fades out where the patch cannot reach the terminator
// (N.L above sin(rho |k|)), so shadows cast onto lit skin keep their place; flat skin is not
// lifted. lift: preskinSkinShadowLift (preskin/skin_vertex.glsl).
vec3 preskinSkinShadowPosition(vec3 positionWs, vec3 geometricNormalWs, vec3 L, vec2 lift) {
    float fade = lift.y > 0.0 ? preskinSaturate(1.0 - dot(geometricNormalWs, L) / lift.y) : 0.0;
    return positionWs + geometricNormalWs * (fade * lift.x);
}

// The same, the lift found at one curvature (profile 1/mm).
vec3 preskinSkinShadowPosition(vec3 positionWs, vec3 geometricNormalWs, vec3 L, float curvaturePerMm,
                               float scatterScale, LutMapping m) {
    return preskinSkinShadowPosition(positionWs, geometricNormalWs, L,
                                     preskinSkinShadowLift(curvaturePerMm, scatterScale, m));
}

// Ambient light of the environment's L2 SH radiance: diffuse from the per-channel transfer t
// (preskinSkinShTransfer; preskinSkinAmbientIrradiance times albedo / pi, less what the specular
// takes) plus specular from the cosine-convolved SH in the reflection direction, weighted by
// Karis's analytic split-sum environment BRDF (none with specularWeight 0). diffuseOut: the
// diffuse part alone. Multiply both by ambient occlusion.
vec3 preskinSkinAmbient(PreskinSkinSurface s, PreskinShTransfer t, vec4 sh[9], vec3 V, uint features,
                        out vec3 diffuseOut) {
    float NoV = max(dot(s.normalSpecular, V), 1e-4);
    vec3 envBrdf = preskinEnvBrdfApprox(s.F0, s.roughness, NoV) * s.specularWeight;
    vec3 R = reflect(-V, s.normalSpecular);
    vec3 specularSh = max(preskinShEvaluate(sh, R, PRESKIN_SH_LAMBERT), vec3(0.0)) / PRESKIN_PI;
    diffuseOut = s.albedo * preskinSkinAmbientIrradiance(s, t, sh, features) / PRESKIN_PI * (vec3(1.0) - envBrdf);
    return diffuseOut + specularSh * envBrdf;
}

// Ambient light with the environment's specular reflection from its prefiltered cube (preskin/
// ibl.glsl): each specular lobe (two with dual specular, mixed as for lights) has its own DFG
// table entry, and the cube is read once, at the lobes' weighted roughness (exact in a uniform
// environment; a second lookup costs a CPU driver about 4 % of a frame of the head); diffuse as
// above, less what the specular takes. diffuseOut: the diffuse part alone. Multiply both by
// ambient occlusion.
vec3 preskinSkinAmbient(PreskinSkinSurface s, PreskinShTransfer t, vec4 sh[9], samplerCube prefiltered, sampler2D dfg,
                        PreskinIbl ibl, vec3 V, uint features, out vec3 diffuseOut) {
    float NoV = max(dot(s.normalSpecular, V), 1e-4);
    vec3 R = reflect(-V, s.normalSpecular);
    vec2 r = (features & kSkinDualSpecular) != 0u ? clamp(s.roughness * s.lobes.xy, 0.03, 1.0) : vec2(s.roughness);
    vec2 ab0 = preskinDfg(dfg, NoV, r.x);
    vec3 envBrdf0 = (s.F0 * ab0.x + ab0.y) * s.specularWeight;
    vec3 envBrdf = envBrdf0;
    float lobeRoughness = r.x;
    if ((features & kSkinDualSpecular) != 0u) {
        vec2 ab1 = preskinDfg(dfg, NoV, r.y);
        envBrdf = mix(envBrdf0, (s.F0 * ab1.x + ab1.y) * s.specularWeight, s.lobes.z);
        lobeRoughness = mix(r.x, r.y, s.lobes.z);
    }
    vec3 specular = preskinPrefilteredRadiance(prefiltered, ibl, R, lobeRoughness) * envBrdf;
    diffuseOut = s.albedo * preskinSkinAmbientIrradiance(s, t, sh, features) / PRESKIN_PI * (vec3(1.0) - envBrdf);
    return diffuseOut + specular;
}

// The same, the transfer looked up at the surface's curvature.
vec3 preskinSkinAmbient(PreskinSkinSurface s, PreskinProfileMix m, sampler2DArray shTransferLut, vec4 sh[9], vec3 V,
                        uint features, out vec3 diffuseOut) {
    return preskinSkinAmbient(s, preskinSkinShTransfer(m, shTransferLut, s.curvaturePerMm, features), sh, V, features,
                              diffuseOut);
}

#endif
