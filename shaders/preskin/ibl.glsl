// preskin/ibl.glsl: image-based specular lighting by the split sum (Karis, "Real Shading in Unreal
// Engine 4", SIGGRAPH 2013 course notes): radiance prefiltered with the GGX lobe (N = V = R) into
// the mip levels of a cube map, times the environment BRDF's scale and bias of F0 from a DFG table.
// What the host binds (the renderer makes all three when the environment changes,
// render/GpuEnvironment.cpp, and a host may make its own):
//  - samplerCube prefiltered: linear, mipmapped; level l holds perceptual roughness
//    l / maxLevel, level 0 the radiance itself. Its directions are the environment image's: the
//    world direction turned back by the environment's rotation about +Y (preskinIblDirection);
//  - sampler2D dfg: RG = (A, B) with F0 * A + B the directional albedo of GGX with height-correlated
//    Smith visibility and Schlick Fresnel (preskin/brdf.glsl); texel (i, j) holds NoV = i / (size - 1),
//    roughness = j / (size - 1) (both ends included); linear filtering, clamped edges;
//  - the environment's rotation as (cos, sin) and maxLevel.
#ifndef PRESKIN_IBL_GLSL
#define PRESKIN_IBL_GLSL

#include "preskin/common.glsl"

struct PreskinIbl {
    vec2 rotation;   // cos and sin of the environment's turn about +Y (Environment::rotationY)
    float maxLevel;  // the prefiltered cube's last mip level (roughness 1)
};

// World direction -> the environment image's own direction (the turn undone).
vec3 preskinIblDirection(vec3 directionWs, vec2 rotation) {
    return vec3(rotation.x * directionWs.x - rotation.y * directionWs.z, directionWs.y,
                rotation.y * directionWs.x + rotation.x * directionWs.z);
}

// Equirectangular image coordinates of an image direction (<preskin/Environment.h>'s convention).
vec2 preskinEquirectUv(vec3 d) {
    float phi = atan(d.z, d.x);
    return vec2(phi / (2.0 * PRESKIN_PI) + 0.5, acos(clamp(d.y, -1.0, 1.0)) / PRESKIN_PI);
}

vec3 preskinPrefilteredRadiance(samplerCube prefiltered, PreskinIbl ibl, vec3 R, float roughness) {
    return textureLod(prefiltered, preskinIblDirection(R, ibl.rotation), preskinSaturate(roughness) * ibl.maxLevel).rgb;
}

// (A, B): the directional albedo is F0 * A + B.
vec2 preskinDfg(sampler2D dfg, float NoV, float roughness) {
    float size = float(textureSize(dfg, 0).x);
    vec2 uv = (clamp(vec2(NoV, roughness), 0.0, 1.0) * (size - 1.0) + 0.5) / size;
    return textureLod(dfg, uv, 0.0).rg;
}

// Specular reflection of the environment by one GGX lobe; multiply by specular occlusion.
vec3 preskinSpecularIbl(samplerCube prefiltered, sampler2D dfg, PreskinIbl ibl, vec3 F0, vec3 R, float NoV,
                        float roughness) {
    vec2 ab = preskinDfg(dfg, NoV, roughness);
    return preskinPrefilteredRadiance(prefiltered, ibl, R, roughness) * (F0 * ab.x + ab.y);
}

#endif
