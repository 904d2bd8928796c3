#include "support/ComputeDispatch.h"

#include "support/TestShaders.h"

#include "vk/Check.h"
#include "vk/Pipeline.h"
#include "vk/Resources.h"

namespace preskin::test {

ComputeResource bufferResource(VkDescriptorType type, VkBuffer buffer, VkDeviceSize bytes) {
    ComputeResource r;
    r.type = type;
    r.buffer = {buffer, 0, bytes};
    return r;
}

ComputeResource imageResource(VkSampler sampler, VkImageView view) {
    ComputeResource r;
    r.type = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    r.image = {sampler, view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    return r;
}

void dispatchCompute(const vk::Device& device, std::string_view shader, std::span<const ComputeResource> resources,
                     std::span<const uint32_t> push, uint32_t invocations, uint32_t localSize) {
    const VkDevice d = device.device();
    const VkShaderStageFlags compute = VK_SHADER_STAGE_COMPUTE_BIT;
    std::vector<vk::Binding> bindings;
    std::vector<VkDescriptorPoolSize> sizes;
    for (uint32_t i = 0; i < resources.size(); ++i) {
        bindings.push_back({i, resources[i].type, compute});
        sizes.push_back({resources[i].type, 1});
    }
    const VkDescriptorSetLayout setLayout = vk::createSetLayout(device, bindings);
    const auto pushBytes = static_cast<uint32_t>(push.size_bytes());
    const VkPipelineLayout layout = vk::createPipelineLayout(device, std::span(&setLayout, 1), pushBytes, compute);
    const VkPipeline pipeline = vk::createComputePipeline(device, test_shaders::spirv(shader), layout);

    VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    poolInfo.maxSets = 1;
    poolInfo.poolSizeCount = static_cast<uint32_t>(sizes.size());
    poolInfo.pPoolSizes = sizes.data();
    VkDescriptorPool pool = VK_NULL_HANDLE;
    PRESKIN_VK(vkCreateDescriptorPool(d, &poolInfo, nullptr, &pool));
    VkDescriptorSetAllocateInfo allocInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    allocInfo.descriptorPool = pool;
    allocInfo.descriptorSetCount = 1;
    allocInfo.pSetLayouts = &setLayout;
    VkDescriptorSet set = VK_NULL_HANDLE;
    PRESKIN_VK(vkAllocateDescriptorSets(d, &allocInfo, &set));
    std::vector<VkWriteDescriptorSet> writes(resources.size());
    for (uint32_t i = 0; i < resources.size(); ++i) {
        writes[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        writes[i].dstSet = set;
        writes[i].dstBinding = i;
        writes[i].descriptorCount = 1;
        writes[i].descriptorType = resources[i].type;
        if (resources[i].type == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER)
            writes[i].pImageInfo = &resources[i].image;
        else
            writes[i].pBufferInfo = &resources[i].buffer;
    }
    vkUpdateDescriptorSets(d, static_cast<uint32_t>(writes.size()), writes.data(), 0, nullptr);

    device.submitAndWait([&](VkCommandBuffer cmd) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout, 0, 1, &set, 0, nullptr);
        if (pushBytes > 0) vkCmdPushConstants(cmd, layout, compute, 0, pushBytes, push.data());
        vkCmdDispatch(cmd, (invocations + localSize - 1) / localSize, 1, 1);
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    });
    vkDestroyDescriptorPool(d, pool, nullptr);
    vkDestroyPipeline(d, pipeline, nullptr);
    vkDestroyPipelineLayout(d, layout, nullptr);
    vkDestroyDescriptorSetLayout(d, setLayout, nullptr);
}

}  // namespace preskin::test
