// forward_material.glsl: the forward pass's material uniforms (descriptor set 1), read by both of
// its stages and by the shadow pass of alpha-masked materials, the texture transform, and a skin
// material's profile mix: the LutMapping of each entry (the material's own from the pipeline's
// specialization, the blended ones from the uniforms) and the entries' weights. Both stages blend
// the same way, so a blend of weight 0 or 1 is exactly the profile it weighs.
#ifndef PRESKIN_FORWARD_MATERIAL_GLSL
#define PRESKIN_FORWARD_MATERIAL_GLSL

#include "forward_specialization.glsl"
// A material without a profile blend compiles without the blend's lookups (preskin/lut.glsl).
#define PRESKIN_PROFILE_MIX_MAX kProfileMix
#define PRESKIN_AREA_LIGHT_TYPES kAreaLightShapes
#include "preskin/lut.glsl"

layout(set = 1, binding = kBindingMaterial) uniform Material { MaterialUniforms material; };

// KHR_texture_transform: a texture's UV through its 3x2 matrix.
vec2 transformUv(GpuUvTransform t, vec2 uv) {
    vec3 p = vec3(uv, 1.0);
    return vec2(dot(t.row0.xyz, p), dot(t.row1.xyz, p));
}

// Entry i of the material's profile mix; the blended entries member by member (glslang stores a
// uniform-block struct into a local one of another layout with a mismatched type, which SPIR-V
// validation refuses).
LutMapping materialLutMapping(int i) {
    if (i == 0) return specializedLutMapping();
    LutMapping m;
    m.diffuseNoL = material.skinLuts[i].diffuseNoL;
    m.diffuseCurvature = material.skinLuts[i].diffuseCurvature;
    m.penumbraShadow = material.skinLuts[i].penumbraShadow;
    m.penumbraWidth = material.skinLuts[i].penumbraWidth;
    m.shCurvature = material.skinLuts[i].shCurvature;
    m.shBandV = material.skinLuts[i].shBandV;
    m.shLambert = material.skinLuts[i].shLambert;
    m.transmittance = material.skinLuts[i].transmittance;
    return m;
}

// The profiles the material blends by its weight texture (0..3; none in a pipeline without blends).
int materialBlendedProfiles() { return kProfileMix > 1u ? clamp(int(material.skinProfileBlend.x), 0, 3) : 0; }

// The material's profile mix where its profile-weight texture reads weightTexel (ignored without a
// blend): r, g, b weigh the blended profiles, the material's own profile gets the rest; weights
// summing above 1 are scaled to sum to 1.
PreskinProfileMix materialProfileMix(vec3 weightTexel) {
    PreskinProfileMix p;
    p.layer = material.skinProfileLayers;
    p.weight = vec4(1.0, 0.0, 0.0, 0.0);
    int blended = materialBlendedProfiles();
    if (blended > 0) {
        vec3 w = max(weightTexel, vec3(0.0)) * vec3(greaterThan(vec3(blended), vec3(0.0, 1.0, 2.0)));
        float sum = w.r + w.g + w.b;
        if (sum > 1.0) w /= sum;
        p.weight = vec4(max(1.0 - (w.r + w.g + w.b), 0.0), w);
    }
    p.count = 1 + blended;
    p.mapping[0] = materialLutMapping(0);
    for (int i = 1; i < 4; ++i) p.mapping[i] = materialLutMapping(i);  // read only by blending pipelines
    return p;
}

// The normal maps' per-channel LOD bias of a mix: its profiles' biases, weighted.
vec3 materialNormalLodBias(PreskinProfileMix p) {
    vec3 bias = p.weight.x * material.skinNormalLodBias[0].rgb;
    if (kProfileMix > 1u)
        bias += p.weight.y * material.skinNormalLodBias[1].rgb + p.weight.z * material.skinNormalLodBias[2].rgb +
                p.weight.w * material.skinNormalLodBias[3].rgb;
    return bias;
}

#endif
