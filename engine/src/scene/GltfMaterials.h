// glTF samplers, textures and materials to preskin types: the metallic-roughness core material,
// KHR_texture_transform, KHR_materials_emissive_strength, KHR_materials_diffuse_transmission,
// KHR_materials_volume (thicknessFactor, attenuation), the scatter drafts KHR_materials_scatter and
// KHR_materials_volume_scatter (<preskin/KhronosScatter.h>) and the project's PRESKIN_materials_skin
// (docs/gltf-extensions.md).
// Only TEXCOORD_0 is loaded: a texture that asks for another set (texCoord, or the transform's
// texCoord override) is sampled with set 0 and a warning. Textures whose source is not PNG or
// JPEG are an error when a material uses them. Factors outside their documented range are an
// error for PRESKIN_materials_skin and clamped with a warning for core glTF fields.
#pragma once

#include "scene/GltfContext.h"

namespace preskin::gltf {

void convertSamplers(const LoadContext& ctx);
void convertMaterials(const LoadContext& ctx);

// The skin parameters of a material: `defaults`, then its KHR transmission / volume values.
SkinMaterial seededSkin(const Material& material, const SkinMaterial& defaults);

// A skin material's profile from its Khronos scatter parameters (Material::khronosScatter), added
// to Scene::profiles (shared by materials with the same parameters), when it names no profile;
// a warning when it names one or the parameters define none.
void applyKhronosScatter(Scene& scene, size_t materialIndex);

}  // namespace preskin::gltf
