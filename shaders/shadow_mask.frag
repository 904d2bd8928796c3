#version 460
// shadow_mask.frag: alpha-masked materials (glTF alphaMode MASK) in the shadow map: where the base
// colour's alpha is below the material's cutoff the surface is absent, so it casts no shadow
// there, as the forward pass discards it there.
#extension GL_GOOGLE_include_directive : require
#include "forward_material.glsl"

layout(set = 1, binding = kBindingBaseColorTexture) uniform sampler2D baseColorTexture;

layout(location = 0) in vec2 inUv0;

void main() {
    float alpha = material.baseColorFactor.a;
    if (material.hasTextures.x > 0.5) alpha *= texture(baseColorTexture, transformUv(material.uv[0], inUv0)).a;
    if (alpha < material.emissiveAlphaCutoff.w) discard;
}
