// preskin/lut.glsl: lookups into the pre-integrated skin LUTs baked by preskin::LutSet
// (`preskin bake`): Penner & Borshukov's diffuse ring integral D(NoL, curvature) and penumbra
// scattering (GPU Pro 2, 2011), per-channel SH transfer A_l(curvature) (zonal coefficients of D;
// Lambert's pi, 2 pi / 3, pi / 4 for flat skin) and thin-slab transmittance T(thickness)
// (after Jimenez et al. 2010). The coordinate mapping is shared with the CPU
// (shared/lut_mapping.h), so LutSet::lookup* on the CPU returns the same values.
// All inputs are in profile units: curvature in 1/mm, widths and thickness in mm (convert world
// units with the material's scatter scale first). Results carry the profile's shape only;
// multiply by the material's albedo.
// Several profiles (preskin::ProfileLibrary): the tables are layers of 2D array textures, each
// layer with its own LutMapping; a PreskinProfileMix names up to four layers and their weights
// (a material's profile, or profiles blended per texel), and each lookup is the weighted sum of
// the layers' lookups.
// Limits: bilinear lookups on the baked grid (values clamp at the axis ends); the penumbra
// table takes the shadow as a straight edge blurred by a Gaussian shadow filter of standard
// deviation filterSigmaMm (see engine/include/preskin/LutSet.h). A blend of lookups is not the
// lookup of the blended profile (docs/profiles.md measures the difference).
#ifndef PRESKIN_LUT_GLSL
#define PRESKIN_LUT_GLSL

#include "shared/lut_mapping.h"

// Pre-integrated diffuse: replaces saturate(NoL) for skin (RGB, 0..1).
vec3 preskinDiffuseLut(LutMapping m, sampler2D diffuseLut, float NoL, float curvaturePerMm) {
    return textureLod(diffuseLut, preskinDiffuseLutUv(m, NoL, curvaturePerMm), 0.0).rgb;
}

// Penumbra scattering: replaces the filtered shadow visibility for skin (RGB, 0..1).
vec3 preskinPenumbraLut(LutMapping m, sampler2D penumbraLut, float shadow, float filterSigmaMm) {
    return textureLod(penumbraLut, preskinPenumbraLutUv(m, shadow, filterSigmaMm), 0.0).rgb;
}

// Per-channel zonal coefficients A_0, A_1, A_2 (absolute: flat skin gives pi, 2 pi / 3, pi / 4),
// to use as SH band scales in place of Lambert's.
void preskinShTransferLut(LutMapping m, sampler2D shTransferLut, float curvaturePerMm, out vec3 a0, out vec3 a1,
                          out vec3 a2) {
    a0 = m.shLambert.x * textureLod(shTransferLut, preskinShTransferLutUv(m, curvaturePerMm, 0), 0.0).rgb;
    a1 = m.shLambert.y * textureLod(shTransferLut, preskinShTransferLutUv(m, curvaturePerMm, 1), 0.0).rgb;
    a2 = m.shLambert.z * textureLod(shTransferLut, preskinShTransferLutUv(m, curvaturePerMm, 2), 0.0).rgb;
}

// Transmittance through thicknessMm of skin lit from behind (RGB, 1 at zero thickness).
vec3 preskinTransmittanceLut(LutMapping m, sampler2D transmittanceLut, float thicknessMm) {
    return textureLod(transmittanceLut, preskinTransmittanceLutUv(m, thicknessMm), 0.0).rgb;
}

// Up to four LUT layers and their weights (summing to 1; unused entries weigh 0).
struct PreskinProfileMix {
    LutMapping mapping[4];
    vec4 layer;   // array layer of each entry
    vec4 weight;
};

// One profile: layer `layer` with weight 1.
PreskinProfileMix preskinSingleProfile(LutMapping m, float layer) {
    PreskinProfileMix p;
    p.mapping[0] = m;
    p.mapping[1] = m;
    p.mapping[2] = m;
    p.mapping[3] = m;
    p.layer = vec4(layer);
    p.weight = vec4(1.0, 0.0, 0.0, 0.0);
    return p;
}

vec3 preskinDiffuseLut(PreskinProfileMix p, sampler2DArray diffuseLut, float NoL, float curvaturePerMm) {
    vec3 sum = vec3(0.0);
    for (int i = 0; i < 4; ++i) {
        if (p.weight[i] <= 0.0) continue;
        vec2 uv = preskinDiffuseLutUv(p.mapping[i], NoL, curvaturePerMm);
        sum += p.weight[i] * textureLod(diffuseLut, vec3(uv, p.layer[i]), 0.0).rgb;
    }
    return sum;
}

vec3 preskinPenumbraLut(PreskinProfileMix p, sampler2DArray penumbraLut, float shadow, float filterSigmaMm) {
    vec3 sum = vec3(0.0);
    for (int i = 0; i < 4; ++i) {
        if (p.weight[i] <= 0.0) continue;
        vec2 uv = preskinPenumbraLutUv(p.mapping[i], shadow, filterSigmaMm);
        sum += p.weight[i] * textureLod(penumbraLut, vec3(uv, p.layer[i]), 0.0).rgb;
    }
    return sum;
}

void preskinShTransferLut(PreskinProfileMix p, sampler2DArray shTransferLut, float curvaturePerMm, out vec3 a0,
                          out vec3 a1, out vec3 a2) {
    a0 = vec3(0.0);
    a1 = vec3(0.0);
    a2 = vec3(0.0);
    for (int i = 0; i < 4; ++i) {
        if (p.weight[i] <= 0.0) continue;
        LutMapping m = p.mapping[i];
        float w = p.weight[i];
        a0 += w * m.shLambert.x * textureLod(shTransferLut, vec3(preskinShTransferLutUv(m, curvaturePerMm, 0), p.layer[i]), 0.0).rgb;
        a1 += w * m.shLambert.y * textureLod(shTransferLut, vec3(preskinShTransferLutUv(m, curvaturePerMm, 1), p.layer[i]), 0.0).rgb;
        a2 += w * m.shLambert.z * textureLod(shTransferLut, vec3(preskinShTransferLutUv(m, curvaturePerMm, 2), p.layer[i]), 0.0).rgb;
    }
}

vec3 preskinTransmittanceLut(PreskinProfileMix p, sampler2DArray transmittanceLut, float thicknessMm) {
    vec3 sum = vec3(0.0);
    for (int i = 0; i < 4; ++i) {
        if (p.weight[i] <= 0.0) continue;
        vec2 uv = preskinTransmittanceLutUv(p.mapping[i], thicknessMm);
        sum += p.weight[i] * textureLod(transmittanceLut, vec3(uv, p.layer[i]), 0.0).rgb;
    }
    return sum;
}

#endif
