// preskin/tonemap.glsl: display mapping for 8-bit output. Khronos PBR Neutral tone mapper
// (Khronos 3D Commerce, 2024): identity below 0.76 after a small toe, then a soft shoulder
// with mild desaturation, so base colours (skin albedo) reproduce faithfully.
#ifndef PRESKIN_TONEMAP_GLSL
#define PRESKIN_TONEMAP_GLSL

vec3 preskinTonemapNeutral(vec3 color) {
    const float startCompression = 0.8 - 0.04;
    const float desaturation = 0.15;
    float x = min(color.r, min(color.g, color.b));
    float offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
    color -= offset;
    float peak = max(color.r, max(color.g, color.b));
    if (peak < startCompression) return color;
    const float d = 1.0 - startCompression;
    float newPeak = 1.0 - d * d / (peak + d - startCompression);
    color *= newPeak / peak;
    float g = 1.0 - 1.0 / (desaturation * (peak - newPeak) + 1.0);
    return mix(color, vec3(newPeak), g);
}

#endif
