// preskin/lights.glsl: punctual lights as in KHR_lights_punctual: inverse-square falloff with
// the extension's recommended smooth range window, and its spot cone attenuation. Stands alone:
// it needs only the GpuLight struct of shared/light.h, not the renderer's bindings.
// Limits: no area lights; the range window follows the extension's recommendation, not physics.
#ifndef PRESKIN_LIGHTS_GLSL
#define PRESKIN_LIGHTS_GLSL

#include "shared/light.h"

// Direction to the light (L) and irradiance normal to it at positionWs.
void preskinLightIncidence(GpuLight light, vec3 positionWs, out vec3 L, out vec3 irradiance) {
    uint type = uint(light.directionType.w);
    if (type == kLightDirectional) {
        L = -light.directionType.xyz;
        irradiance = light.colorIntensity.rgb;
        return;
    }
    vec3 toLight = light.positionRange.xyz - positionWs;
    float d2 = max(dot(toLight, toLight), 1e-8);
    L = toLight * inversesqrt(d2);
    float attenuation = 1.0 / d2;
    float range = light.positionRange.w;
    if (range > 0.0) {
        float r = d2 / (range * range);  // (d / range)^2
        float window = clamp(1.0 - r * r, 0.0, 1.0);
        attenuation *= window * window;
    }
    if (type == kLightSpot) {
        float cd = dot(light.directionType.xyz, -L);
        float a = clamp(cd * light.spotScaleOffset.x + light.spotScaleOffset.y, 0.0, 1.0);
        attenuation *= a * a;
    }
    irradiance = light.colorIntensity.rgb * attenuation;
}

#endif
