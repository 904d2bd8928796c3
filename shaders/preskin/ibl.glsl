// preskin/ibl.glsl: image-based specular lighting by the split sum (Karis, "Real Shading in Unreal
// Engine 4", SIGGRAPH 2013 course notes): radiance prefiltered with the GGX lobe (N = V = R) into
// the mip levels of a cube map, times the environment BRDF's scale and bias of F0 from a DFG table.
// What the host binds (the renderer makes all three when the environment changes,
// render/GpuEnvironment.cpp, and a host may make its own):
//  - samplerCube prefiltered: linear, mipmapped; level l holds perceptual roughness
//    l / maxLevel, level 0 the radiance itself. Its directions are the environment image's: the
//    world direction turned back by the environment's rotation about +Y (preskinIblDirection);
//  - sampler2D dfg: two tables of size x size side by side (2 size x size texels): on the left RG
//    = (A, B) with F0 * A + B the directional albedo of GGX with height-correlated Smith visibility
//    and Schlick Fresnel (preskin/brdf.glsl), on the right RGBA = M^-1 (m00, m02, m20, m11) of the
//    lobe's linearly transformed cosine (engine/src/env/Ltc.h; for lights with a size); texel
//    (i, j) of each holds NoV = i / (size - 1), roughness = j / (size - 1) (both ends included);
//    linear filtering, clamped edges;
//  - the environment's rotation as (cos, sin) and maxLevel.
#ifndef PRESKIN_IBL_GLSL
#define PRESKIN_IBL_GLSL

#include "preskin/common.glsl"
#include "preskin/light_sample.glsl"

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

// Texture coordinates of (NoV, roughness) in the left (A, B) table; add 0.5 in u for the right one.
vec2 preskinDfgUv(sampler2D dfg, float NoV, float roughness) {
    float size = float(textureSize(dfg, 0).y);
    return vec2(0.5, 1.0) * (clamp(vec2(NoV, roughness), 0.0, 1.0) * (size - 1.0) + 0.5) / size;
}

// (A, B): the directional albedo is F0 * A + B.
vec2 preskinDfg(sampler2D dfg, float NoV, float roughness) {
    return textureLod(dfg, preskinDfgUv(dfg, NoV, roughness), 0.0).rg;
}

// World directions -> the space where the GGX lobe of (N, V, roughness) is a clamped cosine.
mat3 preskinLtcMatrix(sampler2D dfg, vec3 N, vec3 V, float NoV, float roughness) {
    vec4 m = textureLod(dfg, preskinDfgUv(dfg, NoV, roughness) + vec2(0.5, 0.0), 0.0);
    vec3 t1 = V - N * dot(N, V);
    float l = length(t1);
    t1 = l > 1e-5 ? t1 / l : (abs(N.z) < 0.9 ? normalize(cross(N, vec3(0.0, 0.0, 1.0))) : normalize(cross(N, vec3(1.0, 0.0, 0.0))));
    vec3 t2 = cross(N, t1);
    mat3 minv = mat3(vec3(m.x, 0.0, m.z), vec3(0.0, m.w, 0.0), vec3(m.y, 0.0, 1.0));  // columns
    return minv * transpose(mat3(t1, t2, N));
}

// One fragment's PreskinLtc (preskin/light_sample.glsl) for one or two GGX lobes of perceptual
// roughness r (r.y = r.x for one lobe).
PreskinLtc preskinLtc(sampler2D dfg, vec3 N, vec3 V, vec2 r) {
    float NoV = max(dot(N, V), 1e-4);
    PreskinLtc ltc;
    ltc.lobe0 = preskinLtcMatrix(dfg, N, V, NoV, r.x);
    ltc.lobe1 = r.y == r.x ? ltc.lobe0 : preskinLtcMatrix(dfg, N, V, NoV, r.y);
    ltc.dfg = vec4(preskinDfg(dfg, NoV, r.x), preskinDfg(dfg, NoV, r.y));
    return ltc;
}

// Specular reflection of the environment by one GGX lobe; multiply by specular occlusion.
vec3 preskinSpecularIbl(samplerCube prefiltered, sampler2D dfg, PreskinIbl ibl, vec3 F0, vec3 R, float NoV,
                        float roughness) {
    vec2 ab = preskinDfg(dfg, NoV, roughness);
    return preskinPrefilteredRadiance(prefiltered, ibl, R, roughness) * (F0 * ab.x + ab.y);
}

#endif
