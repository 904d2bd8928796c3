// preskin/light_sample.glsl: what one light gives a surface point, for lights with a size as well
// as punctual ones (docs/area-lights.md). A light is the cap of directions it covers, or for a
// rectangle, disc or tube the cap with the same vector form factor F = (1/pi) int omega dOmega
// (Heitz & Hill, "Real-Time Line- and Disk-Light Shading with Linearly Transformed Cosines",
// 2017, approximate the horizon-clipped form factor of any light by the sphere cap of equal F):
// its axis F / |F| and angular radius sigma, sin^2(sigma) = |F|, carrying the light's radiance.
// A punctual light is the cap of radius 0. Materials turn a cap into reflected light here:
// Lambert by the exact horizon-clipped irradiance of a uniform cap (Snyder, "Area Light Sources
// for Real-Time Graphics", Microsoft Research TR-96-11, 1996), skin by averaging its diffuse LUT
// over the cap (preskinCapNodes), specular by the lobes' linearly transformed cosines
// (PreskinLtc, Heitz et al. 2016; table fitted in engine/src/env/Ltc.h) blended for small lights
// with the representative point (Karis, "Real Shading in Unreal Engine 4", SIGGRAPH 2013 course,
// GGX widened by the cap's half angle), which is all a host without the table gets.
// Stands alone: no bindings.
#ifndef PRESKIN_LIGHT_SAMPLE_GLSL
#define PRESKIN_LIGHT_SAMPLE_GLSL

#include "preskin/common.glsl"

// Linearly transformed cosines for specular (Heitz, Dupuy, Hill & Neubelt, SIGGRAPH 2016), one
// fragment's: for each GGX lobe the map from world directions to the space where the lobe is a
// clamped cosine (M^-1 times the lobe's frame: the normal and the view's tangent direction), and
// each lobe's directional albedo split (A, B) (preskinLtc in preskin/ibl.glsl fills it from the
// table the renderer binds; env/Ltc.h fits it).
struct PreskinLtc {
    mat3 lobe0;
    mat3 lobe1;
    vec4 dfg;  // xy: lobe 0's (A, B); zw: lobe 1's
};

struct PreskinLightSample {
    vec3 L;                  // the cap's axis, unit (punctual lights: the direction to the light)
    vec3 irradiance;         // the light's radiance times the cap's solid angle (punctual: irradiance normal to L)
    float cosSigma;          // cos of the cap's angular radius: 1 punctual, -1 all directions (inside a sphere light)
    float sinSigma;          // its sine, carried apart so that small caps keep their precision (0 for all directions)
    vec3 specularL;          // the representative point's direction for specular (L for punctual lights)
    float specularAlphaAdd;  // added to GGX's alpha for the light's size (0 punctual)
    // Where the cap stands for another shape: the shape's exact horizon-clipped Lambert term at the
    // shading normal less the cap's (preskinCapLambert), in the units of preskinCapLambert. Lambert
    // adds it to the cap's term, skin to each channel's response (0 for spheres and punctual lights).
    float lambertCorrection;
    // With linearly transformed cosines (preskinLightSample given a PreskinLtc): the light's radiance
    // and, per lobe, its shape's integral of the lobe's normalised cosine; specular is then radiance
    // times (F0 A + B) times that, instead of the representative point.
    bool ltc;
    vec3 radiance;
    vec2 specularFormFactor;
};

PreskinLightSample preskinPunctualSample(vec3 L, vec3 irradiance) {
    return PreskinLightSample(L, irradiance, 1.0, 0.0, L, 0.0, 0.0, false, vec3(0.0), vec2(0.0));
}

// How much of a lobe of GGX alpha `alpha` takes the light's linearly transformed cosine rather than
// its representative point: the fitted cosine matches the lobe's integral over a large light but
// not its value in one direction, which a light far smaller than the lobe samples; so 0 for a
// punctual light, 1 once the light's angular radius reaches the lobe's width, smooth between.
float preskinLtcWeight(PreskinLightSample l, float alpha) {
    return l.ltc ? smoothstep(0.0, 1.0, l.sinSigma / max(alpha, 1e-3)) : 0.0;
}

// Specular of a lobe with the sample's linearly transformed cosine: the lobe's integral over the
// light (its albedo A + B with Fresnel 1, dfg = (A, B), times formFactor) times its radiance, and
// Fresnel (Schlick) at the half vector of V and the light's representative direction: the part of
// the lobe the light covers, where the lobe's mean Fresnel (F0 A + B) / (A + B) would take the
// whole lobe's (multiply by the specular weight).
vec3 preskinLtcSpecular(PreskinLightSample l, vec3 F0, vec2 dfg, float formFactor, vec3 V) {
    float m = 1.0 - preskinSaturate(dot(V, normalize(l.specularL + V)));
    float m2 = m * m;
    vec3 F = F0 + (vec3(1.0) - F0) * (m2 * m2 * m);
    return F * ((dfg.x + dfg.y) * formFactor) * l.radiance;
}

// Lambert: the horizon-clipped irradiance of a uniform cap at angle acos(NoL) from the normal,
// per unit of irradiance as PreskinLightSample carries it (radiance times solid angle). Exact for
// a sphere light (Snyder 1996); saturate(NoL) for a punctual light; 1/4 for all directions.
float preskinCapLambert(float NoL, float cosSigma, float sinSigma) {
    if (cosSigma >= 1.0) return preskinSaturate(NoL);
    if (cosSigma <= -1.0) return 0.25;
    float s2 = max(sinSigma * sinSigma, 1e-30);
    float solidAngle = 2.0 * PRESKIN_PI * s2 / (1.0 + cosSigma);
    float c = clamp(NoL, -1.0, 1.0);
    float sinTheta = sqrt(max(1.0 - c * c, 0.0));
    if (c >= sinSigma) return c * 0.5 * (1.0 + cosSigma);  // the cap lies above the horizon
    if (c <= -sinSigma) return 0.0;                          // below it
    if (sinSigma < 0.02) {
        // A small cap across the horizon: a flat disc of radius sin(sigma) whose part above the
        // horizon line, at u = c / (sin(sigma) sin(theta)) of its radius, is averaged:
        // sin(sigma) sin(theta) (u (acos(-u) + u sqrt(1 - u^2)) + 2/3 (1 - u^2)^(3/2)) / pi.
        // (Snyder's closed form below cancels to nothing in single precision here.)
        float u = clamp(c / max(sinSigma * sinTheta, 1e-30), -1.0, 1.0);
        float r = sqrt(max(1.0 - u * u, 0.0));
        return sinSigma * sinTheta * (u * (acos(-u) + u * r) + (2.0 / 3.0) * r * r * r) / PRESKIN_PI;
    }
    float x = cosSigma / sinSigma;  // cot(sigma)
    float y = clamp(-x * c / max(sinTheta, 1e-7), -1.0, 1.0);
    float t = sinTheta * sqrt(max(1.0 - y * y, 0.0));
    return ((c * acos(y) - x * t) * s2 + atan(t, x)) / solidAngle;
}

// Four nodes c_k of n . omega over a cap (axis at cos(theta) = NoL from n, angular radius sigma)
// and their weights: the cap's directions at n . omega = c lie on an arc of the circle of that
// angle about n, of half angle psi(c) = acos((cos(sigma) - c cos(theta)) / (sin(acos c) sin(theta))),
// so the cap average of any function of n . omega is int f(c) psi(c) dc / int psi(c) dc; here
// by the midpoint rule over the range of c the cap spans, the nodes then moved to the cap's exact
// mean of c. Exact for functions linear in c, for a punctual light (all nodes at NoL) and for all
// directions (uniform c, nodes at -3/4 .. 3/4).
void preskinCapNodes(float NoL, float cosSigma, float sinSigma, out vec4 nodes, out vec4 weights) {
    float cosTheta = clamp(NoL, -1.0, 1.0);
    float sinTheta = sqrt(max(1.0 - cosTheta * cosTheta, 0.0));
    // cos(max(theta - sigma, 0)) and cos(min(theta + sigma, pi)) without the angles.
    float hi = cosTheta <= cosSigma ? cosTheta * cosSigma + sinTheta * sinSigma : 1.0;
    float lo = cosTheta + cosSigma >= 0.0 ? cosTheta * cosSigma - sinTheta * sinSigma : -1.0;
    nodes = lo + (hi - lo) * vec4(0.125, 0.375, 0.625, 0.875);
    vec4 sinBeta = sqrt(max(vec4(1.0) - nodes * nodes, vec4(0.0)));
    vec4 cosPsi = (vec4(cosSigma) - nodes * cosTheta) / max(sinBeta * sinTheta, vec4(1e-7));
    vec4 psi = acos(clamp(cosPsi, vec4(-1.0), vec4(1.0)));
    float sum = psi.x + psi.y + psi.z + psi.w;
    weights = sum > 1e-6 ? psi / sum : vec4(0.25);
    // The nodes moved together so that their mean is the cap's exact mean of n . omega,
    // cos(theta) (1 + cos(sigma)) / 2: exact for any response linear in n . omega.
    nodes = clamp(nodes + (cosTheta * 0.5 * (1.0 + cosSigma) - dot(weights, nodes)), vec4(-1.0), vec4(1.0));
}

#endif
