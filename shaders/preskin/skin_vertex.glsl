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
#include "preskin/shadow.glsl"
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

// The diffuse LUT's row at one curvature as a smoothed ramp per channel, s (x + sqrt(x^2 + c^2)) / 2
// (preskinDiffuseRowFit of preskin/skin.glsl), through the row's values at N.L = 0 and 1:
// s c / 2 = D(0), s (1 + sqrt(1 + c^2)) / 2 = D(1); with rho = D(0) / D(1) = tan(atan(c) / 2),
// c = 2 rho / (1 - rho^2) and s = D(1) (1 - rho^2). What the lights a fragment shades without the
// table (preskinSkinNeedsRowFit of preskin/skin.glsl) read: it depends on the curvature alone.
struct PreskinDiffuseFit {
    vec3 scale;  // s per channel
    vec3 width;  // c per channel
};

// The fit that is Lambert's max(x, 0) (what a light gets with the diffuse LUT off).
const PreskinDiffuseFit kPreskinDiffuseFitLambert = PreskinDiffuseFit(vec3(1.0), vec3(0.0));

PreskinDiffuseFit preskinDiffuseFit(PreskinProfileMix m, PreskinDiffuseRows rows, sampler2DArray diffuseLut) {
    vec3 d0 = preskinDiffuseLut(m, rows, diffuseLut, vec3(0.0));
    vec3 d1 = preskinDiffuseLut(m, rows, diffuseLut, vec3(1.0));
    vec3 rho = min(d0 / max(d1, vec3(1e-4)), vec3(0.9));
    return PreskinDiffuseFit(d1 * (1.0 - rho * rho), 2.0 * rho / (1.0 - rho * rho));
}

PreskinDiffuseFit preskinDiffuseFit(PreskinProfileMix m, sampler2DArray diffuseLut, float curvaturePerMm) {
    return preskinDiffuseFit(m, preskinDiffuseRows(m, diffuseLut, curvaturePerMm), diffuseLut);
}

// What the opposing neighbours' light (preskinSkinOpposingLight of preskin/skin.glsl) needs of a
// directional light towards L that owns the shadow map, none of it from the normal maps: the share
// of the light on the neighbours that reaches the point per channel, opposing_c . L, and where
// their centroid (centroidOffsetWs from positionWs) falls on the map, lifted kSkinOpposingLiftMm
// towards the point, with the normal offset and receiver plane of preskinSampleShadow
// (preskinShadowReceiver) and the compared depth lowered by kSkinOpposingReliefMm: the relief that
// forms the gap (a lip over the lips' line, a helix over its fold) shadows the centroid, deep in
// the gap, but not the lit surface around it that sends the light, while a far occluder (a nose, a
// hat) shadows both. Distances in profile millimetres (scatterScale: profile mm per world mm).
// Where the opposing sums are per vertex (the renderer's) it is found in the vertex stage and
// interpolated: the map's transform is affine, so only the normalisation of the direction towards
// the point and the normal offset's grazing term are not interpolated exactly.
struct PreskinOpposingLookup {
    vec3 facing;      // opposing_c . L per channel
    vec3 shadowUvZ;   // the lifted centroid on the shadow map: uv, and the depth it is compared at
    vec2 dzPerTexel;  // the receiver plane's depth step per texel (PreskinShadowReceiver)
};

// No neighbours facing the point: nothing passed on, off the map.
const PreskinOpposingLookup kPreskinOpposingNone = PreskinOpposingLookup(vec3(0.0), vec3(-1.0, -1.0, 0.0), vec2(0.0));

PreskinOpposingLookup preskinSkinOpposingLookup(mat4 shadowClipFromWorld, vec4 params, vec3 positionWs,
                                                vec3 centroidOffsetWs, vec3 opposingR, vec3 opposingG, vec3 opposingB,
                                                vec3 L, float scatterScale) {
    vec3 sum = opposingR + opposingG + opposingB;
    if (dot(sum, sum) <= 0.0) return kPreskinOpposingNone;
    PreskinOpposingLookup o;
    o.facing = vec3(dot(opposingR, L), dot(opposingG, L), dot(opposingB, L));
    float toWorldM = 0.001 / max(scatterScale, 1e-6);
    vec3 towards = normalize(sum);
    PreskinShadowReceiver r = preskinShadowReceiver(shadowClipFromWorld, params,
                                                    positionWs + centroidOffsetWs + towards * (kSkinOpposingLiftMm * toWorldM),
                                                    towards, 1.0);
    o.shadowUvZ = vec3(r.uv, r.z - kSkinOpposingReliefMm * toWorldM / params.z);
    o.dzPerTexel = r.dzPerTexel;
    return o;
}

#endif
