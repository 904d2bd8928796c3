// The multiview clipping probe (see MultiviewProbe.h).
#include "render/MultiviewProbe.h"

#include <preskin/Error.h>

#include "vk/Pipeline.h"
#include "vk/Resources.h"

#include <cstring>
#include <span>
#include <string_view>
#include <vector>

namespace preskin::shaders {
std::span<const uint32_t> spirv(std::string_view fileName);
}

namespace preskin {

bool multiviewClipsEveryView(const vk::Device& device) {
    if (const std::optional<bool> known = device.multiviewClipping()) return *known;
    constexpr uint32_t kSize = 4;
    constexpr uint32_t kViews = 2;
    constexpr VkFormat kFormat = VK_FORMAT_R8G8B8A8_UNORM;
    vk::Image target(device,
                     {kFormat, kSize, kSize, 1, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                      VK_IMAGE_ASPECT_COLOR_BIT, kViews});
    vk::Buffer readback(device, kSize * kSize * 4 * kViews, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    const VkPipelineLayout layout = vk::createPipelineLayout(device, {}, 0, 0);
    VkPipeline pipeline = VK_NULL_HANDLE;
    try {
        vk::GraphicsPipelineDesc desc;
        desc.vertexSpirv = shaders::spirv("multiview_probe.vert");
        desc.fragmentSpirv = shaders::spirv("multiview_probe.frag");
        desc.colorFormats = {kFormat};
        desc.cullMode = VK_CULL_MODE_NONE;
        desc.depthTest = false;
        desc.depthWrite = false;
        desc.viewMask = (1u << kViews) - 1u;
        desc.layout = layout;
        pipeline = vk::createGraphicsPipeline(device, desc);
        device.submitAndWait([&](VkCommandBuffer cmd) {
            vk::imageBarrier(cmd, target.handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                             VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                             VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                             kViews);
            VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
            color.imageView = target.view();
            color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
            color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
            color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
            VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
            info.renderArea = {{0, 0}, {kSize, kSize}};
            info.viewMask = (1u << kViews) - 1u;
            info.colorAttachmentCount = 1;
            info.pColorAttachments = &color;
            vkCmdBeginRendering(cmd, &info);
            const VkViewport viewport{0.0f, 0.0f, float(kSize), float(kSize), 0.0f, 1.0f};
            const VkRect2D scissor{{0, 0}, {kSize, kSize}};
            vkCmdSetViewport(cmd, 0, 1, &viewport);
            vkCmdSetScissor(cmd, 0, 1, &scissor);
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
            vkCmdDraw(cmd, 3, 1, 0, 0);
            vkCmdEndRendering(cmd);
            vk::imageBarrier(cmd, target.handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                             VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                             VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                             VK_ACCESS_2_TRANSFER_READ_BIT, kViews);
            VkBufferImageCopy region{};
            region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, kViews};
            region.imageExtent = {kSize, kSize, 1};
            vkCmdCopyImageToBuffer(cmd, target.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback.handle(), 1,
                                   &region);
            vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                              VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
        });
    } catch (...) {
        if (pipeline) vkDestroyPipeline(device.device(), pipeline, nullptr);
        vkDestroyPipelineLayout(device.device(), layout, nullptr);
        throw;
    }
    vkDestroyPipeline(device.device(), pipeline, nullptr);
    vkDestroyPipelineLayout(device.device(), layout, nullptr);
    std::vector<uint8_t> pixels(kSize * kSize * 4 * kViews);
    std::memcpy(pixels.data(), readback.mapped(), pixels.size());
    bool covered = true;
    for (uint8_t v : pixels) covered = covered && v == 255;
    device.setMultiviewClipping(covered);
    return covered;
}

}  // namespace preskin
