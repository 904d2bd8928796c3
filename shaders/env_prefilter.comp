#version 460
// env_prefilter.comp: one mip level of the prefiltered specular cube (preskin/ibl.glsl) from the
// environment's equirectangular image (with its mip chain). Level 0 is the radiance itself, read
// at the mip whose texels match the cube texel's solid angle; level l > 0 holds the GGX lobe of
// roughness l / maxLevel with N = V = R, by importance sampling with filtered samples (Krivanek &
// Colbert, "Real-time Shading with Filtered Importance Sampling", EGSR 2008: each sample reads
// the source mip whose texels cover the sample's share of the lobe's solid angle). One
// invocation per texel of every face (z: the face, Vulkan's cube face order and orientation).
#extension GL_GOOGLE_include_directive : require
#include "preskin/ibl.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D source;
layout(set = 0, binding = 1, rgba16f) uniform writeonly image2DArray level;
layout(push_constant) uniform Push {
    vec4 params;  // x roughness, y samples, z source width, w source mip levels
} push;

// Direction through (s, t) in [-1, 1] of a face (Vulkan specification, "Cube Map Face Selection").
vec3 cubeDirection(uint face, float s, float t) {
    if (face == 0u) return vec3(1.0, -t, -s);
    if (face == 1u) return vec3(-1.0, -t, s);
    if (face == 2u) return vec3(s, 1.0, t);
    if (face == 3u) return vec3(s, -1.0, -t);
    if (face == 4u) return vec3(s, -t, 1.0);
    return vec3(-s, -t, -1.0);
}

// The source mip whose texel at direction d covers solid angle `omega`.
float sourceLod(vec3 d, float omega) {
    float width = push.params.z;
    float sinTheta = max(sqrt(max(1.0 - d.y * d.y, 0.0)), 1.0 / width);
    float texelOmega = (2.0 * PRESKIN_PI / width) * (2.0 * PRESKIN_PI / width) * sinTheta;
    return clamp(0.5 * log2(omega / texelOmega), 0.0, push.params.w - 1.0);
}

vec3 sourceRadiance(vec3 d, float omega) {
    return textureLod(source, preskinEquirectUv(d), sourceLod(d, omega)).rgb;
}

float radicalInverse(uint bits) {
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    return float(bits) * 2.3283064365386963e-10;
}

void main() {
    ivec3 size = imageSize(level);
    ivec3 texel = ivec3(gl_GlobalInvocationID);
    if (texel.x >= size.x || texel.y >= size.y) return;
    float s = (float(texel.x) + 0.5) / float(size.x) * 2.0 - 1.0;
    float t = (float(texel.y) + 0.5) / float(size.y) * 2.0 - 1.0;
    vec3 N = normalize(cubeDirection(uint(texel.z), s, t));
    // The cube texel's solid angle: (2 / size)^2 / (1 + s^2 + t^2)^(3/2).
    float cubeOmega = 4.0 / float(size.x * size.x) / pow(1.0 + s * s + t * t, 1.5);
    float roughness = push.params.x;
    vec3 result;
    if (roughness <= 0.0) {
        result = sourceRadiance(N, cubeOmega);
    } else {
        float alpha = max(roughness * roughness, 1e-3);
        float a2 = alpha * alpha;
        vec3 up = abs(N.y) < 0.999 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
        vec3 tx = normalize(cross(up, N));
        vec3 ty = cross(N, tx);
        uint samples = uint(push.params.y);
        vec3 sum = vec3(0.0);
        float weight = 0.0;
        for (uint i = 0u; i < samples; ++i) {
            float u = (float(i) + 0.5) / float(samples);
            float phi = 2.0 * PRESKIN_PI * radicalInverse(i);
            float cosH = sqrt((1.0 - u) / (1.0 + (a2 - 1.0) * u));
            float sinH = sqrt(max(1.0 - cosH * cosH, 0.0));
            vec3 H = tx * (sinH * cos(phi)) + ty * (sinH * sin(phi)) + N * cosH;
            vec3 L = 2.0 * dot(N, H) * H - N;
            float NoL = dot(N, L);
            if (NoL <= 0.0) continue;
            // pdf of L with N = V: D / 4; the sample's share of the lobe: 1 / (samples pdf).
            float d = cosH * cosH * (a2 - 1.0) + 1.0;
            float D = a2 / (PRESKIN_PI * d * d);
            float omega = 4.0 / (float(samples) * D);
            sum += sourceRadiance(L, omega) * NoL;
            weight += NoL;
        }
        result = sum / max(weight, 1e-6);
    }
    imageStore(level, texel, vec4(min(result, vec3(65504.0)), 1.0));
}
