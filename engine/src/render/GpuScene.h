// A Scene on the GPU: one vertex and one index buffer for all primitives (indices rebased to the
// shared vertex buffer), the instance table, textures (sRGB or linear per use, full mip chains),
// samplers, and one descriptor set per material (uniforms + textures; no descriptor indexing,
// which lavapipe lacks). Draws: one per run of consecutive primitives of an instance that share
// a material (blended primitives one each), since each draw call has a fixed cost.
#pragma once

#include <preskin/Scene.h>

#include "shared/gpu_types.h"
#include "vk/Resources.h"

#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace preskin {

struct DrawItem {
    uint32_t firstIndex = 0;
    uint32_t indexCount = 0;
    int32_t vertexOffset = 0;
    uint32_t instance = 0;
    uint32_t material = 0;     // index into GpuScene::materials
    glm::vec3 centerWs{0.0f};  // of the (first) primitive; sorts blended draws, which are never merged
};

struct GpuMaterial {
    VkDescriptorSet set = VK_NULL_HANDLE;
    bool skin = false;
    SkinQuality quality = SkinQuality::High;  // skin: the material's own tier
    AlphaMode alphaMode = AlphaMode::Opaque;
    bool doubleSided = false;
    float texelsPerMm = 0.0f;  // normal-map texels per world millimetre on the meshes using it
    uint32_t profileMix = 1;   // skin: its profile plus the profiles its weight texture blends in (1..4)
    uint32_t skinInputs = 0;   // skin: its inputs, gpu::kSkinInput* bits (kSpecSkinInputs) but the normal levels and
                               // double-sidedness
    uint32_t normalMipLevels = 1;  // mip levels of the normal map (the larger of it and the detail map)
    uint32_t normalLevels = 1;     // skin: whole levels the biased normal samples blend (normalLevelCount)
    gpu::LutMapping lutMapping{};  // skin: its own profile's, which its pipelines are specialised to
    // The kSpecSkinInputs value of a skin material: skinInputs, the normal levels, double-sidedness.
    uint32_t skinInputBits() const {
        return skinInputs | (normalLevels << gpu::kSkinInputNormalLevelsShift) |
            (doubleSided ? gpu::kSkinInputDoubleSided : 0u);
    }
};

// What a skin material takes from a LUT layer (one diffusion profile): the profile's scattering
// widths (normal-map LOD biases) and where its tables lie in the LUT array textures.
struct ProfileLayer {
    glm::vec3 widthMm{0.0f};
    gpu::LutMapping mapping{};
    std::shared_ptr<const DiffusionProfile> profile;  // its normal-basis weights depend on the material's scatter scale
};

// An instance's transforms as the vertex stage reads them.
gpu::GpuInstance toGpuInstance(const glm::mat4& worldFromObject);

class GpuScene {
public:
    GpuScene(const vk::Device& device, const Scene& scene);
    ~GpuScene();
    GpuScene(const GpuScene&) = delete;
    GpuScene& operator=(const GpuScene&) = delete;

    VkDescriptorSetLayout materialLayout() const { return materialLayout_; }
    // Fills every material's uniforms from the LUT layers (layer p + 1 holds SkinMaterial::profile p):
    // the skin LOD biases from the widths of the material's profile (and the normal levels the
    // biased samples blend, part of the pipeline), and the LutMapping of every profile the material
    // mixes.
    void updateMaterials(const std::vector<ProfileLayer>& layers);
    // The scene's materials as uploaded.
    const std::vector<Material>& sceneMaterials() const { return sceneMaterials_; }

    vk::Buffer vertices;
    vk::Buffer indices;
    std::vector<uint32_t> meshFirstVertex;  // where each mesh's vertices start in `vertices`
    // The skin's normal basis of every rest vertex (vertex binding 1, NormalBasis of
    // <preskin/NormalBasis.h>; zero on meshes without skin). The deformer moves it like the normals.
    vk::Buffer normalBasis;
    std::vector<gpu::GpuInstance> restInstances;  // per scene instance (the rest pose), for the renderer
    std::vector<DrawItem> draws;
    std::vector<GpuMaterial> materials;  // scene materials, then the default material
    // Skin materials that are drawn but have no TEXCOORD_0 layout (hasUvLayout), as
    // "materials[i] ('name')": texture-space diffusion cannot lay them out.
    std::vector<std::string> skinWithoutUvLayout;

private:
    // Scene image `image` on the GPU (sRGB or linear), with alphaFrom's red channel in its alpha
    // where alphaFrom >= 0 (a skin material's specular map packed into its base colour).
    const vk::Image& texture(const Scene& scene, int image, bool srgb, int alphaFrom = -1);
    VkSampler sampler(int index) const;
    size_t samplerSlot(int index) const;  // into samplers_: the scene's sampler `index`, or the default
    gpu::MaterialUniforms uniformsFor(const Material& material, const GpuMaterial& gpu,
                                      const std::vector<ProfileLayer>& layers) const;

    const vk::Device& device_;
    std::vector<Material> sceneMaterials_;
    std::map<std::tuple<int, bool, int>, vk::Image> textures_;  // by image, sRGB, alphaFrom
    vk::Image white_;
    vk::Image flatNormal_;
    std::vector<VkSampler> samplers_;       // scene samplers, then the default
    std::vector<bool> samplerAnisotropic_;  // per entry of samplers_
    VkDescriptorSetLayout materialLayout_ = VK_NULL_HANDLE;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    vk::Buffer materialUniforms_;
    VkDeviceSize uniformStride_ = 0;
};

}  // namespace preskin
