// preskin/brdf.glsl: the standard metal-rough BRDF of glTF 2.0 (specification, Appendix B):
// Lambert diffuse, GGX / Trowbridge-Reitz distribution (Walter et al. 2007), height-correlated
// Smith visibility (Heitz 2014), Schlick Fresnel (Schlick 1994); alpha = roughness^2.
// Limits: single scattering only (no multiple-scattering energy compensation).
#ifndef PRESKIN_BRDF_GLSL
#define PRESKIN_BRDF_GLSL

#include "preskin/common.glsl"
#include "preskin/light_sample.glsl"

float preskinGgxD(float NoH, float alpha) {
    float a2 = alpha * alpha;
    float d = NoH * NoH * (a2 - 1.0) + 1.0;
    return a2 / (PRESKIN_PI * d * d);
}

// V = G / (4 NoL NoV), height-correlated Smith for GGX; its view term
// sqrt(NoV^2 (1 - alpha^2) + alpha^2) apart, for a loop over lights to find it once.
float preskinSmithViewTerm(float NoV, float alpha) {
    float a2 = alpha * alpha;
    return sqrt(NoV * NoV * (1.0 - a2) + a2);
}

float preskinSmithV(float NoL, float NoV, float alpha, float viewTerm) {
    float a2 = alpha * alpha;
    float gv = NoL * viewTerm;
    float gl = NoV * sqrt(NoL * NoL * (1.0 - a2) + a2);
    return 0.5 / max(gv + gl, 1e-7);
}

float preskinSmithV(float NoL, float NoV, float alpha) {
    return preskinSmithV(NoL, NoV, alpha, preskinSmithViewTerm(NoV, alpha));
}

vec3 preskinSchlickF(vec3 F0, float VoH) {
    float m = 1.0 - preskinSaturate(VoH);
    float m2 = m * m;
    float f = m2 * m2 * m;  // (1 - VoH)^5 by multiplication: pow() is exp2(5 log2(x)) on some drivers
    return F0 + (vec3(1.0) - F0) * f;
}

// GGX specular lobe (D V F) for one light; multiply by NoL and the light's irradiance.
vec3 preskinSpecularGgx(vec3 F0, float roughness, float NoL, float NoV, float NoH, float VoH) {
    float alpha = max(roughness * roughness, 1e-3);
    return preskinGgxD(NoH, alpha) * preskinSmithV(NoL, NoV, alpha) * preskinSchlickF(F0, VoH);
}

// Split-sum environment BRDF fitted analytically: Karis, "Physically Based Shading on Mobile"
// (Unreal Engine blog, 2014). Scales F0 for the specular part of ambient lighting.
vec3 preskinEnvBrdfApprox(vec3 F0, float roughness, float NoV) {
    const vec4 c0 = vec4(-1.0, -0.0275, -0.572, 0.022);
    const vec4 c1 = vec4(1.0, 0.0425, 1.04, -0.04);
    vec4 r = roughness * c0 + c1;
    float a004 = min(r.x * r.x, exp2(-9.28 * NoV)) * r.x + r.y;
    vec2 ab = vec2(-1.04, 1.04) * a004 + r.zw;
    return F0 * ab.x + ab.y;
}

struct PreskinStandardSurface {
    vec3 diffuseColor;  // baseColor * (1 - metallic)
    vec3 F0;            // mix(0.04, baseColor, metallic)
    float roughness;    // perceptual
    float specularWeight;  // 1: GGX with Fresnel; 0: Lambert alone (no specular, no Fresnel on diffuse)
};

// Reflected radiance of one light: f(l, v) * NoL * irradiance (irradiance normal to the light).
vec3 preskinStandardLight(PreskinStandardSurface s, vec3 N, vec3 V, vec3 L, vec3 irradiance) {
    float NoL = dot(N, L);
    if (NoL <= 0.0) return vec3(0.0);
    vec3 H = normalize(L + V);
    float NoV = max(dot(N, V), 1e-4);
    float NoH = preskinSaturate(dot(N, H));
    float VoH = preskinSaturate(dot(V, H));
    vec3 F = s.specularWeight * preskinSchlickF(s.F0, VoH);
    float alpha = max(s.roughness * s.roughness, 1e-3);
    vec3 specular = F * preskinGgxD(NoH, alpha) * preskinSmithV(NoL, NoV, alpha);
    vec3 diffuse = (vec3(1.0) - F) * s.diffuseColor / PRESKIN_PI;
    return (diffuse + specular) * NoL * irradiance;
}

// Karis's normalisation of a GGX lobe for a light of a size (the representative point's peak
// spread over the widened lobe): (alpha / (alpha + alphaAdd))^2, alpha' at most 1.
float preskinSpecularNormalization(float alpha, float alphaAdd) {
    float widened = min(alpha + alphaAdd, 1.0);
    return (alpha * alpha) / (widened * widened);
}

// The same for any light (preskin/light_sample.glsl): a punctual light as above; a light with
// a size gives Lambert the cap's horizon-clipped irradiance and GGX its linearly transformed
// cosine (l.ltc; ltcDfg: the lobe's (A, B), PreskinLtc.dfg.xy) or its representative point.
vec3 preskinStandardLight(PreskinStandardSurface s, vec3 N, vec3 V, PreskinLightSample l, vec2 ltcDfg) {
    if (l.cosSigma >= 1.0) return preskinStandardLight(s, N, V, l.L, l.irradiance);
    float NoV = max(dot(N, V), 1e-4);
    vec3 Fd = s.specularWeight * preskinSchlickF(s.F0, preskinSaturate(dot(V, normalize(l.L + V))));
    vec3 color = (vec3(1.0) - Fd) * s.diffuseColor / PRESKIN_PI * (preskinCapLambert(dot(N, l.L), l.cosSigma, l.sinSigma) + l.lambertCorrection);
    float alpha = max(s.roughness * s.roughness, 1e-3);
    // The linearly transformed cosine, blended with the representative point for lights small
    // against the lobe (preskinLtcWeight).
    float t = preskinLtcWeight(l, alpha);
    vec3 ltc = t * s.specularWeight * preskinLtcSpecular(l, s.F0, ltcDfg, l.specularFormFactor.x, V);
    float NoL = dot(N, l.specularL);
    if (NoL > 0.0 && s.specularWeight > 0.0 && t < 1.0) {
        vec3 H = normalize(l.specularL + V);
        vec3 F = preskinSchlickF(s.F0, preskinSaturate(dot(V, H)));
        color += (1.0 - t) * s.specularWeight * F * preskinGgxD(preskinSaturate(dot(N, H)), alpha) *
                 preskinSmithV(NoL, NoV, alpha) * preskinSpecularNormalization(alpha, l.specularAlphaAdd) * NoL;
    }
    return color * l.irradiance + ltc;
}

#endif
