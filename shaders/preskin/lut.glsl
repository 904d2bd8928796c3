// preskin/lut.glsl: lookups into the pre-integrated skin LUTs baked by preskin::LutSet
// (`preskin bake`): Penner & Borshukov's diffuse ring integral D(NoL, curvature) and penumbra
// scattering (GPU Pro 2, 2011), per-channel SH transfer A_l(curvature) (zonal coefficients of D;
// Lambert's pi, 2 pi / 3, pi / 4 for flat skin) and thin-slab transmittance T(thickness)
// (after Jimenez et al. 2010). The coordinate mapping is shared with the CPU
// (shared/lut_mapping.h), so LutSet::lookup* on the CPU returns the same values.
// All inputs are in profile units: curvature in 1/mm, widths and thickness in mm (convert world
// units with the material's scatter scale first). Results carry the profile's shape only;
// multiply by the material's albedo.
// Limits: bilinear lookups on the baked grid (values clamp at the axis ends); the penumbra
// table takes the shadow as a straight edge blurred by a Gaussian shadow filter of standard
// deviation filterSigmaMm (see engine/include/preskin/LutSet.h).
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

#endif
