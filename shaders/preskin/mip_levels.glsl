// preskin/mip_levels.glsl: one texture at several levels of detail at once, filtered between
// mip levels by hand (what a sampler's LINEAR mipmap mode does: each level of detail blends the
// two whole levels around it by its fraction) from bilinear samples at whole levels that the
// levels of detail share. Skin reads its normal map at three biased levels, one per colour
// channel, and unbiased for specular (preskin/skin_surface.glsl): four trilinear samples read
// eight bilinear footprints, this reads ceil(span) + 2 for levels of detail that span `span`
// levels (4 for the bundled head's biases), and a CPU driver (lavapipe) pays per footprint.
// Limits: the sampler's minification and magnification filters apply within each level, but the
// levels are always blended (LINEAR mipmap mode) whatever its mipmap mode; no anisotropic
// filtering (as with any explicit level of detail); filtering happens on the texel values (as the
// sampler's does), so sRGB textures blend their decoded values.
#ifndef PRESKIN_MIP_LEVELS_GLSL
#define PRESKIN_MIP_LEVELS_GLSL

// `map` at four levels of detail lod.x .. lod.w (each clamped to the map's levels): t0 .. t3
// receive the filtered texel (rgb) at each (a level of detail the caller does not need may repeat
// another). levelCount: the whole levels read, from floor(min(lod)) on; it must reach the level
// above max(lod), ceil(max(lod) - min(lod)) + 2 at most (preskin::normalLevelCount in
// <preskin/SkinParameters.h>). A constant or a specialization constant unrolls the loop.
void preskinSampleLevels(sampler2D map, vec2 uv, vec4 lod, int levelCount, out vec3 t0, out vec3 t1, out vec3 t2,
                         out vec3 t3) {
    vec4 l = clamp(lod, vec4(0.0), vec4(float(textureQueryLevels(map) - 1)));
    float first = floor(min(min(l.x, l.y), min(l.z, l.w)));
    t0 = vec3(0.0);
    t1 = vec3(0.0);
    t2 = vec3(0.0);
    t3 = vec3(0.0);
    for (int i = 0; i < levelCount; ++i) {
        float level = first + float(i);
        vec3 texel = textureLod(map, uv, level).rgb;  // whole level: bilinear only
        vec4 w = max(vec4(1.0) - abs(l - level), vec4(0.0));
        t0 += w.x * texel;
        t1 += w.y * texel;
        t2 += w.z * texel;
        t3 += w.w * texel;
    }
}

#endif
