// forward_material.glsl: the forward pass's material uniforms (descriptor set 1), read by both of
// its stages and by the shadow pass of alpha-masked materials, the texture transform, and the LutMapping of each entry of a skin material's profile mix: the material's
// own from the pipeline's specialization, the blended ones from the uniforms.
#ifndef PRESKIN_FORWARD_MATERIAL_GLSL
#define PRESKIN_FORWARD_MATERIAL_GLSL

#include "forward_specialization.glsl"

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

#endif
