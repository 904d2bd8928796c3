// Material parameters for the diffusion reference, read like forward.frag reads them (see
// ReferenceMaterials.h).
#include "ReferenceMaterials.h"

#include <algorithm>

namespace preskin::reference {

ReferenceMaterials::ReferenceMaterials(const Scene& scene) : materials_(scene.materials) {
    materials_.emplace_back();  // glTF's default material
    for (const Material& m : materials_) {
        Textures t;
        t.baseColor = texture(scene, m.baseColor, true);
        t.metallicRoughness = texture(scene, m.metallicRoughness, false);
        t.occlusion = texture(scene, m.occlusion, false);
        t.emissive = texture(scene, m.emissive, true);
        textures_.push_back(t);
    }
}

const ReferenceTexture* ReferenceMaterials::texture(const Scene& scene, const TextureRef& ref, bool srgb) {
    if (!ref.valid() || size_t(ref.image) >= scene.images.size()) return nullptr;
    const int sampler = ref.sampler >= 0 && size_t(ref.sampler) < scene.samplers.size() ? ref.sampler : -1;
    auto& slot = cache_[{ref.image, sampler, srgb}];
    if (!slot)
        slot = std::make_unique<ReferenceTexture>(scene.images[size_t(ref.image)],
                                                  sampler >= 0 ? scene.samplers[size_t(sampler)] : Sampler{}, srgb);
    return slot.get();
}

glm::dvec4 ReferenceMaterials::sample(const TextureRef& ref, const ReferenceTexture* texture,
                                      const UvFootprint& at) const {
    const glm::dmat3 m(ref.uvTransform());
    const glm::dvec2 uv = glm::dvec2(m * glm::dvec3(at.uv, 1.0));
    const glm::dmat2 linear(m);
    return texture->sample(uv, linear * at.duvDx, linear * at.duvDy);
}

glm::dvec4 ReferenceMaterials::baseColor(uint32_t index, const UvFootprint& at) const {
    const Material& m = materials_[index];
    glm::dvec4 c(m.baseColorFactor);
    if (const ReferenceTexture* t = textures_[index].baseColor) c *= sample(m.baseColor, t, at);
    return c;
}

double ReferenceMaterials::metallic(uint32_t index, const UvFootprint& at) const {
    const Material& m = materials_[index];
    double b = 1.0;
    if (const ReferenceTexture* t = textures_[index].metallicRoughness) b = sample(m.metallicRoughness, t, at).b;
    return std::clamp(double(m.metallicFactor) * b, 0.0, 1.0);
}

double ReferenceMaterials::occlusion(uint32_t index, const UvFootprint& at) const {
    const Material& m = materials_[index];
    const ReferenceTexture* t = textures_[index].occlusion;
    if (!t) return 1.0;
    return 1.0 + double(m.occlusion.scale) * (sample(m.occlusion, t, at).r - 1.0);
}

glm::dvec3 ReferenceMaterials::emissive(uint32_t index, const UvFootprint& at) const {
    const Material& m = materials_[index];
    glm::dvec3 e(m.emissiveFactor);
    if (const ReferenceTexture* t = textures_[index].emissive) e *= glm::dvec3(sample(m.emissive, t, at));
    return e;
}

bool ReferenceMaterials::covers(uint32_t index, const glm::dvec2& uv) const {
    const Material& m = materials_[index];
    if (m.alphaMode != AlphaMode::Mask) return true;
    return baseColor(index, UvFootprint{uv, glm::dvec2(0.0), glm::dvec2(0.0)}).a >= double(m.alphaCutoff);
}

}  // namespace preskin::reference
