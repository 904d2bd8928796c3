// preskin/lut.glsl: lookups into the pre-integrated skin LUTs baked by preskin::LutSet
// (`preskin bake`): Penner & Borshukov's diffuse ring integral D(NoL, curvature) and penumbra
// scattering (GPU Pro 2, 2011), per-channel SH transfer A_l(curvature) (zonal coefficients of D;
// Lambert's pi, 2 pi / 3, pi / 4 for flat skin) and thin-slab transmittance T(thickness)
// (after Jimenez et al. 2010). The coordinate mapping is shared with the CPU
// (shared/lut_mapping.h), so LutSet::lookup* on the CPU returns the same values.
// All inputs are in profile units: curvature in 1/mm, widths and thickness in mm (convert world
// units with the material's scatter scale first). Results carry the profile's shape only;
// multiply by the material's albedo.
// The diffuse table is read per light and per colour channel, so it is stored as its bilinear
// footprints (preskin::lutFootprints: texel (c W + x, y) holds channel c of the 2x2 texels from
// (x, y)) and filtered here: one unfiltered fetch of one texel per channel instead of four.
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

// Where one fragment's curvature falls in a diffuse table: texel row y0 and the weight fy of row
// y0 + 1, found once per fragment and shared by all its lights.
struct PreskinDiffuseRow {
    float y0;
    float fy;
};

PreskinDiffuseRow preskinDiffuseRow(LutMapping m, sampler2DArray diffuseFootprints, float curvaturePerMm) {
    float height = float(textureSize(diffuseFootprints, 0).y);
    float y = preskinDiffuseLutV(m, curvaturePerMm) * height - 0.5;
    PreskinDiffuseRow row;
    row.y0 = clamp(floor(y), 0.0, height - 1.0);
    row.fy = clamp(y - row.y0, 0.0, 1.0);
    return row;
}

// Pre-integrated diffuse, replacing saturate(NoL) per channel: red at NoL.r, green at NoL.g,
// blue at NoL.b (the per-channel prefiltered normals; pass one NoL three times for RGB at one
// angle), on row `row` of layer `layer` of the footprint image (3 W x H). Bilinear with
// CLAMP_TO_EDGE at texel centres, as LINEAR filtering of the table itself (LutTable::sample on
// the CPU).
vec3 preskinDiffuseLut(LutMapping m, PreskinDiffuseRow row, sampler2DArray diffuseFootprints, float layer, vec3 NoL) {
    int width = textureSize(diffuseFootprints, 0).x / 3;
    vec3 u = vec3(preskinDiffuseLutU(m, NoL.r), preskinDiffuseLutU(m, NoL.g), preskinDiffuseLutU(m, NoL.b));
    vec3 x = u * float(width) - 0.5;
    vec3 x0 = clamp(floor(x), 0.0, float(width - 1));
    vec3 fx = clamp(x - x0, 0.0, 1.0);
    ivec3 column = ivec3(x0) + ivec3(0, width, 2 * width);
    vec4 r = texelFetch(diffuseFootprints, ivec3(column.r, int(row.y0), int(layer)), 0);
    vec4 g = texelFetch(diffuseFootprints, ivec3(column.g, int(row.y0), int(layer)), 0);
    vec4 b = texelFetch(diffuseFootprints, ivec3(column.b, int(row.y0), int(layer)), 0);
    vec3 near = mix(vec3(r.x, g.x, b.x), vec3(r.y, g.y, b.y), fx);  // row y0
    vec3 far = mix(vec3(r.z, g.z, b.z), vec3(r.w, g.w, b.w), fx);   // row y0 + 1
    return mix(near, far, row.fy);
}

// The same at one curvature (finds the row on every call).
vec3 preskinDiffuseLut(LutMapping m, sampler2DArray diffuseFootprints, float layer, vec3 NoL, float curvaturePerMm) {
    return preskinDiffuseLut(m, preskinDiffuseRow(m, diffuseFootprints, curvaturePerMm), diffuseFootprints, layer, NoL);
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

// The diffuse rows of a mix's entries at one fragment's curvature (preskinDiffuseRow).
struct PreskinDiffuseRows {
    vec4 y0;
    vec4 fy;
};

PreskinDiffuseRows preskinDiffuseRows(PreskinProfileMix p, sampler2DArray diffuseFootprints, float curvaturePerMm) {
    PreskinDiffuseRows rows;
    PreskinDiffuseRow row = preskinDiffuseRow(p.mapping[0], diffuseFootprints, curvaturePerMm);
    rows.y0 = vec4(row.y0);
    rows.fy = vec4(row.fy);
    if (int(PRESKIN_PROFILE_MIX_MAX) > 1) for (int i = 1; i < p.count; ++i) {
        row = preskinDiffuseRow(preskinMixMapping(p, i), diffuseFootprints, curvaturePerMm);
        rows.y0[i] = row.y0;
        rows.fy[i] = row.fy;
    }
    return rows;
}

// The lookups of a mix: entry 0 always, entries 1..count-1 of non-zero weight in a loop (not
// compiled where PRESKIN_PROFILE_MIX_MAX is 1). With the rows found once per fragment
// (preskinDiffuseRows), for a loop over lights:
vec3 preskinDiffuseLut(PreskinProfileMix p, PreskinDiffuseRows rows, sampler2DArray diffuseFootprints, vec3 NoL) {
    PreskinDiffuseRow row;
    row.y0 = rows.y0.x;
    row.fy = rows.fy.x;
    vec3 sum = p.weight.x * preskinDiffuseLut(p.mapping[0], row, diffuseFootprints, p.layer.x, NoL);
    if (int(PRESKIN_PROFILE_MIX_MAX) > 1) for (int i = 1; i < p.count; ++i) {
        if (p.weight[i] <= 0.0) continue;
        row.y0 = rows.y0[i];
        row.fy = rows.fy[i];
        sum += p.weight[i] * preskinDiffuseLut(preskinMixMapping(p, i), row, diffuseFootprints, p.layer[i], NoL);
    }
    return sum;
}

// At one curvature (finds the rows on every call).
vec3 preskinDiffuseLut(PreskinProfileMix p, sampler2DArray diffuseFootprints, vec3 NoL, float curvaturePerMm) {
    return preskinDiffuseLut(p, preskinDiffuseRows(p, diffuseFootprints, curvaturePerMm), diffuseFootprints, NoL);
}

vec3 preskinPenumbraLut(PreskinProfileMix p, sampler2DArray penumbraLut, float shadow, float filterSigmaMm) {
    vec3 sum = p.weight.x * textureLod(penumbraLut, vec3(preskinPenumbraLutUv(p.mapping[0], shadow, filterSigmaMm), p.layer.x), 0.0).rgb;
    if (int(PRESKIN_PROFILE_MIX_MAX) > 1) for (int i = 1; i < p.count; ++i) {
        if (p.weight[i] <= 0.0) continue;
        vec2 uv = preskinPenumbraLutUv(preskinMixMapping(p, i), shadow, filterSigmaMm);
        sum += p.weight[i] * textureLod(penumbraLut, vec3(uv, p.layer[i]), 0.0).rgb;
    }
    return sum;
}

// One entry's weighted SH transfer added to a0..a2.
void preskinShTransferLutAdd(LutMapping m, sampler2DArray shTransferLut, float layer, float weight,
                             float curvaturePerMm, inout vec3 a0, inout vec3 a1, inout vec3 a2) {
    a0 += weight * m.shLambert.x * textureLod(shTransferLut, vec3(preskinShTransferLutUv(m, curvaturePerMm, 0), layer), 0.0).rgb;
    a1 += weight * m.shLambert.y * textureLod(shTransferLut, vec3(preskinShTransferLutUv(m, curvaturePerMm, 1), layer), 0.0).rgb;
    a2 += weight * m.shLambert.z * textureLod(shTransferLut, vec3(preskinShTransferLutUv(m, curvaturePerMm, 2), layer), 0.0).rgb;
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

vec3 preskinTransmittanceLut(PreskinProfileMix p, sampler2DArray transmittanceLut, float thicknessMm) {
    vec3 sum = p.weight.x * textureLod(transmittanceLut, vec3(preskinTransmittanceLutUv(p.mapping[0], thicknessMm), p.layer.x), 0.0).rgb;
    if (int(PRESKIN_PROFILE_MIX_MAX) > 1) for (int i = 1; i < p.count; ++i) {
        if (p.weight[i] <= 0.0) continue;
        vec2 uv = preskinTransmittanceLutUv(preskinMixMapping(p, i), thicknessMm);
        sum += p.weight[i] * textureLod(transmittanceLut, vec3(uv, p.layer[i]), 0.0).rgb;
    }
    return sum;
}

#endif
