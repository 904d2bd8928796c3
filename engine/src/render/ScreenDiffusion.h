// The screen-space separable baseline (RenderSettings::diffusion ScreenSpace, docs/baselines.md):
// what preskin's one forward pass replaces, built into the same renderer so both are measured
// alike. The forward pass (forward_split.frag) draws into this pass's own targets: the frame
// without skin's diffuse light (scene), skin's diffuse light (diffuse) and every surface's view
// depth with skin's material (surface), each resolved from MSAA before the blur; then two
// full-screen passes (shaders/screen_diffusion.frag) blur the diffuse light along rows into an
// intermediate target and along columns, adding it to the scene into the frame's target, in every
// eye (one blur per eye layer). Its cost is what the comparison counts: 2 passes, 4 targets.
#pragma once

#include <preskin/Renderer.h>
#include <preskin/Scene.h>

#include "render/GpuScene.h"
#include "vk/Pipeline.h"
#include "vk/Resources.h"

#include <array>
#include <functional>
#include <map>
#include <span>
#include <tuple>
#include <vector>

namespace preskin {

class ScreenDiffusion {
public:
    // `shader`: the renderer's SPIR-V by file name (its overrides included).
    ScreenDiffusion(const vk::Device& device, std::function<std::span<const uint32_t>(const char*)> shader,
                    uint32_t slots);
    ~ScreenDiffusion();
    ScreenDiffusion(const ScreenDiffusion&) = delete;
    ScreenDiffusion& operator=(const ScreenDiffusion&) = delete;

    static constexpr VkFormat kSceneFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
    static constexpr VkFormat kDiffuseFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
    static constexpr VkFormat kSurfaceFormat = VK_FORMAT_R32G32_SFLOAT;

    // Each skin material's kernel (skin/SeparableKernel.h): its own profile (LUT layer profile + 1)
    // at its scatter scale. `materials`: the GPU scene's order (the scene's, then the default).
    // Each slot takes them up when it is next recorded.
    void setKernels(const std::vector<Material>& materials, const std::vector<ProfileLayer>& layers, uint32_t taps);
    uint32_t taps() const { return taps_; }

    // The targets for frames of this size, eyes and samples; `retire` takes replaced images.
    void ensureTargets(VkExtent2D extent, uint32_t eyes, uint32_t samples,
                       const std::function<void(vk::Image&)>& retire);

    // The forward pass's colour attachments after the scene (location 0): diffuse, surface; with
    // their multisampled images when samples > 1.
    struct Attachment {
        const vk::Image* resolved;
        const vk::Image* multisampled;  // null without MSAA
        VkFormat format;
    };
    std::array<Attachment, 2> splitAttachments() const;
    const vk::Image& scene() const { return scene_; }
    const vk::Image& sceneMultisampled() const { return msaaScene_; }

    // After the forward pass (the scene, diffuse and surface targets written and resolved): the
    // two blur passes, the second into `target` (left in target.layoutAfter).
    void record(VkCommandBuffer cmd, uint32_t slot, const RenderTarget& target, const View& view, bool layered,
                const std::function<void()>& betweenPasses);

    // What the baseline adds: its passes and its targets' bytes (multisampled ones included).
    static constexpr uint32_t kPasses = 2;
    uint32_t targetCount() const;
    uint64_t targetBytes() const;

    // Rebuilds the pipelines with the current shaders (after the renderer's overrides changed);
    // throws and keeps the old ones on failure.
    void rebuildPipelines();

private:
    VkPipeline pipeline(uint32_t pass, VkFormat format, uint32_t eyes, bool layered);
    VkPipeline createPipeline(uint32_t pass, VkFormat format, uint32_t eyes, bool layered, uint32_t taps) const;

    const vk::Device& device_;
    std::function<std::span<const uint32_t>(const char*)> shader_;
    VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    std::vector<std::array<VkDescriptorSet, 2>> sets_;  // per slot: horizontal, vertical
    VkSampler linear_ = VK_NULL_HANDLE;
    VkSampler nearest_ = VK_NULL_HANDLE;
    std::vector<glm::vec4> kernelData_;
    uint64_t kernelVersion_ = 0;
    struct SlotKernels {
        vk::Buffer buffer;
        uint64_t version = ~0ull;
    };
    std::vector<SlotKernels> kernels_;  // per slot
    uint32_t kernelMaterials_ = 0;
    uint32_t taps_ = 0;
    vk::Image scene_, diffuse_, surface_, intermediate_;
    vk::Image msaaScene_, msaaDiffuse_, msaaSurface_;
    using Key = std::tuple<uint32_t, VkFormat, uint32_t, bool, uint32_t>;  // pass, format, eyes, layered, taps
    std::map<Key, VkPipeline> pipelines_;
};

}  // namespace preskin
