// Pipeline creation for dynamic rendering: shader modules from embedded SPIR-V, graphics and
// compute pipelines with specialization constants, descriptor-set layouts.
#pragma once

#include "vk/Device.h"

#include <cstdint>
#include <span>
#include <vector>

namespace preskin::vk {

// Specialization constants: constant_id i takes values[i] (32-bit each: bool, int, uint, float bits).
struct Specialization {
    std::vector<uint32_t> values;
};

struct GraphicsPipelineDesc {
    std::span<const uint32_t> vertexSpirv;
    std::span<const uint32_t> fragmentSpirv;  // empty: depth-only
    Specialization specialization;            // applies to both stages
    std::vector<VkVertexInputBindingDescription> vertexBindings;
    std::vector<VkVertexInputAttributeDescription> vertexAttributes;
    std::vector<VkFormat> colorFormats;
    VkFormat depthFormat = VK_FORMAT_UNDEFINED;
    VkCullModeFlags cullMode = VK_CULL_MODE_BACK_BIT;
    VkFrontFace frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    bool depthTest = true;
    bool depthWrite = true;
    VkCompareOp depthCompare = VK_COMPARE_OP_GREATER_OR_EQUAL;  // reversed Z
    bool depthBias = false;                                     // dynamic state when set
    bool alphaBlend = false;
    // Per colour attachment: which components it writes (missing entries: all).
    std::vector<VkColorComponentFlags> colorWriteMasks;
    int additiveBlendAttachment = -1;  // this colour attachment adds what it is given (blend ONE, ONE)
    uint32_t viewMask = 0;             // multiview: must equal the rendering's viewMask
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
    bool alphaToCoverage = false;
    bool alphaToOne = false;  // needs the alphaToOne feature
    VkPipelineLayout layout = VK_NULL_HANDLE;
};

VkShaderModule createShaderModule(const Device& device, std::span<const uint32_t> spirv);
VkPipeline createGraphicsPipeline(const Device& device, const GraphicsPipelineDesc& desc);
VkPipeline createComputePipeline(const Device& device, std::span<const uint32_t> spirv, VkPipelineLayout layout,
                                 const Specialization& specialization = {});

struct Binding {
    uint32_t binding;
    VkDescriptorType type;
    VkShaderStageFlags stages;
};
VkDescriptorSetLayout createSetLayout(const Device& device, std::span<const Binding> bindings);
VkPipelineLayout createPipelineLayout(const Device& device, std::span<const VkDescriptorSetLayout> sets,
                                      uint32_t pushConstantBytes, VkShaderStageFlags pushStages);
// A pool for at most `maxSets` sets holding the given descriptors in all, and one set from it.
VkDescriptorPool createDescriptorPool(const Device& device, std::span<const VkDescriptorPoolSize> sizes,
                                      uint32_t maxSets);
VkDescriptorSet allocateDescriptorSet(const Device& device, VkDescriptorPool pool, VkDescriptorSetLayout layout);
// A sampler of one mip level with `filter` and clamp-to-edge addressing.
VkSampler createClampSampler(const Device& device, VkFilter filter);

}  // namespace preskin::vk
