// The skin LUTs on the GPU: four half-float textures sampled with LINEAR filtering and
// CLAMP_TO_EDGE, plus the mapping parameters the shader needs. Without a LutSet, 1x1 stand-ins
// keep the descriptors valid and skin materials render with the standard model.
#pragma once

#include "render/GpuScene.h"
#include "shared/gpu_types.h"
#include "vk/Resources.h"

#include <array>

namespace preskin {

class LutSet;

class GpuLuts {
public:
    GpuLuts(const vk::Device& device, const LutSet* luts);
    ~GpuLuts();
    GpuLuts(const GpuLuts&) = delete;
    GpuLuts& operator=(const GpuLuts&) = delete;

    bool valid() const { return valid_; }
    ProfileWidths profileWidths() const { return widths_; }
    const gpu::LutMapping& mapping() const { return mapping_; }
    // diffuse, penumbra, SH transfer, transmittance
    std::array<VkDescriptorImageInfo, 4> descriptors() const;

private:
    const vk::Device& device_;
    bool valid_ = false;
    ProfileWidths widths_;
    gpu::LutMapping mapping_{};
    std::array<vk::Image, 4> images_;
    VkSampler sampler_ = VK_NULL_HANDLE;
};

}  // namespace preskin
