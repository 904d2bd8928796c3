// preskin/common.glsl: constants and small helpers shared by every preskin include.
#ifndef PRESKIN_COMMON_GLSL
#define PRESKIN_COMMON_GLSL

#include "shared/constants.h"

// Marks the shadow filter's loops for unrolling: a shader that enables
// GL_EXT_control_flow_attributes may define it as [[unroll]] before including (the renderer's
// shaders do). A CPU driver (lavapipe) kept the skin path's filter loop rolled once the
// occluders' sums were in it, and the rolled loop cost 6 % of the skin frame's instructions.
#ifndef PRESKIN_UNROLL
#define PRESKIN_UNROLL
#endif

const float PRESKIN_PI = kPi;

float preskinSaturate(float x) { return clamp(x, 0.0, 1.0); }
vec3 preskinSaturate(vec3 x) { return clamp(x, vec3(0.0), vec3(1.0)); }
float preskinLuminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

// The standard normal distribution Phi(x), from erf by Abramowitz & Stegun 7.1.26 (|error| < 1.5e-7).
float preskinNormalCdf(float x) {
    float z = abs(x) * 0.70710678;
    float t = 1.0 / (1.0 + 0.3275911 * z);
    float erfc = t * (0.254829592 + t * (-0.284496736 + t * (1.421413741 + t * (-1.453152027 + t * 1.061405429)))) *
                 exp(-z * z);
    return x >= 0.0 ? 1.0 - 0.5 * erfc : 0.5 * erfc;
}

// Its inverse Phi^-1(p) for p in (0, 1), by Acklam's rational approximations (relative error
// 1.2e-9 in double; float precision here).
float preskinNormalQuantile(float p) {
    const float plow = 0.02425;
    if (p < plow || p > 1.0 - plow) {
        float q = sqrt(-2.0 * log(p < plow ? p : 1.0 - p));
        float x = (((((-7.784894002430293e-03 * q - 3.223964580411365e-01) * q - 2.400758277161838e+00) * q -
                      2.549732539343734e+00) * q + 4.374664141464968e+00) * q + 2.938163982698783e+00) /
                  ((((7.784695709041462e-03 * q + 3.224671290700398e-01) * q + 2.445134137142996e+00) * q +
                    3.754408661907416e+00) * q + 1.0);
        return p < plow ? x : -x;
    }
    float q = p - 0.5;
    float r = q * q;
    return (((((-3.969683028665376e+01 * r + 2.209460984245205e+02) * r - 2.759285104469687e+02) * r +
              1.383577518672690e+02) * r - 3.066479806614716e+01) * r + 2.506628277459239e+00) * q /
           (((((-5.447609879822406e+01 * r + 1.615858368580409e+02) * r - 1.556989798598866e+02) * r +
              6.680131188771972e+01) * r - 1.328068155288572e+01) * r + 1.0);
}

#endif
