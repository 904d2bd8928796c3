// preskin/sh.glsl: L2 real spherical harmonics (Ramamoorthi & Hanrahan 2001). Coefficients are
// environment radiance L_lm (RGB); band scales turn them into convolved quantities, e.g.
// Lambert's (pi, 2pi/3, pi/4) gives irradiance, skin's per-channel A_l(curvature) gives the
// pre-integrated diffuse ambient. Limits: 9 coefficients hold only low-frequency light.
#ifndef PRESKIN_SH_GLSL
#define PRESKIN_SH_GLSL

#include "preskin/common.glsl"

const vec3 PRESKIN_SH_LAMBERT = vec3(kShLambert0, kShLambert1, kShLambert2);

void preskinShBasis(vec3 d, out float y[9]) {
    y[0] = kShY00;
    y[1] = kShY1 * d.y;
    y[2] = kShY1 * d.z;
    y[3] = kShY1 * d.x;
    y[4] = kShY2 * d.x * d.y;
    y[5] = kShY2 * d.y * d.z;
    y[6] = kShY20 * (3.0 * d.z * d.z - 1.0);
    y[7] = kShY2 * d.x * d.z;
    y[8] = kShY22 * (d.x * d.x - d.y * d.y);
}

// sum_lm bandScale_l * L_lm * Y_lm(d), one scalar band scale per band.
vec3 preskinShEvaluate(vec4 sh[9], vec3 d, vec3 bandScale) {
    float y[9];
    preskinShBasis(d, y);
    vec3 b0 = sh[0].rgb * y[0];
    vec3 b1 = sh[1].rgb * y[1] + sh[2].rgb * y[2] + sh[3].rgb * y[3];
    vec3 b2 = sh[4].rgb * y[4] + sh[5].rgb * y[5] + sh[6].rgb * y[6] + sh[7].rgb * y[7] + sh[8].rgb * y[8];
    return b0 * bandScale.x + b1 * bandScale.y + b2 * bandScale.z;
}

// Per-channel band scales: bandR/G/B hold (A_0, A_1, A_2) of the red, green and blue channel.
vec3 preskinShEvaluateRgb(vec4 sh[9], vec3 d, vec3 bandR, vec3 bandG, vec3 bandB) {
    float y[9];
    preskinShBasis(d, y);
    vec3 b0 = sh[0].rgb * y[0];
    vec3 b1 = sh[1].rgb * y[1] + sh[2].rgb * y[2] + sh[3].rgb * y[3];
    vec3 b2 = sh[4].rgb * y[4] + sh[5].rgb * y[5] + sh[6].rgb * y[6] + sh[7].rgb * y[7] + sh[8].rgb * y[8];
    return vec3(dot(vec3(b0.r, b1.r, b2.r), bandR), dot(vec3(b0.g, b1.g, b2.g), bandG),
                dot(vec3(b0.b, b1.b, b2.b), bandB));
}

// One colour channel (0 red, 1 green, 2 blue) of preskinShEvaluate.
float preskinShEvaluateChannel(vec4 sh[9], vec3 d, vec3 bandScale, int channel) {
    float y[9];
    preskinShBasis(d, y);
    float b0 = sh[0][channel] * y[0];
    float b1 = sh[1][channel] * y[1] + sh[2][channel] * y[2] + sh[3][channel] * y[3];
    float b2 = sh[4][channel] * y[4] + sh[5][channel] * y[5] + sh[6][channel] * y[6] + sh[7][channel] * y[7] +
               sh[8][channel] * y[8];
    return dot(vec3(b0, b1, b2), bandScale);
}

#endif
