// preskin/skin_vertex.glsl: the parts of pre-integrated skin (preskin/skin.glsl) that depend on
// the surface's curvature, its geometric normal and a directional light alone, none on the
// normal maps, so where curvature is per vertex a host can find them in the vertex stage and let
// the fragment stage interpolate them (the renderer does; a CPU driver such as lavapipe runs the
// vertex stage for a fraction of the invocations):
//  - the SH transfer (preskinShTransfer of preskin/lut.glsl);
//  - the lift of the shadow lookup above the local patch (preskinSkinShadowLift, used by
//    preskinSkinShadowPosition);
//  - the transmittance the diffuse LUT already holds (preskinSkinSphereTransmittance, subtracted
//    by preskinSkinTransmission).
// Interpolated across a triangle they differ from their value at the interpolated curvature by
// second-order terms. Also the geometric normal prefiltered per colour channel from the mesh's
// normal basis (preskinPrefilteredNormal). Every function here is valid in any shader stage.
#ifndef PRESKIN_SKIN_VERTEX_GLSL
#define PRESKIN_SKIN_VERTEX_GLSL

#include "preskin/common.glsl"
#include "preskin/lut.glsl"
#include "shared/skin_features.h"

// The mesh normal seen through one colour channel's profile (<preskin/NormalBasis.h>): `normal`
// the vertex normal, `basis` its normal basis (computeNormalBasis, kNormalBasisCount vectors, in
// the normal's space), `weights` the channel's basis weights (normalBasisWeights). Not unit
// length: normalise after interpolation.
vec3 preskinPrefilteredNormal(vec3 normal, vec3 basis[kNormalBasisCount], vec4 weights) {
    vec3 n = (1.0 - (weights.x + weights.y + weights.z + weights.w)) * normal;
    for (int b = 0; b < int(kNormalBasisCount); ++b) n += weights[b] * basis[b];
    return n;
}

// The opposing neighbours seen through one colour channel's profile (<preskin/NormalBasis.h>):
// sum_b a_b O_b for `opposing` the vertex's O_0 .. O_3 and `weights` the channel's basis weights,
// the vector whose dot product with a light's direction is the share of the light falling on them
// that reaches the vertex (preskinSkinOpposingLight). Not unit length; interpolate as it is.
vec3 preskinOpposingNormal(vec3 opposing[kNormalBasisCount], vec4 weights) {
    vec3 n = vec3(0.0);
    for (int b = 0; b < int(kNormalBasisCount); ++b) n += weights[b] * opposing[b];
    return n;
}

// The shadow lookup's lift for curvaturePerMm (profile 1/mm): x the height in world metres of the
// osculating sphere's sagitta over the local patch (radius rho = m.diffuseNoL.w profile mm,
// LutSet::localPatchMm), (1 - cos(rho |k|)) / |k|; y the N.L above which the lift has faded out,
// sin(rho |k|) (0 on flat skin). See preskinSkinShadowPosition.
vec2 preskinSkinShadowLift(float curvaturePerMm, float scatterScale, LutMapping m) {
    float k = abs(curvaturePerMm);
    float angle = min(m.diffuseNoL.w * k, PRESKIN_PI);
    float liftMm = angle < 1e-3 ? 0.5 * m.diffuseNoL.w * angle : (1.0 - cos(angle)) / k;
    float reach = sin(min(angle, 0.5 * PRESKIN_PI));
    return vec2(liftMm * 0.001 / max(scatterScale, 1e-6), reach);
}

// The lift of a profile mix: its profiles' lifts, weighted.
vec2 preskinSkinShadowLift(float curvaturePerMm, float scatterScale, PreskinProfileMix p) {
    vec2 lift = p.weight.x * preskinSkinShadowLift(curvaturePerMm, scatterScale, p.mapping[0]);
    if (int(PRESKIN_PROFILE_MIX_MAX) > 1) for (int i = 1; i < p.count; ++i) {
        if (p.weight[i] <= 0.0) continue;
        lift += p.weight[i] * preskinSkinShadowLift(curvaturePerMm, scatterScale, preskinMixMapping(p, i));
    }
    return lift;
}

// What the diffuse LUT already holds of the light a directional light sends through convex skin:
// preskinSkinTransmission's transmittance on the osculating sphere (radius a = 1/curvature). From
// the point kSkinThicknessShrinkMm = d inside, the light's path to the sphere's lit side is
// t = (a - d) c + r, r = sqrt((a - d)^2 c^2 + 2 a d - d^2), where the surface's cosine to the light
// is r / a: T(t r / a + d), c = saturate(-dot(geometricNormal, L)). Zero where the LUT diffuse is
// off and on flat or concave skin; where the skin faces the light, its value at the terminator
// (c = 0), so that found per vertex it interpolates across the terminator without a step.
vec3 preskinSkinSphereTransmittance(PreskinProfileMix m, sampler2DArray transmittanceLut, float curvaturePerMm,
                                    vec3 geometricNormal, vec3 L, uint features) {
    float c = preskinSaturate(-dot(geometricNormal, L));
    if ((features & (kSkinTransmission | kSkinLutDiffuse)) != (kSkinTransmission | kSkinLutDiffuse) ||
        curvaturePerMm <= 0.0)
        return vec3(0.0);
    float d = kSkinThicknessShrinkMm;
    float a = 1.0 / curvaturePerMm;
    float r = sqrt(max((a - d) * (a - d) * c * c + 2.0 * a * d - d * d, 0.0));
    float sphereMm = ((a - d) * c + r) * r / a + d;
    return preskinTransmittanceLut(m, transmittanceLut, sphereMm);
}

#endif
