// preskin/lut.glsl: lookups into the pre-integrated skin LUTs baked by preskin::LutSet
// (`preskin bake`): Penner & Borshukov's diffuse ring integral D(NoL, curvature) and penumbra
// scattering (GPU Pro 2, 2011), per-channel SH transfer A_l(curvature) (zonal coefficients of D;
// Lambert's pi, 2 pi / 3, pi / 4 for flat skin) and thin-slab transmittance T(thickness)
// (after Jimenez et al. 2010). The coordinate mapping is shared with the CPU
// (shared/lut_mapping.h), so LutSet::lookup* on the CPU returns the same values.
// All inputs are in profile units: curvature in 1/mm, widths and thickness in mm (convert world
// units with the material's scatter scale first). Results carry the profile's shape only;
// multiply by the material's albedo.
// Every table is stored as its channel planes (preskin::lutPlanes: one 32-bit float channel,
// the red, green and blue planes side by side, 3 W x H; texel (c W + x, y) holds channel c of
// texel (x, y)) and filtered here from one textureGather per channel: bilinear with
// CLAMP_TO_EDGE at texel centres, as LINEAR filtering of the table itself (LutTable::sample on
// the CPU) but with exact weights. The diffuse table is read per light and per channel; a CPU
// driver (lavapipe) gathers a single 32-bit channel for under half of what one texel of a
// four-channel half-float image costs it, and filters a four-channel texel at twice that again.
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

// World curvature (1/m) -> the LUTs' profile units (1/mm of the profile): world 1/m * 0.001 / scatter scale.
float preskinCurvatureProfilePerMm(float curvaturePerM, float scatterScale) {
    return curvaturePerM * 0.001 / max(scatterScale, 1e-6);
}

// One axis of a bilinear lookup in a plane `size` texels wide: the first texel x0 of the pair
// (x0, x0 + 1) and the weight of x0 + 1, clamped like CLAMP_TO_EDGE; the pair stays inside the
// plane (x0 <= size - 2), so it never reaches the next channel's plane.
vec2 preskinLutAxis(float u, float size) {
    float x = clamp(u * size - 0.5, 0.0, size - 1.0);
    float x0 = max(min(floor(x), size - 2.0), 0.0);
    return vec2(x0, x - x0);
}

// Channel `channel` (0..2) of layer `layer` filtered at the texel pair positions x = (x0, fx),
// y = (y0, fy) (preskinLutAxis), from one gather; imageSize = textureSize of the planes image.
float preskinLutGather(sampler2DArray planes, vec2 imageSize, float channel, vec2 x, vec2 y, float layer) {
    float column = channel * (imageSize.x / 3.0) + x.x;
    vec4 g = textureGather(planes, vec3((column + 1.0) / imageSize.x, (y.x + 1.0) / imageSize.y, layer), 0);
    // gather order: (x0, y0 + 1), (x0 + 1, y0 + 1), (x0 + 1, y0), (x0, y0)
    return mix(mix(g.w, g.z, x.y), mix(g.x, g.y, x.y), y.y);
}

// All three channels of layer `layer` at texture coordinates uv.
vec3 preskinLutBilinear(sampler2DArray planes, vec2 uv, float layer) {
    vec2 imageSize = vec2(textureSize(planes, 0).xy);
    vec2 x = preskinLutAxis(uv.x, imageSize.x / 3.0);
    vec2 y = preskinLutAxis(uv.y, imageSize.y);
    return vec3(preskinLutGather(planes, imageSize, 0.0, x, y, layer), preskinLutGather(planes, imageSize, 1.0, x, y, layer),
                preskinLutGather(planes, imageSize, 2.0, x, y, layer));
}

// Where one fragment's curvature falls in a diffuse table (preskinLutAxis of its v), found once
// per fragment and shared by all its lights.
vec2 preskinDiffuseRow(LutMapping m, sampler2DArray diffuseLut, float curvaturePerMm) {
    return preskinLutAxis(preskinDiffuseLutV(m, curvaturePerMm), float(textureSize(diffuseLut, 0).y));
}

// Pre-integrated diffuse, replacing saturate(NoL) per channel: red at NoL.r, green at NoL.g,
// blue at NoL.b (the per-channel prefiltered normals; pass one NoL three times for RGB at one
// angle), on row `row` (preskinDiffuseRow) of layer `layer`.
vec3 preskinDiffuseLut(LutMapping m, vec2 row, sampler2DArray diffuseLut, float layer, vec3 NoL) {
    vec2 imageSize = vec2(textureSize(diffuseLut, 0).xy);
    float width = imageSize.x / 3.0;
    return vec3(preskinLutGather(diffuseLut, imageSize, 0.0, preskinLutAxis(preskinDiffuseLutU(m, NoL.r), width), row, layer),
                preskinLutGather(diffuseLut, imageSize, 1.0, preskinLutAxis(preskinDiffuseLutU(m, NoL.g), width), row, layer),
                preskinLutGather(diffuseLut, imageSize, 2.0, preskinLutAxis(preskinDiffuseLutU(m, NoL.b), width), row, layer));
}

// The same at one curvature (finds the row on every call).
vec3 preskinDiffuseLut(LutMapping m, sampler2DArray diffuseLut, float layer, vec3 NoL, float curvaturePerMm) {
    return preskinDiffuseLut(m, preskinDiffuseRow(m, diffuseLut, curvaturePerMm), diffuseLut, layer, NoL);
}

// The most entries a PreskinProfileMix uses in this shader, 1..4 (default 4). A shader for
// materials without a profile blend defines it as 1 (a constant or a specialization constant)
// before including, which compiles the blend's lookups out: SIMD drivers on the CPU (lavapipe)
// run a loop's body once under an empty lane mask even when no fragment enters it.
#ifndef PRESKIN_PROFILE_MIX_MAX
#define PRESKIN_PROFILE_MIX_MAX 4
#endif

// Up to four LUT layers and their weights (summing to 1; unused entries weigh 0).
struct PreskinProfileMix {
    LutMapping mapping[4];
    vec4 layer;   // array layer of each entry
    vec4 weight;
    int count;    // entries in use, 1..4 (at most PRESKIN_PROFILE_MIX_MAX)
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
    p.count = 1;
    return p;
}

// Entry i >= 1 of a mix, picked with constant indices (an indexed local array costs a CPU driver
// per-lane memory traffic even where the loop below never runs).
LutMapping preskinMixMapping(PreskinProfileMix p, int i) {
    return i == 1 ? p.mapping[1] : (i == 2 ? p.mapping[2] : p.mapping[3]);
}

// The local patch radius of a mix (its profiles' LutSet::localPatchMm, weighted), profile mm.
float preskinMixPatchMm(PreskinProfileMix p) {
    float patchMm = p.weight.x * p.mapping[0].diffuseNoL.w;
    if (int(PRESKIN_PROFILE_MIX_MAX) > 1) for (int i = 1; i < p.count; ++i)
        patchMm += p.weight[i] * preskinMixMapping(p, i).diffuseNoL.w;
    return patchMm;
}

// The diffuse rows of a mix's entries at one fragment's curvature (preskinDiffuseRow): entry
// i's texel row in y0[i], its weight in fy[i].
struct PreskinDiffuseRows {
    vec4 y0;
    vec4 fy;
};

PreskinDiffuseRows preskinDiffuseRows(PreskinProfileMix p, sampler2DArray diffuseLut, float curvaturePerMm) {
    PreskinDiffuseRows rows;
    vec2 row = preskinDiffuseRow(p.mapping[0], diffuseLut, curvaturePerMm);
    rows.y0 = vec4(row.x);
    rows.fy = vec4(row.y);
    if (int(PRESKIN_PROFILE_MIX_MAX) > 1) for (int i = 1; i < p.count; ++i) {
        row = preskinDiffuseRow(preskinMixMapping(p, i), diffuseLut, curvaturePerMm);
        rows.y0[i] = row.x;
        rows.fy[i] = row.y;
    }
    return rows;
}

// The lookups of a mix: entry 0 always, entries 1..count-1 of non-zero weight in a loop (not
// compiled where PRESKIN_PROFILE_MIX_MAX is 1). With the rows found once per fragment
// (preskinDiffuseRows), for a loop over lights:
vec3 preskinDiffuseLut(PreskinProfileMix p, PreskinDiffuseRows rows, sampler2DArray diffuseLut, vec3 NoL) {
    vec3 sum = p.weight.x * preskinDiffuseLut(p.mapping[0], vec2(rows.y0.x, rows.fy.x), diffuseLut, p.layer.x, NoL);
    if (int(PRESKIN_PROFILE_MIX_MAX) > 1) for (int i = 1; i < p.count; ++i) {
        if (p.weight[i] <= 0.0) continue;
        sum += p.weight[i] *
               preskinDiffuseLut(preskinMixMapping(p, i), vec2(rows.y0[i], rows.fy[i]), diffuseLut, p.layer[i], NoL);
    }
    return sum;
}

// At one curvature (finds the rows on every call).
vec3 preskinDiffuseLut(PreskinProfileMix p, sampler2DArray diffuseLut, vec3 NoL, float curvaturePerMm) {
    return preskinDiffuseLut(p, preskinDiffuseRows(p, diffuseLut, curvaturePerMm), diffuseLut, NoL);
}

vec3 preskinPenumbraLut(PreskinProfileMix p, sampler2DArray penumbraLut, float shadow, float filterSigmaMm) {
    vec3 sum = p.weight.x * preskinLutBilinear(penumbraLut, preskinPenumbraLutUv(p.mapping[0], shadow, filterSigmaMm), p.layer.x);
    if (int(PRESKIN_PROFILE_MIX_MAX) > 1) for (int i = 1; i < p.count; ++i) {
        if (p.weight[i] <= 0.0) continue;
        vec2 uv = preskinPenumbraLutUv(preskinMixMapping(p, i), shadow, filterSigmaMm);
        sum += p.weight[i] * preskinLutBilinear(penumbraLut, uv, p.layer[i]);
    }
    return sum;
}

// One entry's weighted SH transfer added to a0..a2.
void preskinShTransferLutAdd(LutMapping m, sampler2DArray shTransferLut, float layer, float weight,
                             float curvaturePerMm, inout vec3 a0, inout vec3 a1, inout vec3 a2) {
    a0 += weight * m.shLambert.x * preskinLutBilinear(shTransferLut, preskinShTransferLutUv(m, curvaturePerMm, 0), layer);
    a1 += weight * m.shLambert.y * preskinLutBilinear(shTransferLut, preskinShTransferLutUv(m, curvaturePerMm, 1), layer);
    a2 += weight * m.shLambert.z * preskinLutBilinear(shTransferLut, preskinShTransferLutUv(m, curvaturePerMm, 2), layer);
}

void preskinShTransferLut(PreskinProfileMix p, sampler2DArray shTransferLut, float curvaturePerMm, out vec3 a0,
                          out vec3 a1, out vec3 a2) {
    a0 = vec3(0.0);
    a1 = vec3(0.0);
    a2 = vec3(0.0);
    preskinShTransferLutAdd(p.mapping[0], shTransferLut, p.layer.x, p.weight.x, curvaturePerMm, a0, a1, a2);
    if (int(PRESKIN_PROFILE_MIX_MAX) > 1) for (int i = 1; i < p.count; ++i) {
        if (p.weight[i] <= 0.0) continue;
        preskinShTransferLutAdd(preskinMixMapping(p, i), shTransferLut, p.layer[i], p.weight[i], curvaturePerMm, a0, a1, a2);
    }
}

// Skin's SH band scales: (A_0, A_1, A_2) of each colour channel, the zonal transfer of the diffuse
// response at curvature |curvaturePerMm| (ambient light is unshadowed: either sign reads the same).
// They depend on the curvature alone, so where curvature is per vertex they may be found in the
// vertex stage and interpolated (the renderer does).
struct PreskinShTransfer {
    vec3 red;
    vec3 green;
    vec3 blue;
};

PreskinShTransfer preskinShTransfer(PreskinProfileMix p, sampler2DArray shTransferLut, float curvaturePerMm) {
    vec3 a0, a1, a2;
    preskinShTransferLut(p, shTransferLut, abs(curvaturePerMm), a0, a1, a2);
    return PreskinShTransfer(vec3(a0.r, a1.r, a2.r), vec3(a0.g, a1.g, a2.g), vec3(a0.b, a1.b, a2.b));
}

vec3 preskinTransmittanceLut(PreskinProfileMix p, sampler2DArray transmittanceLut, float thicknessMm) {
    vec3 sum = p.weight.x * preskinLutBilinear(transmittanceLut, preskinTransmittanceLutUv(p.mapping[0], thicknessMm), p.layer.x);
    if (int(PRESKIN_PROFILE_MIX_MAX) > 1) for (int i = 1; i < p.count; ++i) {
        if (p.weight[i] <= 0.0) continue;
        vec2 uv = preskinTransmittanceLutUv(preskinMixMapping(p, i), thicknessMm);
        sum += p.weight[i] * preskinLutBilinear(transmittanceLut, uv, p.layer[i]);
    }
    return sum;
}

#endif
