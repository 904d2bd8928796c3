// The environment on the GPU for specular reflection and the background (preskin/ibl.glsl):
// its image with a mip chain (the backdrop), the GGX-prefiltered cube made from the image less
// its extracted lights by a compute pass (env_prefilter.comp) whenever the environment or the
// extraction changes, and the split-sum DFG table (made once, on the CPU: env/Dfg.h).
#pragma once

#include <preskin/Environment.h>

#include "vk/Resources.h"

namespace preskin {

class GpuEnvironment {
public:
    explicit GpuEnvironment(const vk::Device& device);
    ~GpuEnvironment();
    GpuEnvironment(const GpuEnvironment&) = delete;
    GpuEnvironment& operator=(const GpuEnvironment&) = delete;

    // The backdrop from the environment's image (a constant environment: its radiance), the
    // prefiltered cube from `specularImage` (EnvironmentLights::residualImage; empty: the
    // environment's radiance). Waits for the device.
    void set(const Environment& environment, const EquirectImage& specularImage);

    VkDescriptorImageInfo imageInfo() const {
        return {sampler_, image_.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    }
    VkDescriptorImageInfo prefilteredInfo() const {
        return {sampler_, prefiltered_.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    }
    VkDescriptorImageInfo dfgInfo() const {
        return {clampSampler_, dfg_.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    }
    // The prefiltered cube's last level (roughness 1).
    float maxLevel() const { return float(prefiltered_.desc().mipLevels - 1); }
    uint32_t faceSize() const { return prefiltered_.desc().width; }
    // Every level of the prefiltered cube read back as RGBA floats, level after level, face after
    // face (for tests).
    std::vector<glm::vec4> readPrefiltered() const;
    // CPU wall time of the last set(): upload, mips and the prefiltering on the device.
    double setMs() const { return setMs_; }
    // Bumped by every set(): descriptor sets that hold the images are written again.
    uint64_t version() const { return version_; }

private:
    void prefilter(const EquirectImage& image);

    const vk::Device& device_;
    VkSampler sampler_ = VK_NULL_HANDLE;       // linear, mipmapped, longitude repeats
    VkSampler clampSampler_ = VK_NULL_HANDLE;  // linear, clamped (the DFG table, the cube)
    VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkPipeline pipeline_ = VK_NULL_HANDLE;
    vk::Image image_;
    vk::Image prefiltered_;
    vk::Image dfg_;
    double setMs_ = 0.0;
    uint64_t version_ = 0;
};

}  // namespace preskin
