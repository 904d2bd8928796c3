// preskin/mip_levels.glsl: one texture at several levels of detail at once, filtered between
// mip levels by hand (what a sampler's LINEAR mipmap mode does: each level of detail blends the
// two whole levels around it by its fraction) from bilinear samples at whole levels that the
// levels of detail share. Skin reads its normal map at three biased levels, one per colour
// channel (preskin/skin_surface.glsl): three trilinear samples read six bilinear footprints, this
// reads ceil(span) + 2 for levels of detail that span `span` levels (4 for the bundled head's
// biases), and a CPU driver (lavapipe) pays per footprint.
// Limits: the sampler's minification and magnification filters apply within each level; no
// anisotropic filtering (as with any explicit level of detail); filtering happens on the texel
// values (as the sampler's does), so sRGB textures blend their decoded values.
#ifndef PRESKIN_MIP_LEVELS_GLSL
#define PRESKIN_MIP_LEVELS_GLSL

// `map` at the levels of detail lod.r, lod.g and lod.b (each clamped to the map's levels): red,
// green and blue receive the filtered texel (rgb) at each. levelCount: the whole levels read, from
// floor(min(lod)) on; it must reach the level above max(lod), ceil(max(lod) - min(lod)) + 2 at
// most (preskin::normalLevelCount in <preskin/SkinParameters.h>). A constant or a specialization
// constant unrolls the loop.
void preskinSampleLevels(sampler2D map, vec2 uv, vec3 lod, int levelCount, out vec3 red, out vec3 green,
                         out vec3 blue) {
    vec3 l = clamp(lod, vec3(0.0), vec3(float(textureQueryLevels(map) - 1)));
    float first = floor(min(l.r, min(l.g, l.b)));
    red = vec3(0.0);
    green = vec3(0.0);
    blue = vec3(0.0);
    for (int i = 0; i < levelCount; ++i) {
        float level = first + float(i);
        vec3 texel = textureLod(map, uv, level).rgb;  // whole level: bilinear only
        vec3 w = max(vec3(1.0) - abs(l - level), vec3(0.0));
        red += w.r * texel;
        green += w.g * texel;
        blue += w.b * texel;
    }
}

#endif
