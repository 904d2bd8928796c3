// One dispatch of a test compute shader (tests/reference/shaders/*.comp) with its resources bound at
// set 0, bindings 0, 1, 2, ... in order, and push constants; waits for it and makes its storage
// writes visible to the host.
#pragma once

#include "vk/Device.h"

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace preskin::test {

struct ComputeResource {
    VkDescriptorType type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;  // a buffer type or COMBINED_IMAGE_SAMPLER
    VkDescriptorBufferInfo buffer{};
    VkDescriptorImageInfo image{};
};

ComputeResource bufferResource(VkDescriptorType type, VkBuffer buffer, VkDeviceSize bytes);
ComputeResource imageResource(VkSampler sampler, VkImageView view);

void dispatchCompute(const vk::Device& device, std::string_view shader, std::span<const ComputeResource> resources,
                     std::span<const uint32_t> push, uint32_t invocations, uint32_t localSize = 64);

}  // namespace preskin::test
