// The texture-space baseline (RenderSettings::diffusion TextureSpace, docs/baselines.md; d'Eon,
// Luebke, Enderton, "Efficient Rendering of Human Skin", EGSR 2007): each skin draw's diffuse
// light for a white albedo is rendered into its layer of an irradiance texture in the mesh's UV
// layout (the renderer's irradiance pass, texture_irradiance.vert/.frag, which also writes the
// surface's stretch), blurred by each Gaussian of its material's profile in turn, separably and
// stretch-corrected (shaders/texture_blur.frag), the levels summed with the Gaussians' weights;
// the forward pass (forward_texture.frag) reads the sum at the fragment's TEXCOORD_0 times the
// albedo (post-scatter texturing). Profiles that are not sums of Gaussians are fitted by one
// (skin/GaussianFit.h). Its cost is what the comparison counts: per skin draw 1 + 2 x Gaussians
// passes, 5 texture layers. Limits: skin meshes need TEXCOORD_0 laid out without overlaps in
// [0, 1]; the irradiance is lit as eye 0 sees it (its Fresnel); light across a UV seam does not
// reach the other side.
#pragma once

#include <preskin/Scene.h>

#include "render/GpuScene.h"
#include "vk/Pipeline.h"
#include "vk/Resources.h"

#include <array>
#include <functional>
#include <span>
#include <vector>

namespace preskin {

class TextureDiffusion {
public:
    TextureDiffusion(const vk::Device& device, std::function<std::span<const uint32_t>(const char*)> shader,
                     uint32_t slots);
    ~TextureDiffusion();
    TextureDiffusion(const TextureDiffusion&) = delete;
    TextureDiffusion& operator=(const TextureDiffusion&) = delete;

    static constexpr VkFormat kIrradianceFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
    static constexpr VkFormat kStretchFormat = VK_FORMAT_R16G16_SFLOAT;

    // Each skin material's Gaussians (variance in world m^2, ascending; weight per channel,
    // summing to 1): its own profile (LUT layer profile + 1) at its scatter scale.
    struct Gaussian {
        double varianceM2;
        glm::vec3 weight;
    };
    void setKernels(const std::vector<Material>& materials, const std::vector<ProfileLayer>& layers);
    const std::vector<Gaussian>& gaussians(uint32_t material) const { return gaussians_[material]; }

    // size x size texels, `layers` skin draws (at least 1). Replacing them waits for the device.
    void ensureTargets(uint32_t size, uint32_t layers);
    uint32_t size() const { return size_; }
    // The irradiance pass's attachments for one layer: irradiance, stretch.
    std::array<VkImageView, 2> irradianceViews(uint32_t layer) const;
    // The summed levels, every layer (the forward pass's kBindingDiffusionTexture).
    VkImageView sumView() const { return sum_.view(); }
    VkSampler sampler() const { return linear_; }

    // Before the irradiance pass: the irradiance and stretch layers to attachments (cleared by it).
    void beginIrradiance(VkCommandBuffer cmd);
    // After it: each listed layer's blur by its material's Gaussians, into the sum, left for the
    // forward pass to sample.
    void recordBlur(VkCommandBuffer cmd, uint32_t slot,
                    const std::vector<std::pair<uint32_t, uint32_t>>& layerMaterials);

    uint32_t passesPerFrame(const std::vector<std::pair<uint32_t, uint32_t>>& layerMaterials) const;
    static constexpr uint32_t kTargets = 5;                // irradiance, stretch, ping-pong level, intermediate, sum
    static constexpr uint64_t kBytesPerTexel = 4 * 8 + 4;  // four RGBA16F, the RG16F stretch
    uint64_t targetBytes() const;

    void rebuildPipelines();

private:
    VkPipeline createPipeline(bool vertical) const;
    void destroyViews();

    const vk::Device& device_;
    std::function<std::span<const uint32_t>(const char*)> shader_;
    VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    std::vector<std::array<VkDescriptorSet, 3>> sets_;  // per slot: input irradiance, level, intermediate
    VkSampler linear_ = VK_NULL_HANDLE;
    VkSampler nearest_ = VK_NULL_HANDLE;
    std::array<VkPipeline, 2> pipelines_{};  // horizontal, vertical
    std::vector<std::vector<Gaussian>> gaussians_;
    uint32_t size_ = 0;
    uint32_t layers_ = 0;
    vk::Image irradiance_, stretch_, level_, intermediate_, sum_;
    // Per image above, per layer: a 2D view for rendering into it.
    std::array<std::vector<VkImageView>, 5> layerViews_;
};

}  // namespace preskin
