// preskin/shadow.glsl: directional shadow map filtered by hand with a Gaussian-weighted PCF
// kernel. Lavapipe cannot filter depth formats (no LINEAR compare sampler), so each of the 4x4
// taps gathers the 2x2 nearest depths (textureGather, no filtering), compares them and blends
// the results bilinearly; tap offsets are fixed around the exact sample point and weighted by a
// Gaussian of standard deviation sigma, so the result varies continuously (no texel blocks) at a
// cost of 16 gathers for any sigma. Receiver-plane depth bias (Isidoro, "Shadow Mapping:
// GPU-based Tips and Techniques", GDC 2006) tilts the compared depth along the surface so wide
// kernels do not self-shadow sloped receivers. Also gives what skin needs: the occluder depth
// (thickness) and the filter's width in world units (penumbra LUT).
// Limits: one orthographic map (no cascades, no contact hardening); for sigma above ~1.5 texels
// the 4x4 taps under-sample the kernel (each tap is still a smooth bilinear footprint).
#ifndef PRESKIN_SHADOW_GLSL
#define PRESKIN_SHADOW_GLSL

#include "preskin/common.glsl"

struct PreskinShadowSample {
    float visibility;     // filtered, 0 (shadowed) .. 1 (lit)
    float thicknessM;     // receiver depth minus nearest occluder depth along the light, metres
    float kernelWidthM;   // standard deviation of the filter on the light's image plane, metres
};

// Distance along the light from the nearest occluder to positionWs (metres), 0 outside the map.
float preskinShadowThickness(sampler2D shadowMap, mat4 shadowClipFromWorld, vec4 params, vec3 positionWs) {
    vec4 clip = shadowClipFromWorld * vec4(positionWs, 1.0);
    vec2 uv = clip.xy * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return 0.0;
    ivec2 texel = clamp(ivec2(uv * params.w), ivec2(0), ivec2(params.w) - 1);
    return max(clip.z - texelFetch(shadowMap, texel, 0).r, 0.0) * params.z;
}

// shadowClipFromWorld: orthographic light matrix (depth 0 near .. 1 far).
// params: x texel size (m), y Gaussian sigma (texels), z depth range (m), w map size (texels).
PreskinShadowSample preskinSampleShadow(sampler2D shadowMap, mat4 shadowClipFromWorld, vec4 params,
                                        vec3 positionWs, vec3 geometricNormalWs) {
    PreskinShadowSample result;
    float mapSize = params.w;
    float sigma = max(params.y, 0.25);
    // Normal offset of one texel, larger at grazing light.
    vec3 r0 = vec3(shadowClipFromWorld[0][0], shadowClipFromWorld[1][0], shadowClipFromWorld[2][0]);
    vec3 r1 = vec3(shadowClipFromWorld[0][1], shadowClipFromWorld[1][1], shadowClipFromWorld[2][1]);
    vec3 r2 = vec3(shadowClipFromWorld[0][2], shadowClipFromWorld[1][2], shadowClipFromWorld[2][2]);
    vec3 lightDir = normalize(r2);
    float cosTheta = abs(dot(geometricNormalWs, lightDir));
    vec3 offsetWs = geometricNormalWs * params.x * (0.5 + 1.5 * sqrt(max(1.0 - cosTheta * cosTheta, 0.0)));
    vec4 clip = shadowClipFromWorld * vec4(positionWs + offsetWs, 1.0);
    vec2 uv = clip.xy * 0.5 + 0.5;
    float z = clip.z;

    // Depth gradient along the receiver plane per shadow-map texel, from the normal.
    vec3 n = geometricNormalWs;
    float n0 = dot(n, r0) / dot(r0, r0);
    float n1 = dot(n, r1) / dot(r1, r1);
    float n2 = dot(n, r2) / dot(r2, r2);
    n2 = sign(n2) * max(abs(n2), 1e-4 * (abs(n0) + abs(n1)) + 1e-12);
    vec2 dzPerTexel = clamp(-vec2(n0, n1) / n2 * (2.0 / mapSize), vec2(-0.02), vec2(0.02));
    const float bias = 2e-4;

    // 4 x 4 taps at +-0.5 and +-1.5 strides; a stride of 1.1 sigma keeps the Gaussian's shape
    // and never goes below one texel apart (bilinear taps then overlap).
    float stride = max(1.1 * sigma, 1.0);
    vec2 texel = uv * mapSize - 0.5;
    float sum = 0.0;
    float weightSum = 0.0;
    float varianceSum = 0.0;
    for (int j = 0; j < 4; ++j) {
        float oy = (float(j) - 1.5) * stride;
        for (int i = 0; i < 4; ++i) {
            float ox = (float(i) - 1.5) * stride;
            float w = exp(-(ox * ox + oy * oy) / (2.0 * sigma * sigma));
            vec2 t = texel + vec2(ox, oy);
            vec2 base = floor(t);
            vec2 f = t - base;
            // Gather order: (0,1), (1,1), (1,0), (0,0) relative to base.
            vec4 occluder = textureGather(shadowMap, (base + 1.0) / mapSize, 0);
            float receiver = z + dot(dzPerTexel, vec2(ox, oy)) - bias;
            vec4 lit = vec4(greaterThanEqual(occluder, vec4(receiver)));
            float top = mix(lit.w, lit.z, f.x);
            float bottom = mix(lit.x, lit.y, f.x);
            sum += w * mix(top, bottom, f.y);
            weightSum += w;
            varianceSum += w * ox * ox;
        }
    }
    bool inside = all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0))) && z <= 1.0;
    result.visibility = inside ? sum / weightSum : 1.0;
    result.thicknessM = preskinShadowThickness(shadowMap, shadowClipFromWorld, params, positionWs);
    // Per-axis standard deviation of the weighted taps; each bilinear tap's tent adds 1/6 texel^2.
    result.kernelWidthM = sqrt(varianceSum / weightSum + 1.0 / 6.0) * params.x;
    return result;
}

#endif
