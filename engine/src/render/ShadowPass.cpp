// The shadow pass of the sample renderer: the directional light's orthographic shadow map
// (fitted to the skin in view, render/ShadowFit.h), its depth-only pipeline and its recording. The
// forward pass samples the map with preskin/shadow.glsl's Gaussian PCF.
#include "render/RendererImpl.h"

#include "shared/gpu_types.h"
#include "vk/Check.h"
#include "vk/Pipeline.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

namespace preskin {

// The shadow map at the settings' size; a new one starts in the read layout (sampled even
// when no light casts a shadow), transitioned in `cmd`.
void Renderer::Impl::createShadowMap(VkCommandBuffer cmd, uint32_t slotIndex) {
    const uint32_t size = std::clamp<uint32_t>(settings.shadowMapSize, 16, 8192);
    if (shadowMap && shadowMap.desc().width == size) return;
    if (!dev.supportsFormat(kDepthFormat, VK_FORMAT_FEATURE_2_DEPTH_STENCIL_ATTACHMENT_BIT |
                                              VK_FORMAT_FEATURE_2_SAMPLED_IMAGE_BIT))
        throw Error("Vulkan: the device cannot render and sample D32_SFLOAT depth");
    retire(shadowMap, slotIndex);
    shadowMap = vk::Image(dev, {kDepthFormat, size, size, 1,
                                VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                                VK_IMAGE_ASPECT_DEPTH_BIT});
    vk::imageBarrier(cmd, shadowMap.handle(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                     VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
}

VkPipeline Renderer::Impl::createShadowPipeline() const {
    vk::GraphicsPipelineDesc desc;
    desc.vertexSpirv = shader("shadow.vert");
    desc.vertexBindings = {{0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX}};
    desc.vertexAttributes = {{gpu::kAttributePosition, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, positionOs)}};
    desc.depthFormat = kDepthFormat;
    desc.cullMode = VK_CULL_MODE_NONE;  // the nearest surface of either facing: thickness needs it
    desc.depthCompare = VK_COMPARE_OP_LESS_OR_EQUAL;
    desc.depthBias = true;
    desc.layout = shadowLayout;
    return vk::createGraphicsPipeline(dev, desc);
}

VkPipeline Renderer::Impl::depthOnlyPipeline() {
    if (!shadowPipeline) shadowPipeline = createShadowPipeline();
    return shadowPipeline;
}

void Renderer::Impl::recordShadowPass(VkCommandBuffer cmd, Slot& slot, uint32_t slotIndex) {
    const uint32_t size = shadowMap.desc().width;
    vk::imageBarrier(cmd, shadowMap.handle(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                     VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                     VK_ACCESS_2_NONE,
                     VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                     VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
    VkRenderingAttachmentInfo depthAttachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depthAttachment.imageView = shadowMap.view();
    depthAttachment.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depthAttachment.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depthAttachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    depthAttachment.clearValue.depthStencil = {1.0f, 0};
    VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
    info.renderArea = {{0, 0}, {size, size}};
    info.layerCount = 1;
    info.pDepthAttachment = &depthAttachment;
    vkCmdBeginRendering(cmd, &info);
    const VkViewport viewport{0.0f, 0.0f, float(size), float(size), 0.0f, 1.0f};
    const VkRect2D scissor{{0, 0}, {size, size}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    vkCmdSetDepthBias(cmd, 1.0f, 0.0f, 1.5f);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, depthOnlyPipeline());
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, shadowLayout, 0, 1, &slot.set, 0, nullptr);
    VkBuffer boundVertices = VK_NULL_HANDLE;
    bindGeometry(cmd, boundVertices);
    for (const DrawItem& d : scene->draws) {
        if (scene->materials[d.material].alphaMode == AlphaMode::Blend) continue;
        const int32_t vertexOffset = bindDrawVertices(cmd, slotIndex, d, boundVertices);
        const gpu::DrawPush push{glm::uvec4(d.instance, d.material, 0, 0)};
        vkCmdPushConstants(cmd, shadowLayout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                           sizeof(push), &push);
        vkCmdDrawIndexed(cmd, d.indexCount, 1, d.firstIndex, vertexOffset, 0);
    }
    vkCmdEndRendering(cmd);
    vk::imageBarrier(cmd, shadowMap.handle(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                     VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                     VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
}

}  // namespace preskin
