// ReferenceMaterials: the scene's materials as the reference reads them, with the renderer's
// conventions (forward.frag): base colour = factor times the sRGB texture, metallic = factor
// times the metallic-roughness texture's blue channel, occlusion = 1 + strength (texture red - 1),
// emissive = factor times the sRGB texture, alpha masking against the cutoff; every texture
// through its KHR_texture_transform and sampler. Index Scene::materials.size() is glTF's default
// material (white, metallic 1, roughness 1, like forward.frag's fallback).
// Limits: skin-specific textures (specular, detail normal, curvature) and normal maps are not
// read: the reference has no specular and shades the smooth surface.
#pragma once

#include "ReferenceTexture.h"

#include <preskin/Scene.h>

#include <glm/glm.hpp>

#include <map>
#include <memory>
#include <tuple>
#include <vector>

namespace preskin::reference {

// Where a texture is read: TEXCOORD_0 and its screen-space derivatives (per pixel; zero for the
// finest level).
struct UvFootprint {
    glm::dvec2 uv{0.0};
    glm::dvec2 duvDx{0.0};
    glm::dvec2 duvDy{0.0};
};

class ReferenceMaterials {
public:
    explicit ReferenceMaterials(const Scene& scene);

    const Material& material(uint32_t index) const { return materials_[index]; }
    bool isSkin(uint32_t index) const { return materials_[index].skin.has_value(); }

    glm::dvec4 baseColor(uint32_t index, const UvFootprint& at) const;
    double metallic(uint32_t index, const UvFootprint& at) const;
    double occlusion(uint32_t index, const UvFootprint& at) const;
    glm::dvec3 emissive(uint32_t index, const UvFootprint& at) const;
    // False where an alpha-masked material discards the fragment (finest level, as a hit test).
    bool covers(uint32_t index, const glm::dvec2& uv) const;

private:
    const ReferenceTexture* texture(const Scene& scene, const TextureRef& ref, bool srgb);
    glm::dvec4 sample(const TextureRef& ref, const ReferenceTexture* texture, const UvFootprint& at) const;

    struct Textures {
        const ReferenceTexture* baseColor = nullptr;
        const ReferenceTexture* metallicRoughness = nullptr;
        const ReferenceTexture* occlusion = nullptr;
        const ReferenceTexture* emissive = nullptr;
    };
    std::vector<Material> materials_;
    std::vector<Textures> textures_;
    std::map<std::tuple<int, int, bool>, std::unique_ptr<ReferenceTexture>> cache_;
};

}  // namespace preskin::reference
