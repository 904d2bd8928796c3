// The shadow pass of the sample renderer: the directional light's orthographic shadow map
// (fitted to the skin in view, render/ShadowFit.h), its depth-only pipeline (and the alpha-tested
// one of masked materials) and its recording, and
// for scenes with skin the wide map reduced from it (shaders/shadow_reduce.comp). The forward pass
// samples both with preskin/shadow.glsl's Gaussian PCF.
#include "render/RendererImpl.h"

#include "shared/gpu_types.h"
#include "vk/Check.h"
#include "vk/Pipeline.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

namespace preskin {

// The shadow map at the settings' size and skin's wide map; new ones start in the read layout
// (sampled even when no light casts a shadow), transitioned in `cmd`.
void Renderer::Impl::createShadowMap(VkCommandBuffer cmd, uint32_t slotIndex) {
    const uint32_t size = std::clamp<uint32_t>(settings.shadowMapSize, 16, 8192);
    if (shadowMap && shadowMap.desc().width == size) return;
    if (!dev.supportsFormat(kDepthFormat,
                            VK_FORMAT_FEATURE_2_DEPTH_STENCIL_ATTACHMENT_BIT | VK_FORMAT_FEATURE_2_SAMPLED_IMAGE_BIT))
        throw Error("Vulkan: the device cannot render and sample D32_SFLOAT depth");
    retire(shadowMap, slotIndex);
    shadowMap = vk::Image(
        dev,
        {kDepthFormat, size, size, 1, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
         VK_IMAGE_ASPECT_DEPTH_BIT});
    vk::imageBarrier(cmd, shadowMap.handle(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                     VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
}

uint32_t Renderer::Impl::wideShadowSize() const {
    const uint32_t size = std::clamp<uint32_t>(settings.shadowMapSize, 16, 8192);
    return (size + wideFactor - 1) / wideFactor;
}

void Renderer::Impl::createWideShadowMap(VkCommandBuffer cmd, uint32_t slotIndex) {
    const uint32_t wideSize = wideShadowSize();
    if (wideShadowMap && wideShadowMap.desc().width == wideSize) return;
    retire(wideShadowMap, slotIndex);
    wideShadowMap = vk::Image(dev,
                              {VK_FORMAT_R32_SFLOAT, wideSize, wideSize, 1,
                               VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, VK_IMAGE_ASPECT_COLOR_BIT});
    vk::imageBarrier(cmd, wideShadowMap.handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                     VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
}

void Renderer::Impl::recordWideShadow(VkCommandBuffer cmd, Slot& slot) {
    // The slot's set, like its frame set, is only in use by the slot's previous frame, which is done.
    const VkDescriptorImageInfo read{shadowSampler, shadowMap.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    const VkDescriptorImageInfo write{VK_NULL_HANDLE, wideShadowMap.view(), VK_IMAGE_LAYOUT_GENERAL};
    VkWriteDescriptorSet writes[2]{};
    for (uint32_t b = 0; b < 2; ++b) {
        writes[b] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        writes[b].dstSet = slot.reduceSet;
        writes[b].dstBinding = b;
        writes[b].descriptorCount = 1;
        writes[b].descriptorType =
            b == 0 ? VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER : VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
        writes[b].pImageInfo = b == 0 ? &read : &write;
    }
    vkUpdateDescriptorSets(dev.device(), 2, writes, 0, nullptr);
    vk::imageBarrier(cmd, wideShadowMap.handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                     VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_NONE,
                     VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, reducePipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, reduceLayout, 0, 1, &slot.reduceSet, 0, nullptr);
    vkCmdPushConstants(cmd, reduceLayout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(uint32_t), &wideFactor);
    const uint32_t groups = (wideShadowMap.desc().width + 7) / 8;
    vkCmdDispatch(cmd, groups, groups, 1);
    vk::imageBarrier(cmd, wideShadowMap.handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_GENERAL,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                     VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                     VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
}

// Depth only, or for alpha-masked materials with shadow_mask.frag, which reads the material's set
// (the forward layout) and discards below the cutoff.
VkPipeline Renderer::Impl::createShadowPipeline(bool masked) const {
    vk::GraphicsPipelineDesc desc;
    desc.vertexSpirv = shader("shadow.vert");
    if (masked) desc.fragmentSpirv = shader("shadow_mask.frag");
    desc.vertexBindings = {{0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX}};
    desc.vertexAttributes = {{gpu::kAttributePosition, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, positionOs)},
                             {gpu::kAttributeUv0, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(Vertex, uv0)}};
    desc.depthFormat = kDepthFormat;
    desc.cullMode = VK_CULL_MODE_NONE;  // the nearest surface of either facing: thickness needs it
    desc.depthCompare = VK_COMPARE_OP_LESS_OR_EQUAL;
    desc.depthBias = true;
    desc.layout = masked ? forwardLayout : shadowLayout;
    return vk::createGraphicsPipeline(dev, desc);
}

VkPipeline Renderer::Impl::depthOnlyPipeline(bool masked) {
    VkPipeline& p = masked ? shadowMaskPipeline : shadowPipeline;
    if (!p) p = createShadowPipeline(masked);
    return p;
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
    vkCmdSetDepthBias(cmd, gpu::kShadowDepthBiasConstant, 0.0f, gpu::kShadowDepthBiasSlope);
    VkBuffer boundVertices = VK_NULL_HANDLE;
    bindGeometry(cmd, boundVertices);
    // Opaque draws depth only, then alpha-masked ones through shadow_mask.frag; blended ones cast
    // no shadow.
    for (const bool masked : {false, true}) {
        const VkPipelineLayout layout = masked ? forwardLayout : shadowLayout;
        bool bound = false;
        uint32_t boundMaterial = UINT32_MAX;
        for (const DrawItem& d : scene->draws) {
            const GpuMaterial& m = scene->materials[d.material];
            if (m.alphaMode == AlphaMode::Blend || (m.alphaMode == AlphaMode::Mask) != masked) continue;
            if (!bound) {
                vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, depthOnlyPipeline(masked));
                vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &slot.set, 0, nullptr);
                bound = true;
            }
            if (masked && d.material != boundMaterial) {
                vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 1, 1, &m.set, 0, nullptr);
                boundMaterial = d.material;
            }
            const int32_t vertexOffset = bindDrawVertices(cmd, slotIndex, d, boundVertices);
            const gpu::DrawPush push{glm::uvec4(d.instance, d.material, 0, 0)};
            vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(push),
                               &push);
            vkCmdDrawIndexed(cmd, d.indexCount, 1, d.firstIndex, vertexOffset, 0);
        }
    }
    vkCmdEndRendering(cmd);
    vk::imageBarrier(cmd, shadowMap.handle(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                     VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                     VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    timestamp(cmd, slot, 6);  // the map drawn; the wide map's reduction (skin only) follows
    // Without a reader the wide map keeps its contents and its read-only layout (both unused).
    if (sceneHasSkin && wideShadowRead()) recordWideShadow(cmd, slot);
}

bool Renderer::Impl::wideShadowRead() const {
    for (const GpuMaterial& m : scene->materials)
        if (m.skin && luts->valid() && (skinMask(m) & gpu::kSkinWideShadowBits) == gpu::kSkinWideShadowBits)
            return true;
    return false;
}

}  // namespace preskin
