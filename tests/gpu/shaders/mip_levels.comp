#version 460
// mip_levels.comp: preskinSampleLevels (preskin/mip_levels.glsl) against the sampler's own
// trilinear filtering (textureLod at each of the three levels of detail), one invocation per
// input, for tests/gpu/test_mip_levels.cpp.
// Input i: (u, v, lod.r, lod.g) then (lod.b, 0, 0, 0). Output 6i + c: preskinSampleLevels' texel
// at lod[c]; output 6i + 3 + c: textureLod's.
#extension GL_GOOGLE_include_directive : require
#include "preskin/mip_levels.glsl"

layout(local_size_x = 64) in;

layout(set = 0, binding = 0) uniform sampler2D map;
layout(std430, set = 0, binding = 1) readonly buffer Inputs { vec4 inputs[]; };
layout(std430, set = 0, binding = 2) writeonly buffer Outputs { vec4 outputs[]; };

layout(push_constant) uniform Push {
    uint count;
    int levelCount;
} push;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= push.count) return;
    vec2 uv = inputs[2 * i].xy;
    vec3 lod = vec3(inputs[2 * i].zw, inputs[2 * i + 1].x);
    vec3 r, g, b;
    preskinSampleLevels(map, uv, lod, push.levelCount, r, g, b);
    outputs[6 * i] = vec4(r, 0.0);
    outputs[6 * i + 1] = vec4(g, 0.0);
    outputs[6 * i + 2] = vec4(b, 0.0);
    for (int c = 0; c < 3; ++c) outputs[6 * i + 3 + c] = vec4(textureLod(map, uv, lod[c]).rgb, 0.0);
}
