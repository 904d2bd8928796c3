#version 460
// lut_lookup.comp: evaluates the lookups of preskin/lut.glsl (diffuse, penumbra, SH transfer,
// transmittance) at a list of inputs, one invocation per input, so tests/reference/test_lut_gpu.cpp
// can compare the GPU's sampling of the uploaded LUTs with LutSet's CPU lookups.
// Input i: x = table (0 diffuse, 1 penumbra, 2 SH transfer, 3 transmittance), y and z = the
// lookup's arguments in order (SH transfer: z = band 0..2). Output i: the RGB result. The tables
// are array textures, read at layer push.layer through a one-profile PreskinProfileMix, as the
// renderer reads them.
#extension GL_GOOGLE_include_directive : require
#include "preskin/lut.glsl"

layout(local_size_x = 64) in;

layout(set = 0, binding = 0) uniform Mapping { LutMapping lut; };
layout(set = 0, binding = 1) uniform sampler2DArray diffuseLut;
layout(set = 0, binding = 2) uniform sampler2DArray penumbraLut;
layout(set = 0, binding = 3) uniform sampler2DArray shTransferLut;
layout(set = 0, binding = 4) uniform sampler2DArray transmittanceLut;
layout(std430, set = 0, binding = 5) readonly buffer Inputs { vec4 inputs[]; };
layout(std430, set = 0, binding = 6) writeonly buffer Outputs { vec4 outputs[]; };

layout(push_constant) uniform Push {
    uint count;
    uint layer;
} push;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= push.count) return;
    vec4 arg = inputs[i];
    uint table = uint(arg.x);
    vec3 result = vec3(0.0);
    PreskinProfileMix profile = preskinSingleProfile(lut, float(push.layer));
    if (table == 0u) {
        result = preskinDiffuseLut(profile, diffuseLut, vec3(arg.y), arg.z);
    } else if (table == 1u) {
        result = preskinPenumbraLut(profile, penumbraLut, arg.y, arg.z);
    } else if (table == 2u) {
        vec3 a0, a1, a2;
        preskinShTransferLut(profile, shTransferLut, arg.y, a0, a1, a2);
        uint band = uint(arg.z);
        result = band == 0u ? a0 : (band == 1u ? a1 : a2);
    } else {
        result = preskinTransmittanceLut(profile, transmittanceLut, arg.y);
    }
    outputs[i] = vec4(result, 0.0);
}
