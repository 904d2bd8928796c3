#version 460
// texture_blur.frag: one direction of one Gaussian of the texture-space baseline (d'Eon, Luebke,
// Enderton, "Efficient Rendering of Human Skin", EGSR 2007): a sum-of-Gaussians profile blurs
// the irradiance texture by each Gaussian in turn, each from the previous one (variances add), and
// sums the levels with the Gaussians' weights. 9 taps 2/3 sigma apart (sampled Gaussian weights,
// normalised), sigma in texels from the surface's stretch at the centre texel (metres per texel
// along the axis, measured in the irradiance pass): the blur is in world units across the
// mesh's UV layout. Texels off the mesh (coverage 0) weigh nothing; each channel renormalises
// over the covered taps, so UV seams and island borders do not darken.
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"

layout(constant_id = kSpecBlurAccumulate) const uint kAccumulate = 0;

layout(set = 0, binding = kBindingBlurInput) uniform sampler2DArray levelIn;
layout(set = 0, binding = kBindingBlurStretch) uniform sampler2DArray stretchIn;
layout(push_constant) uniform Push { BlurPush push; };

layout(location = 0) flat in uint inEye;  // unused: one layer per pass
layout(location = 0) out vec4 outLevel;
layout(location = 1) out vec4 outSum;  // the vertical pass: added (blend ONE, ONE) to the sum

void main() {
    int layer = int(push.direction.w);
    ivec2 texel = ivec2(gl_FragCoord.xy);
    vec4 centre = texelFetch(levelIn, ivec3(texel, layer), 0);
    vec2 stretch = texelFetch(stretchIn, ivec3(texel, layer), 0).rg;
    float metresPerTexel = push.direction.x > 0.5 ? stretch.x : stretch.y;
    vec4 level = centre;
    if (centre.a > 0.0 && metresPerTexel > 0.0) {
        vec2 size = vec2(textureSize(levelIn, 0).xy);
        vec2 step = push.direction.xy * (push.direction.z / metresPerTexel) * (2.0 / 3.0) / size;
        vec2 uv = gl_FragCoord.xy / size;
        vec3 sum = vec3(0.0);
        float coverage = 0.0;
        for (int k = -4; k <= 4; ++k) {
            float w = exp(-0.5 * (4.0 / 9.0) * float(k * k));
            vec4 s = texture(levelIn, vec3(uv + float(k) * step, float(layer)));
            sum += w * s.rgb;
            coverage += w * s.a;
        }
        level = vec4(centre.a * sum / max(coverage, 1e-6), centre.a);
    }
    outLevel = level;
    // The sum's alpha: the coverage, added once (weight.a is 1 for the first Gaussian only).
    outSum = kAccumulate != 0u ? push.weight * vec4(level.rgb, level.a) : vec4(0.0);
}
