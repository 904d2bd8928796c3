// preskin/lights.glsl: punctual lights as in KHR_lights_punctual: inverse-square falloff with
// the extension's recommended smooth range window, and its spot cone attenuation; and lights with
// a size (PRESKIN_lights_area: sphere, tube, rectangle, disc, and directional lights with an
// angular radius) as the cap of directions of preskin/light_sample.glsl (docs/area-lights.md). Stands alone: it needs only the GpuLight
// struct of shared/light.h, not the renderer's bindings.
// Limits: the range window follows the extension's recommendation, not physics (area lights take
// it at the distance to their centre); a tube, rectangle or disc is the sphere cap of its vector
// form factor, not its exact shape; a tube's form factor is a rectangle facing the point with a
// half sphere at each end.
#ifndef PRESKIN_LIGHTS_GLSL
#define PRESKIN_LIGHTS_GLSL

#include "preskin/light_sample.glsl"
#include "shared/light.h"

// The area light types a shader has code for: bit (type - kLightSphere) for each of sphere, tube,
// rectangle and disc (default all). A renderer that knows which its frame holds defines it (a
// specialization constant) before including: a CPU driver (lavapipe) runs the code of every
// branch under a lane mask, so code for absent types still costs it.
#ifndef PRESKIN_AREA_LIGHT_TYPES
#define PRESKIN_AREA_LIGHT_TYPES 15u
#endif

// type == which, and false at compile time where PRESKIN_AREA_LIGHT_TYPES leaves `which` out.
bool preskinIsLight(uint type, uint which) {
    return (uint(PRESKIN_AREA_LIGHT_TYPES) & (1u << (which - kLightSphere))) != 0u && type == which;
}

// Direction to the light (L) and irradiance normal to it at positionWs.
void preskinLightIncidence(GpuLight light, vec3 positionWs, out vec3 L, out vec3 irradiance) {
    uint type = uint(light.directionType.w);
    if (type == kLightDirectional) {
        L = -light.directionType.xyz;
        irradiance = light.colorIntensity.rgb;
        return;
    }
    vec3 toLight = light.positionRange.xyz - positionWs;
    float d2 = max(dot(toLight, toLight), 1e-8);
    L = toLight * inversesqrt(d2);
    float attenuation = 1.0 / d2;
    float range = light.positionRange.w;
    if (range > 0.0) {
        float r = d2 / (range * range);  // (d / range)^2
        float window = clamp(1.0 - r * r, 0.0, 1.0);
        attenuation *= window * window;
    }
    if (type == kLightSpot) {
        float cd = dot(light.directionType.xyz, -L);
        float a = clamp(cd * light.spotScaleOffset.x + light.spotScaleOffset.y, 0.0, 1.0);
        attenuation *= a * a;
    }
    irradiance = light.colorIntensity.rgb * attenuation;
}

// KHR_lights_punctual's range window at squared distance d2 (1 for an unlimited light).
float preskinRangeWindow(float d2, float range) {
    if (range <= 0.0) return 1.0;
    float r = d2 / (range * range);
    float window = clamp(1.0 - r * r, 0.0, 1.0);
    return window * window;
}

// Vector form factor of a polygon edge seen from the origin (unit corners a, b): the edge's
// part of (1/pi) int omega dOmega, acos(a . b) / (2 pi) times the unit normal of its plane.
vec3 preskinEdgeFormFactor(vec3 a, vec3 b) {
    vec3 n = cross(a, b);
    float s = length(n);  // sin of the edge's angle; the angle from atan, precise at both ends
    float thetaOverSin = s > 1e-7 ? atan(s, dot(a, b)) / s : 1.0;
    return n * (thetaOverSin / (2.0 * PRESKIN_PI));
}

// Vector form factor of the parallelogram centre +- u +- v (relative to the shaded point).
vec3 preskinQuadFormFactor(vec3 center, vec3 u, vec3 v) {
    vec3 p0 = normalize(center - u - v), p1 = normalize(center + u - v);
    vec3 p2 = normalize(center + u + v), p3 = normalize(center - u + v);
    vec3 F = preskinEdgeFormFactor(p0, p1) + preskinEdgeFormFactor(p1, p2) + preskinEdgeFormFactor(p2, p3) +
             preskinEdgeFormFactor(p3, p0);
    return dot(F, center) < 0.0 ? -F : F;  // towards the light whichever way the corners wind
}

// The form factor of the parallelogram centre +- u +- v seen from the shaded point with normal
// N: the polygon clipped by the tangent plane (at most five corners), then the edges' vector
// form factors along N. Exact: (1/pi) int max(N . omega, 0) dOmega over the light.
float preskinQuadClippedFormFactor(vec3 center, vec3 u, vec3 v, vec3 N) {
    // The clipped polygon streamed corner by corner, each edge's form factor summed as it closes
    // (no arrays: a CPU driver keeps indexed local arrays in memory for the whole shader).
    vec3 F = vec3(0.0), first = vec3(0.0), previous = vec3(0.0);
    int emitted = 0;
    for (int i = 0; i < 4; ++i) {
        vec3 a = center + (i == 1 || i == 2 ? u : -u) + (i >= 2 ? v : -v);
        int j = (i + 1) & 3;
        vec3 b = center + (j == 1 || j == 2 ? u : -u) + (j >= 2 ? v : -v);
        float da = dot(a, N), db = dot(b, N);
        for (int k = 0; k < 2; ++k) {
            bool emit = k == 0 ? da >= 0.0 : (da >= 0.0) != (db >= 0.0);
            if (!emit) continue;
            vec3 p = normalize(k == 0 ? a : a + (b - a) * (da / (da - db)));
            if (emitted == 0) first = p;
            else F += preskinEdgeFormFactor(previous, p);
            previous = p;
            ++emitted;
        }
    }
    if (emitted < 3) return 0.0;
    F += preskinEdgeFormFactor(previous, first);
    return abs(dot(F, N));
}

// Vector form factor of a disc of radius a, its centre at `center` from the shaded point, facing
// it along the unit normal m (dot(center, m) < 0): with h the point's height over the disc's
// plane, r its distance from the axis and S = h^2 + r^2 + a^2, Q = sqrt(S^2 - 4 r^2 a^2), the
// component along the axis is a^2 (1 - 2 r^2 / (Q + S)) / Q and towards the axis 2 h r a^2 /
// (Q (Q + S)) (the form factors of a differential area parallel and perpendicular to a disc,
// Howell's catalogue of radiation configuration factors, written without the division by r).
vec3 preskinDiscFormFactor(vec3 center, vec3 m, float a) {
    float h = -dot(center, m);
    vec3 w = -center - h * m;  // from the axis to the point, in the disc's plane
    float r2 = dot(w, w), a2 = a * a;
    float S = h * h + r2 + a2;
    float Q = sqrt(max(S * S - 4.0 * r2 * a2, 1e-30));
    return -m * (a2 * (1.0 - 2.0 * r2 / (Q + S)) / Q) - w * (2.0 * h * a2 / (Q * (Q + S)));
}

// A sphere (centre at `center` from the shaded point) as a cap: its axis, cos(sigma), and the
// solid angle over the sphere's projected area pi radius^2 (which turns candela into radiance
// times solid angle: 2 / ((1 + cos sigma) d^2), 1 / d^2 for a vanishing sphere).
void preskinSphereCap(vec3 center, float radius, out vec3 axis, out float cosSigma, out float sinSigma,
                      out float perArea) {
    float d2 = dot(center, center);
    if (d2 <= radius * radius) {  // inside: every direction
        axis = d2 > 0.0 ? center * inversesqrt(d2) : vec3(0.0, 1.0, 0.0);
        cosSigma = -1.0;
        sinSigma = 0.0;
        perArea = 4.0 / max(radius * radius, 1e-30);
        return;
    }
    float invD = inversesqrt(d2);
    axis = center * invD;
    sinSigma = radius * invD;
    cosSigma = sqrt(max(1.0 - sinSigma * sinSigma, 0.0));
    perArea = 2.0 / ((1.0 + cosSigma) * d2);
}

// The representative point of a sphere for specular: the point of the sphere nearest the
// reflected ray R (Karis 2013), relative to the shaded point.
vec3 preskinSphereRepresentative(vec3 center, float radius, vec3 R) {
    vec3 toRay = dot(center, R) * R - center;
    return center + toRay * preskinSaturate(radius * inversesqrt(max(dot(toRay, toRay), 1e-30)));
}

// The normalised clamped cosine's integral over a shape of vector form factor F in the cosine's
// space (z up), its horizon taken as the sphere cap's of equal F (Heitz & Hill 2017).
float preskinCappedFormFactor(vec3 F) {
    float f = length(F);
    float s2 = min(f, 1.0);
    if (s2 <= 0.0) return 0.0;
    float cosSigma = sqrt(1.0 - s2), sinSigma = sqrt(s2);
    return 2.0 * s2 / (1.0 + cosSigma) * preskinCapLambert(F.z / f, cosSigma, sinSigma);
}

// Vector form factor of the octagon centre + cos(k pi / 4) u + sin(k pi / 4) v, k = 0..7 (a disc
// of radius 1.0539 |u| has its area), in the space `m` maps to.
vec3 preskinOctagonFormFactor(mat3 m, vec3 center, vec3 u, vec3 v) {
    const float h = 0.70710678;
    vec3 c = m * center, a = m * u, b = m * v;
    vec3 p0 = normalize(c + a), p1 = normalize(c + h * (a + b)), p2 = normalize(c + b), p3 = normalize(c + h * (b - a));
    vec3 p4 = normalize(c - a), p5 = normalize(c - h * (a + b)), p6 = normalize(c - b), p7 = normalize(c + h * (a - b));
    vec3 F = preskinEdgeFormFactor(p0, p1) + preskinEdgeFormFactor(p1, p2) + preskinEdgeFormFactor(p2, p3) +
             preskinEdgeFormFactor(p3, p4) + preskinEdgeFormFactor(p4, p5) + preskinEdgeFormFactor(p5, p6) +
             preskinEdgeFormFactor(p6, p7) + preskinEdgeFormFactor(p7, p0);
    return dot(F, c) < 0.0 ? -F : F;
}

// Two unit vectors perpendicular to unit w and to each other.
void preskinPerpendicular(vec3 w, out vec3 u, out vec3 v) {
    u = normalize(cross(w, abs(w.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0)));
    v = cross(w, u);
}

// One lobe's integral of its normalised cosine over light `light` (centre at `center` from the
// shaded point), `m` the lobe's map (PreskinLtc): a rectangle exactly (clipped in the cosine's
// space); a tube as the rectangle facing the point of its projected area (2 r by l + pi r / 2);
// a disc as the octagon of its area, a sphere as its silhouette disc, their horizon by the cap.
float preskinLtcFormFactor(mat3 m, GpuLight light, uint type, vec3 center, float radius) {
    if (preskinIsLight(type, kLightRectangle))
        return preskinQuadClippedFormFactor(m * center, m * light.directionType.xyz, m * light.spotScaleOffset.xyz,
                                            vec3(0.0, 0.0, 1.0));
    if (preskinIsLight(type, kLightTube)) {
        vec3 halfAxis = light.directionType.xyz;
        float halfLength = length(halfAxis);
        vec3 across = cross(halfAxis, center);
        float acrossLength = length(across);
        if (acrossLength <= 1e-12 || halfLength <= 0.0) return 0.0;
        vec3 u = halfAxis * ((halfLength + 0.25 * PRESKIN_PI * radius) / halfLength);
        return preskinQuadClippedFormFactor(m * center, m * u, m * (across * (radius / acrossLength)), vec3(0.0, 0.0, 1.0));
    }
    vec3 u, v, c = center;
    float rho = 1.0539 * radius;
    if (preskinIsLight(type, kLightDisc)) {
        preskinPerpendicular(light.directionType.xyz, u, v);
    } else if (preskinIsLight(type, kLightSphere)) {  // its silhouette, a disc facing the point
        float d2 = dot(center, center);
        if (d2 <= radius * radius) return 1.0;
        preskinPerpendicular(center * inversesqrt(d2), u, v);
        float shrink = 1.0 - radius * radius / d2;
        c = center * shrink;
        rho *= sqrt(shrink);
    } else {
        return 0.0;
    }
    return preskinCappedFormFactor(preskinOctagonFormFactor(m, c, u * rho, v * rho));
}

// Light `light` at positionWs as a cap (preskin/light_sample.glsl); N: the shading normal (a
// rectangle's exact horizon-clipped form factor there corrects the cap's Lambert term); R: the
// reflected view direction, for the representative point of specular; with useLtc, each lobe of
// `ltc` also gets the light's integral of its linearly transformed cosine (preskinLtcFormFactor),
// which materials then use for specular instead. Punctual lights give preskinLightIncidence.
PreskinLightSample preskinLightSample(GpuLight light, vec3 positionWs, vec3 N, vec3 R, PreskinLtc ltc, bool useLtc) {
    uint type = uint(light.directionType.w);
    // A directional light with an angular radius sigma (where the shader has sphere code): a sphere
    // of radius sin(sigma) at unit distance, whose candela are then the light's lux.
    bool sun = (uint(PRESKIN_AREA_LIGHT_TYPES) & 1u) != 0u && type == kLightDirectional && light.spotScaleOffset.z > 0.0;
    if (type < kLightSphere && !sun) {
        vec3 L, irradiance;
        preskinLightIncidence(light, positionWs, L, irradiance);
        return preskinPunctualSample(L, irradiance);
    }
    vec3 center = sun ? -light.directionType.xyz : light.positionRange.xyz - positionWs;
    float window = sun ? 1.0 : preskinRangeWindow(dot(center, center), light.positionRange.w);
    vec3 intensity = light.colorIntensity.rgb * window;
    float radius = sun ? light.spotScaleOffset.z : light.spotScaleOffset.x;
    if (sun) type = kLightSphere;
    // The area-light size floor: a rectangle's half extents, a disc's and a tube's radius below a
    // thousandth of the distance are computed at that size. Below it the edges' form factors lose
    // their float precision (a 1e-10 m rectangle lost most of its light, a 1e-30 m one all of it);
    // the irradiance per candela does not (1 / d^2 times the facing cosine for a vanishing flat
    // light), so the light keeps its power, as a point light with its cosine falloff would, within
    // about 1e-6.
    float sizeFloor = 1e-3 * length(center);
    if (preskinIsLight(type, kLightRectangle)) {
        vec3 u = light.directionType.xyz, v = light.spotScaleOffset.xyz;
        light.directionType.xyz = u * max(1.0, sizeFloor / length(u));  // half sizes >= 5e-10 (toGpuLight)
        light.spotScaleOffset.xyz = v * max(1.0, sizeFloor / length(v));
    } else if (preskinIsLight(type, kLightDisc) || preskinIsLight(type, kLightTube)) {
        radius = max(radius, sizeFloor);
    }
    // The projected area the candela spread over: a sphere's or disc's pi r^2, a rectangle's w h, a
    // tube's broadside 2 r l + pi r^2.
    float area = PRESKIN_PI * radius * radius;
    if (preskinIsLight(type, kLightRectangle))
        area = 4.0 * length(light.directionType.xyz) * length(light.spotScaleOffset.xyz);
    if (preskinIsLight(type, kLightTube)) area += 4.0 * length(light.directionType.xyz) * radius;
    PreskinLightSample s;
    s.lambertCorrection = 0.0;
    vec3 representative;
    float perArea;  // radiance times solid angle per candela
    if (preskinIsLight(type, kLightSphere)) {
        preskinSphereCap(center, radius, s.L, s.cosSigma, s.sinSigma, perArea);
        representative = preskinSphereRepresentative(center, radius, R);
    } else {
        vec3 F = vec3(0.0);
        representative = center;
        if (preskinIsLight(type, kLightTube)) {
            // A rectangle facing the point along the axis, a half sphere at each end.
            vec3 halfAxis = light.directionType.xyz;
            vec3 across = cross(halfAxis, center);
            float acrossLength = length(across);
            across = acrossLength > 1e-12 ? across * (radius / acrossLength) : vec3(0.0);
            F = preskinQuadFormFactor(center, halfAxis, across);
            vec3 a0, a1;
            float c0, c1, s0, s1, unused;
            preskinSphereCap(center - halfAxis, radius, a0, c0, s0, unused);
            preskinSphereCap(center + halfAxis, radius, a1, c1, s1, unused);
            F += 0.5 * (s0 * s0 * a0 + s1 * s1 * a1);
            // Representative point: the axis point nearest the reflected ray (Karis 2013), then the sphere there.
            vec3 p0 = center - halfAxis, d = 2.0 * halfAxis;
            float rd = dot(R, d);
            float t = preskinSaturate((dot(R, p0) * rd - dot(p0, d)) / max(dot(d, d) - rd * rd, 1e-30));
            representative = preskinSphereRepresentative(p0 + t * d, radius, R);
        } else if (preskinIsLight(type, kLightRectangle) || preskinIsLight(type, kLightDisc)) {
            vec3 m, u = vec3(0.0), v = vec3(0.0);  // normal it emits along; half axes (rectangle)
            bool rectangle = preskinIsLight(type, kLightRectangle);
            if (rectangle) {
                u = light.directionType.xyz;
                v = light.spotScaleOffset.xyz;
                m = normalize(cross(v, u));
            } else {
                m = light.directionType.xyz;
            }
            if (dot(center, m) >= 0.0) return preskinPunctualSample(normalize(center), vec3(0.0));  // behind it
            if (rectangle) F = preskinQuadFormFactor(center, u, v);
            else F = preskinDiscFormFactor(center, m, radius);
            // Representative point: where the reflected ray meets the plane (or the plane's point
            // nearest the ray's point at the centre's distance), clamped to the light.
            float toward = -dot(R, m);
            vec3 hit = toward > 1e-4 ? R * (-dot(center, m) / toward) : R * length(center);
            vec3 q = hit - center;
            q -= dot(q, m) * m;
            if (rectangle) {
                vec2 extent = vec2(length(u), length(v));
                vec2 xy = clamp(vec2(dot(q, u), dot(q, v)) / extent, -extent, extent);
                representative = center + xy.x * (u / extent.x) + xy.y * (v / extent.y);
            } else {
                float ql = length(q);
                representative = center + (ql > radius ? q * (radius / ql) : q);
            }
        }
        float s2 = min(length(F), 1.0);
        s.L = s2 > 0.0 ? F / length(F) : normalize(center);
        s.cosSigma = sqrt(1.0 - s2);
        s.sinSigma = sqrt(s2);
        perArea = 2.0 * PRESKIN_PI * s2 / ((1.0 + s.cosSigma) * max(area, 1e-30));
        if (preskinIsLight(type, kLightRectangle) && s2 > 0.0) {
            // pi F_clipped / solid angle, in the sample's units, less the cap's own Lambert term.
            float solidAngle = 2.0 * PRESKIN_PI * s2 / (1.0 + s.cosSigma);
            float exact = PRESKIN_PI * preskinQuadClippedFormFactor(center, light.directionType.xyz,
                                                                    light.spotScaleOffset.xyz, N) / solidAngle;
            s.lambertCorrection = exact - preskinCapLambert(dot(N, s.L), s.cosSigma, s.sinSigma);
        }
    }
    s.irradiance = intensity * perArea;
    s.ltc = useLtc;
    s.radiance = vec3(0.0);
    s.specularFormFactor = vec2(0.0);
    if (useLtc) {
        s.radiance = intensity / max(area, 1e-30);
        s.specularFormFactor.x = preskinLtcFormFactor(ltc.lobe0, light, type, center, radius);
        s.specularFormFactor.y = ltc.lobe1 == ltc.lobe0 ? s.specularFormFactor.x
                                                        : preskinLtcFormFactor(ltc.lobe1, light, type, center, radius);
    }
    s.specularL = normalize(representative);
    s.specularAlphaAdd = s.cosSigma <= -1.0 ? 1.0 : 0.5 * s.sinSigma;
    return s;
}

// The same with specular at the representative point (a host that binds no LTC table).
PreskinLightSample preskinLightSample(GpuLight light, vec3 positionWs, vec3 N, vec3 R) {
    PreskinLtc none = PreskinLtc(mat3(1.0), mat3(1.0), vec4(0.0));
    return preskinLightSample(light, positionWs, N, R, none, false);
}

#endif
