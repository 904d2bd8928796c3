// LutMapping: every parameter a shader needs to turn physical quantities (NoL, curvature in
// 1/mm, filtered shadow value and shadow-filter width in mm, thickness in mm) into texture
// coordinates of the four skin LUTs, and the mapping functions themselves, written once for
// C++ (LutSet's CPU lookups) and GLSL (shaders/preskin/lut.glsl). Axis definitions and the
// physics behind them: engine/include/preskin/LutSet.h; the texel-centre convention:
// engine/include/preskin/LutTable.h (node i of an N-texel axis at u = (i + 0.5) / N).
//
// Textures (the renderer uploads LutTable::rgba16f() as R16G16B16A16_SFLOAT, LINEAR filter,
// CLAMP_TO_EDGE, no mips): diffuse (x NoL, y curvature), penumbra (x shadow, y filter width),
// SH transfer (x curvature, y band 0..2; sample exactly at the band rows), transmittance
// (x thickness, one row).
//
// Limits: all lookups are bilinear on the baked grid; inputs outside an axis range clamp to its
// ends (curvature above curvatureMaxPerMm reads the last row).
#ifndef PRESKIN_SHARED_LUT_MAPPING_H
#define PRESKIN_SHARED_LUT_MAPPING_H

#include "shared/common.h"

#ifdef __cplusplus
#define PRESKIN_LUT_FN inline
#else
#define PRESKIN_LUT_FN
#endif

PRESKIN_GPU_BEGIN

struct LutMapping {
    vec4 diffuseNoL;        // x: u at NoL = 0; y: du/dNoL for NoL < 0; z: du/dNoL for NoL >= 0;
                            // w: local patch radius, profile mm (LutSet::localPatchMm)
    vec4 diffuseCurvature;  // x: 1 / curvatureMaxPerMm; y: v at curvature 0; z: dv/ds for c < 0; w: dv/ds for
                            // c >= 0, s = sqrt(saturate(|c| x))
    vec4 penumbraShadow;    // x: (N-1)/N; y: 0.5/N  (u = y + x saturate(shadow))
    vec4 penumbraWidth;     // x: 1 / referenceWidthMm; y: (N-1)/N; z: 0.5/N  (w = sigma x; v = z + y w / (w + 1))
    vec4 shCurvature;       // as diffuseCurvature, for the SH table's width
    vec4 shBandV;           // x, y, z: v of the rows of bands 0, 1, 2
    vec4 shLambert;         // xyz: pi, 2 pi / 3, pi / 4 (the table stores A_l relative to these)
    vec4 transmittance;     // x: 1 / scaleMm; y: 1 / ln(1 + maxMm / scaleMm); z: (N-1)/N; w: 0.5/N
};
PRESKIN_CHECK_SIZE(LutMapping, 128)

// Diffuse D(NoL, curvature): NoL = dot(N, L) (any sign), curvaturePerMm = signed mean curvature in
// profile 1/mm (1 / radius; > 0 convex, < 0 concave).
// Its two coordinates apart: u depends on the light, v on the fragment only.
PRESKIN_LUT_FN float preskinDiffuseLutU(LutMapping m, float NoL) {
    float n = clamp(NoL, -1.0f, 1.0f);
    return m.diffuseNoL.x + n * ((n < 0.0f) ? m.diffuseNoL.y : m.diffuseNoL.z);
}

PRESKIN_LUT_FN float preskinDiffuseLutV(LutMapping m, float curvaturePerMm) {
    float s = sqrt(clamp(abs(curvaturePerMm) * m.diffuseCurvature.x, 0.0f, 1.0f));
    return m.diffuseCurvature.y + ((curvaturePerMm < 0.0f) ? -m.diffuseCurvature.z : m.diffuseCurvature.w) * s;
}

PRESKIN_LUT_FN vec2 preskinDiffuseLutUv(LutMapping m, float NoL, float curvaturePerMm) {
    return vec2(preskinDiffuseLutU(m, NoL), preskinDiffuseLutV(m, curvaturePerMm));
}

// Penumbra: shadow = filtered visibility in [0, 1]; filterSigmaMm = the shadow filter's Gaussian
// standard deviation on the receiver, across the edge, in profile mm.
PRESKIN_LUT_FN vec2 preskinPenumbraLutUv(LutMapping m, float shadow, float filterSigmaMm) {
    float u = m.penumbraShadow.y + m.penumbraShadow.x * clamp(shadow, 0.0f, 1.0f);
    float w = max(filterSigmaMm, 0.0f) * m.penumbraWidth.x;
    float v = m.penumbraWidth.z + m.penumbraWidth.y * (w / (w + 1.0f));
    return vec2(u, v);
}

// SH transfer: band in {0, 1, 2}.
PRESKIN_LUT_FN vec2 preskinShTransferLutUv(LutMapping m, float curvaturePerMm, int band) {
    float u = m.shCurvature.z + m.shCurvature.y * sqrt(clamp(curvaturePerMm * m.shCurvature.x, 0.0f, 1.0f));
    float v = (band == 0) ? m.shBandV.x : ((band == 1) ? m.shBandV.y : m.shBandV.z);
    return vec2(u, v);
}

// Transmittance: thicknessMm in profile mm.
PRESKIN_LUT_FN vec2 preskinTransmittanceLutUv(LutMapping m, float thicknessMm) {
    float t = min(log(1.0f + max(thicknessMm, 0.0f) * m.transmittance.x) * m.transmittance.y, 1.0f);
    return vec2(m.transmittance.w + m.transmittance.z * t, 0.5f);
}

PRESKIN_GPU_END

#endif
