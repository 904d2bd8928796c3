// preskin/shadow.glsl: directional shadow map filtered by hand with a Gaussian-weighted PCF
// kernel. Every tap is a NEAREST texelFetch (lavapipe cannot filter depth formats linearly);
// weights are a Gaussian of each texel centre's distance to the exact sample point, minus its
// value at the kernel edge, so the result varies continuously as the point moves (no texel
// blocks). Receiver-plane depth bias (Isidoro, "Shadow Mapping: GPU-based Tips and Techniques",
// GDC 2006) tilts the compared depth along the surface, so wide kernels do not self-shadow
// sloped receivers. Also returns what skin needs: the occluder depth for thickness and the
// kernel's width in world units for the penumbra LUT.
// Limits: one orthographic map (no cascades); kernel radius capped at 4 texels.
#ifndef PRESKIN_SHADOW_GLSL
#define PRESKIN_SHADOW_GLSL

#include "preskin/common.glsl"

struct PreskinShadowSample {
    float visibility;     // filtered, 0 (shadowed) .. 1 (lit)
    float thicknessM;     // receiver depth minus nearest occluder depth along the light, metres
    float kernelWidthM;   // Gaussian sigma of the filter on the light's image plane, metres
};

// shadowClipFromWorld: orthographic light matrix (depth 0 near .. 1 far).
// params: x texel size (m), y Gaussian sigma (texels), z depth range (m), w map size (texels).
PreskinShadowSample preskinSampleShadow(sampler2D shadowMap, mat4 shadowClipFromWorld, vec4 params,
                                        vec3 positionWs, vec3 geometricNormalWs) {
    PreskinShadowSample result;
    float mapSize = params.w;
    float sigma = max(params.y, 0.25);
    // Normal offset of one texel, smaller when the surface faces the light.
    vec3 lightDir = normalize(vec3(shadowClipFromWorld[0][2], shadowClipFromWorld[1][2], shadowClipFromWorld[2][2]));
    float cosTheta = abs(dot(geometricNormalWs, lightDir));
    vec3 offsetWs = geometricNormalWs * params.x * (0.5 + 1.5 * sqrt(max(1.0 - cosTheta * cosTheta, 0.0)));
    vec4 clip = shadowClipFromWorld * vec4(positionWs + offsetWs, 1.0);
    vec2 uv = clip.xy * 0.5 + 0.5;
    float z = clip.z;

    // Depth gradient along the receiver plane per shadow-map texel, from the normal.
    vec3 r0 = vec3(shadowClipFromWorld[0][0], shadowClipFromWorld[1][0], shadowClipFromWorld[2][0]);
    vec3 r1 = vec3(shadowClipFromWorld[0][1], shadowClipFromWorld[1][1], shadowClipFromWorld[2][1]);
    vec3 r2 = vec3(shadowClipFromWorld[0][2], shadowClipFromWorld[1][2], shadowClipFromWorld[2][2]);
    vec3 n = geometricNormalWs;
    float n0 = dot(n, r0) / dot(r0, r0);
    float n1 = dot(n, r1) / dot(r1, r1);
    float n2 = dot(n, r2) / dot(r2, r2);
    n2 = sign(n2) * max(abs(n2), 1e-4 * (abs(n0) + abs(n1)) + 1e-12);
    vec2 dzPerTexel = clamp(-vec2(n0, n1) / n2 * (2.0 / mapSize), vec2(-0.02), vec2(0.02));
    float bias = 2e-4;

    int radius = int(min(ceil(2.0 * sigma), 4.0));
    vec2 texel = uv * mapSize - 0.5;
    ivec2 base = ivec2(floor(texel));
    vec2 f = texel - vec2(base);
    float edge = exp(-float(radius * radius) / (2.0 * sigma * sigma));
    ivec2 maxTexel = ivec2(mapSize) - 1;
    float sum = 0.0;
    float weightSum = 0.0;
    for (int dy = -radius + 1; dy <= radius; ++dy) {
        float ty = float(dy) - f.y;
        float wy = max(exp(-ty * ty / (2.0 * sigma * sigma)) - edge, 0.0);
        for (int dx = -radius + 1; dx <= radius; ++dx) {
            float tx = float(dx) - f.x;
            float w = wy * max(exp(-tx * tx / (2.0 * sigma * sigma)) - edge, 0.0);
            float occluder = texelFetch(shadowMap, clamp(base + ivec2(dx, dy), ivec2(0), maxTexel), 0).r;
            float receiver = z + dot(dzPerTexel, vec2(tx, ty)) - bias;
            sum += w * (receiver <= occluder ? 1.0 : 0.0);
            weightSum += w;
        }
    }
    bool inside = all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0))) && z <= 1.0;
    result.visibility = inside ? sum / max(weightSum, 1e-6) : 1.0;
    float nearest = texelFetch(shadowMap, clamp(ivec2(uv * mapSize), ivec2(0), maxTexel), 0).r;
    result.thicknessM = inside ? max(z - nearest, 0.0) * params.z : 0.0;
    result.kernelWidthM = sigma * params.x;
    return result;
}

#endif
