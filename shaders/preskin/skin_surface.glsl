// preskin/skin_surface.glsl: the per-fragment set-up of a PreskinSkinSurface (preskin/skin.glsl)
// from a host's textures and material values, so a host forward shader needs no skin code of
// its own:
//  - the tangent frame and tangent-space normal maps (glTF: +Y up, bitangent = cross(N, T) * w),
//    with an optional detail map blended over the base map (whiteout blend, Barre-Brisebois &
//    Hill, "Blending in Detail", 2012);
//  - per-channel normal prefiltering (Penner & Borshukov; d'Eon & Luebke): one level-of-detail
//    query, then the map at three levels lod + bias per channel (the biases from normalLodBias()
//    in <preskin/SkinParameters.h>), filtered trilinearly by hand from bilinear samples at whole
//    levels that the three channels share (preskinSampleLevels); the unbiased normal for specular,
//    from the same levels where the sampler does not filter anisotropically, else from the sampler;
//  - the curvature source (per-vertex, texture or screen derivatives; preskinCurvatureProfilePerMm
//    of preskin/lut.glsl converts it to profile 1/mm);
//  - skin F0 (kSkinF0 of shared/constants.h times the material's intensity and specular map);
//  - the thickness sample point (kSkinThicknessShrinkMm inside along the normal, after Jimenez
//    et al. 2010's shrink) and the gate that skips the shadow-map read where no transmission
//    shows (the skin faces the light: the diffuse LUT holds that light).
// Limits: the detail map's level follows the base map's (a fixed offset from their texel
// densities); texture curvature is read at the base colour's coordinates the host passes.
#ifndef PRESKIN_SKIN_SURFACE_GLSL
#define PRESKIN_SKIN_SURFACE_GLSL

#include "preskin/common.glsl"
#include "preskin/mip_levels.glsl"
#include "shared/skin_features.h"

// Tangent frame (tangent, bitangent, normal); a degenerate tangent gives (0, 0, N).
mat3 preskinTangentFrame(vec3 N, vec4 T) {
    vec3 t = T.xyz - N * dot(N, T.xyz);
    if (dot(t, t) < 1e-12) return mat3(vec3(0.0), vec3(0.0), N);
    t = normalize(t);
    return mat3(t, cross(N, t) * (T.w < 0.0 ? -1.0 : 1.0), N);
}

// How a skin material's normal maps are sampled.
struct PreskinNormalMaps {
    float scale;         // glTF normalTexture.scale
    bool hasDetail;      // a detail normal map is bound
    float detailUvScale; // detail uv = uv * detailUvScale
    float detailScale;   // strength of the detail map's xy
    vec3 lodBias;        // per-channel level-of-detail bias (red, green, blue): normalLodBias()
    int levelCount;      // whole levels the biased samples blend: normalLevelCount() (preskinSampleLevels)
    bool specularFromLevels;  // the unbiased normal blended from the same levels (a sampler without anisotropic
                              // filtering gives the same; levelCount must then span bias 0 too)
};

// Tangent-space normal from a texel of the base map and one of the detail map (whiteout blend;
// without a detail map its texel is not read).
vec3 preskinNormalTs(vec3 baseTexel, vec3 detailTexel, PreskinNormalMaps maps) {
    vec3 base = baseTexel * 2.0 - 1.0;
    base.xy *= maps.scale;
    if (maps.hasDetail) {
        vec3 detail = detailTexel * 2.0 - 1.0;
        detail.xy *= maps.detailScale;
        base = vec3(base.xy + detail.xy, base.z * detail.z);
    }
    base.z = max(base.z, 1e-4);
    return base;
}

// The surface's four normals from the maps: normalSpecular (unbiased) and normalR/G/B
// (prefiltered per channel when kSkinNormalPrefilter is set, else equal to normalSpecular: each
// channel's geometric normal carrying the map at that channel's level, or with
// kSkinNormalMapLevels off the one unbiased sample).
// geometricNormal: the interpolated vertex normal facing the viewer; geometricR/G/B: the same
// prefiltered per channel (the mesh seen through each channel's profile, <preskin/NormalBasis.h>;
// the geometric normal where the host has none), whose tangent frames carry each channel's map
// sample; tangentWs: xyz, w sign.
void preskinSkinNormals(sampler2D normalMap, sampler2D detailMap, PreskinNormalMaps maps, vec2 uv,
                        vec3 geometricNormal, vec3 geometricR, vec3 geometricG, vec3 geometricB, vec4 tangentWs,
                        uint features, out vec3 normalSpecular, out vec3 normalR, out vec3 normalG,
                        out vec3 normalB) {
    mat3 tbn = preskinTangentFrame(geometricNormal, tangentWs);
    vec2 uvDetail = uv * maps.detailUvScale;
    bool perChannel = (features & kSkinNormalPrefilter) != 0u;
    bool levels = perChannel && (features & kSkinNormalMapLevels) != 0u;  // else one sample for all channels
    vec3 base = vec3(0.5, 0.5, 1.0);
    vec3 detail = vec3(0.5, 0.5, 1.0);
    if (!levels || !maps.specularFromLevels) {
        base = texture(normalMap, uv).rgb;
        if (maps.hasDetail) detail = texture(detailMap, uvDetail).rgb;
    }
    vec3 baseR = base, baseG = base, baseB = base;
    vec3 detailR = detail, detailG = detail, detailB = detail;
    if (levels) {
        // The fourth level of detail: the unbiased one with specularFromLevels, else the red one again.
        vec3 unbiased;
        float lod = textureQueryLod(normalMap, uv).y;
        float lodW = maps.specularFromLevels ? 0.0 : maps.lodBias.r;
        preskinSampleLevels(normalMap, uv, vec4(lod + maps.lodBias, lod + lodW), maps.levelCount, baseR, baseG, baseB,
                            unbiased);
        if (maps.specularFromLevels) base = unbiased;
        if (maps.hasDetail) {
            float detailLod = textureQueryLod(detailMap, uvDetail).y;
            preskinSampleLevels(detailMap, uvDetail, vec4(detailLod + maps.lodBias, detailLod + lodW), maps.levelCount,
                                detailR, detailG, detailB, unbiased);
            if (maps.specularFromLevels) detail = unbiased;
        }
    }
    normalSpecular = normalize(tbn * preskinNormalTs(base, detail, maps));
    normalR = perChannel ? normalize(preskinTangentFrame(geometricR, tangentWs) * preskinNormalTs(baseR, detailR, maps))
                     : normalSpecular;
    normalG = perChannel ? normalize(preskinTangentFrame(geometricG, tangentWs) * preskinNormalTs(baseG, detailG, maps))
                     : normalSpecular;
    normalB = perChannel ? normalize(preskinTangentFrame(geometricB, tangentWs) * preskinNormalTs(baseB, detailB, maps))
                     : normalSpecular;
}

// The same without prefiltered geometric normals (all three the geometric normal).
void preskinSkinNormals(sampler2D normalMap, sampler2D detailMap, PreskinNormalMaps maps, vec2 uv,
                        vec3 geometricNormal, vec4 tangentWs, uint features, out vec3 normalSpecular,
                        out vec3 normalR, out vec3 normalG, out vec3 normalB) {
    preskinSkinNormals(normalMap, detailMap, maps, uv, geometricNormal, geometricNormal, geometricNormal,
                       geometricNormal, tangentWs, features, normalSpecular, normalR, normalG, normalB);
}

// Curvature in 1/m from screen-space derivatives (Penner's fallback: constant per triangle).
float preskinCurvatureFromDerivatives(vec3 normalWs, vec3 positionWs) {
    float dn = length(fwidth(normalWs));
    float dp = length(fwidth(positionWs));
    return dp > 0.0 ? dn / dp : 0.0;
}

// World curvature (1/m) from the material's source (kCurvatureSource* of shared/constants.h):
// the interpolated per-vertex value, the curvature texture's red channel less its bias (the value
// of zero curvature: 0.5 for signed maps) times its scale (1/m), or the screen derivatives of the geometric normal and position.
float preskinSkinCurvaturePerM(uint source, float vertexCurvaturePerM, sampler2D curvatureTexture, vec2 uv,
                               float textureBias, float textureScalePerM, vec3 geometricNormal, vec3 positionWs) {
    if (source == kCurvatureSourceTexture) return (texture(curvatureTexture, uv).r - textureBias) * textureScalePerM;
    if (source == kCurvatureSourceDerivatives) return preskinCurvatureFromDerivatives(geometricNormal, positionWs);
    return vertexCurvaturePerM;
}

// The surface's principal curvatures about their mean, from the interpolated normal's screen
// derivatives (dN = S dP over the pixel's steps dPx, dPy and the normal's dNx, dNy; call them in
// uniform control flow): the unit tangent `axis` of the larger normal curvature and half the two
// curvatures' difference, in profile 1/mm (world 1/mm / scatterScale), >= 0. A light's diffuse
// LUT row (preskinSkinLightCurvaturePerMm of preskin/skin.glsl) reads the curvature along it from
// these; 0 (no derivatives, or concave skin, curvaturePerMm <= 0, whose rows keep the mean) gives
// every light the mean curvature's row.
void preskinSkinCurvatureSpread(vec3 N, float curvaturePerMm, float scatterScale, vec3 dPx, vec3 dPy, vec3 dNx,
                                vec3 dNy, out vec3 axis, out float spreadPerMm) {
    vec3 e1 = dPx - dot(dPx, N) * N;
    float l1 = length(e1);
    axis = vec3(0.0);
    spreadPerMm = 0.0;
    if (curvaturePerMm <= 0.0 || l1 <= 0.0) return;
    e1 /= l1;
    vec3 e2 = cross(N, e1);
    mat2 P = mat2(dot(dPx, e1), dot(dPx, e2), dot(dPy, e1), dot(dPy, e2));
    float det = determinant(P);
    if (!(abs(det) > 1e-20)) return;
    mat2 S = mat2(dot(dNx, e1), dot(dNx, e2), dot(dNy, e1), dot(dNy, e2)) * inverse(P);
    // S's symmetric part less its mean: [[p, q], [q, -p]], eigenvalues +-sqrt(p^2 + q^2).
    float p = 0.5 * (S[0][0] - S[1][1]);
    float q = 0.5 * (S[1][0] + S[0][1]);
    float spread = sqrt(p * p + q * q);
    if (!(spread > 0.0)) return;
    // The eigenvector of +spread: (p + spread, q), or (0, 1) where p = -spread.
    vec2 v = p >= 0.0 ? vec2(p + spread, q) : vec2(q, spread - p);
    axis = normalize(v.x * e1 + v.y * e2);
    spreadPerMm = min(spread * 0.001 / max(scatterScale, 1e-6), 1e4);
}

// Skin's specular reflectance at normal incidence.
vec3 preskinSkinF0(float specularIntensity, float specularMap) { return vec3(kSkinF0 * specularIntensity * specularMap); }

// Where to read the shadow map's occluder (what preskinSkinTransmission expects):
// kSkinThicknessShrinkMm profile-mm inside along the normal, so the shadow map's depth bias does
// not dominate where the light enters at a grazing angle.
vec3 preskinThicknessPointWs(vec3 positionWs, vec3 geometricNormal, float scatterScale) {
    return positionWs - geometricNormal * (kSkinThicknessShrinkMm * 0.001 / max(scatterScale, 1e-6));
}

// Whether transmission can show for light direction L (else skip the thickness read): the
// technique is on and the skin faces away from the light.
bool preskinTransmissionGate(vec3 geometricNormal, vec3 L, uint features) {
    return (features & kSkinTransmission) != 0u && dot(geometricNormal, L) < 0.0;
}

#endif
