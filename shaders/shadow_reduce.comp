#version 460
// shadow_reduce.comp: skin's wide shadow map, one texel per block of `factor` x `factor` texels of
// the shadow map holding the block's nearest depth (a min reduction, by gathers; the renderer
// picks the factor per frame so that the Gaussian filter's footprint on the wide map covers the
// distance skin's widest profile scatters, preskin/skin.glsl). A texel is occluded for a receiver
// wherever any part of its block is, so the wide map never misses an occluder the shadow map
// holds, and its edges lie on average half a wide texel on the lit side of the shadow map's
// (preskinSkinShadow moves its estimate back). (A median of each block would place them exactly
// but costs lavapipe about 50 times more: arrays indexed in loops spill. Counting a block whose
// depth range holds the receiver as half lit, from its nearest and farthest depths, was no
// closer to the reference at a straight edge and doubles the wide filter's gathers.)
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D shadowMap;
layout(set = 0, binding = 1, r32f) uniform writeonly image2D wideMap;
layout(push_constant) uniform Push { uint factor; } push;

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, imageSize(wideMap)))) return;
    vec2 size = vec2(textureSize(shadowMap, 0));
    float nearest = 1.0;
    // Gathers of 2x2 texels at each even offset of the block (an odd block's last gather reaches one
    // texel into the next block; texels past the map's edge clamp).
    for (uint j = 0; j < push.factor; j += 2)
        for (uint i = 0; i < push.factor; i += 2) {
            vec2 corner = vec2(texel * int(push.factor) + ivec2(i, j)) + 1.0;  // between the 2x2 texels
            vec4 d = textureGather(shadowMap, corner / size, 0);
            nearest = min(nearest, min(min(d.x, d.y), min(d.z, d.w)));
        }
    imageStore(wideMap, texel, vec4(nearest));
}
