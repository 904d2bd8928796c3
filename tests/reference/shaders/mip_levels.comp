#version 460
// mip_levels.comp: preskinSampleLevels (preskin/mip_levels.glsl) against the sampler's own
// trilinear filtering (textureLod at each of the four levels of detail), one invocation per
// input, for tests/reference/test_mip_levels.cpp.
// Input i: (u, v, lod.x, lod.y) then (lod.z, lod.w, 0, 0). Output 8i + c: preskinSampleLevels'
// texel at lod[c]; output 8i + 4 + c: textureLod's.
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
    vec4 lod = vec4(inputs[2 * i].zw, inputs[2 * i + 1].xy);
    vec3 t[4];
    preskinSampleLevels(map, uv, lod, push.levelCount, t[0], t[1], t[2], t[3]);
    for (int c = 0; c < 4; ++c) {
        outputs[8 * i + c] = vec4(t[c], 0.0);
        outputs[8 * i + 4 + c] = vec4(textureLod(map, uv, lod[c]).rgb, 0.0);
    }
}
