#version 460
// screen_diffusion.frag: the screen-space separable baseline (RenderSettings::diffusion
// ScreenSpace; Jimenez et al., "Separable Subsurface Scattering", CGF 2015), one pass per
// direction: skin's diffuse light (forward_split.frag) blurred along rows into an intermediate
// target, then along columns and added to the rest of the frame, tone-mapped for 8-bit targets.
// Each skin material has its own kernel (skin/SeparableKernel.h: its profile's line profile at
// its scatter scale, offsets in world metres), placed in pixels by the pixel's view depth.
// Depth-aware ("follow surface"): a tap whose depth differs from the centre's by dz lies
// sqrt(r^2 + dz^2) away, not r; for a Gaussian profile of per-axis variance v that scales its
// weight by exp(-dz^2 / 2v), and each channel's tap is taken that much from the tap and the rest
// from the centre, with v the channel's own (its RMS radius^2 / 2): a nose over a cheek (dz of
// centimetres) keeps its light, a tilted plane keeps its values. Taps off the skin (coverage 0:
// background, other materials) are the centre too, so silhouettes are not pulled towards the
// interior. Light and coverage are premultiplied (MSAA edges), renormalised per channel.
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
#include "preskin/tonemap.glsl"

layout(constant_id = kSpecDiffusionPass) const uint kPass = kDiffusionHorizontal;
layout(constant_id = kSpecDiffusionTaps) const uint kTaps = 17;
layout(constant_id = kSpecDiffusionOutput) const uint kOutput = kOutputLinear;

layout(set = 0, binding = kBindingDiffusionInput) uniform sampler2DArray diffuseIn;  // read at texels
layout(set = 0, binding = kBindingDiffusionSurface) uniform sampler2DArray surfaceIn;
layout(set = 0, binding = kBindingDiffusionScene) uniform sampler2DArray sceneIn;
layout(std430, set = 0, binding = kBindingDiffusionKernels) readonly buffer Kernels { vec4 kernelTaps[]; };
layout(push_constant) uniform Push { DiffusionPush push; };

layout(location = 0) flat in uint inEye;
layout(location = 0) out vec4 outColor;

vec4 scattered(ivec2 pixel) {
    ivec3 at = ivec3(pixel, int(inEye));
    vec4 centre = texelFetch(diffuseIn, at, 0);
    vec2 surface = texelFetch(surfaceIn, at, 0).rg;
    if (centre.a <= 1e-4 || surface.y <= 0.0) return vec4(0.0);
    uint material = uint(round(surface.y / centre.a)) - 1u;
    if (material >= push.params.x) return vec4(0.0);
    float depth = surface.x;
    vec4 scale = push.eyeScale[inEye];
    vec2 direction = kPass == kDiffusionHorizontal ? vec2(1.0, 0.0) : vec2(0.0, 1.0);
    float pixelsPerM = (kPass == kDiffusionHorizontal ? scale.x : scale.y) / (scale.z > 0.5 ? max(depth, 1e-6) : 1.0);
    ivec2 last = textureSize(diffuseIn, 0).xy - 1;
    vec2 centreUv = gl_FragCoord.xy;
    vec3 sum = vec3(0.0);
    vec3 weightSum = vec3(0.0);
    uint first = material * (kTaps + 1u);
    vec3 halfInvVariance = kernelTaps[first].rgb;  // 1 / 2v per channel, 1/m^2
    for (uint i = 0u; i < kTaps; ++i) {
        vec4 tap = kernelTaps[first + 1u + i];
        // The nearest pixel, light and depth alike: a filtered tap would mix in a neighbour across a
        // depth edge that the depth test, made at one pixel, cannot see.
        ivec3 p = ivec3(clamp(ivec2(floor(centreUv + direction * (tap.w * pixelsPerM))), ivec2(0), last), int(inEye));
        vec4 s = texelFetch(diffuseIn, p, 0);
        float tapDepth = texelFetch(surfaceIn, p, 0).r;
        float dz = tapDepth - depth;
        vec3 follow = exp(-dz * dz * halfInvVariance) * min(s.a / centre.a, 1.0);
        vec3 light = mix(centre.rgb, s.rgb, follow);
        vec3 coverage = mix(vec3(centre.a), vec3(s.a), follow);
        sum += tap.rgb * light;
        weightSum += tap.rgb * coverage;
    }
    return vec4(centre.a * sum / max(weightSum, vec3(1e-8)), centre.a);
}

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 diffuse = scattered(pixel);
    if (kPass == kDiffusionHorizontal) {
        outColor = diffuse;
        return;
    }
    vec4 scene = texelFetch(sceneIn, ivec3(pixel, int(inEye)), 0);
    vec3 color = scene.rgb + diffuse.rgb;
    outColor = vec4(kOutput == kOutputTonemapped ? preskinTonemapNeutral(max(color, vec3(0.0))) : color, scene.a);
}
