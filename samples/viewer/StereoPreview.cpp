// The side-by-side stereo preview (see StereoPreview.h).
#include "StereoPreview.h"

#include <preskin/Error.h>

#include <algorithm>

namespace preskin::viewer {

void StereoPreview::release() {
    if (view_) vk_.vkDestroyImageView(vk_.device, view_, nullptr);
    if (image_) vk_.vkDestroyImage(vk_.device, image_, nullptr);
    if (memory_) vk_.vkFreeMemory(vk_.device, memory_, nullptr);
    view_ = VK_NULL_HANDLE;
    image_ = VK_NULL_HANDLE;
    memory_ = VK_NULL_HANDLE;
}

void StereoPreview::ensure(VkExtent2D eye, VkFormat format) {
    if (image_ && eye.width == eye_.width && eye.height == eye_.height && format == format_) return;
    if (image_) check(vk_.vkDeviceWaitIdle(vk_.device), "vkDeviceWaitIdle");  // a frame in flight may still copy it
    release();
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent = {eye.width, eye.height, 1};
    info.mipLevels = 1;
    info.arrayLayers = 2;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    check(vk_.vkCreateImage(vk_.device, &info, nullptr, &image_), "vkCreateImage (stereo preview)");
    VkMemoryRequirements req{};
    vk_.vkGetImageMemoryRequirements(vk_.device, image_, &req);
    VkPhysicalDeviceMemoryProperties props{};
    vk_.vkGetPhysicalDeviceMemoryProperties(vk_.physicalDevice, &props);
    uint32_t type = UINT32_MAX;
    for (uint32_t i = 0; i < props.memoryTypeCount && type == UINT32_MAX; ++i)
        if ((req.memoryTypeBits & (1u << i)) &&
            (props.memoryTypes[i].propertyFlags & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT))
            type = i;
    for (uint32_t i = 0; i < props.memoryTypeCount && type == UINT32_MAX; ++i)
        if (req.memoryTypeBits & (1u << i)) type = i;
    if (type == UINT32_MAX) throw Error("Vulkan: no memory type for the stereo preview image");
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = type;
    check(vk_.vkAllocateMemory(vk_.device, &alloc, nullptr, &memory_), "vkAllocateMemory (stereo preview)");
    check(vk_.vkBindImageMemory(vk_.device, image_, memory_, 0), "vkBindImageMemory (stereo preview)");
    VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    viewInfo.image = image_;
    viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D_ARRAY;
    viewInfo.format = format;
    viewInfo.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 2};
    check(vk_.vkCreateImageView(vk_.device, &viewInfo, nullptr, &view_), "vkCreateImageView (stereo preview)");
    eye_ = eye;
    format_ = format;
}

void StereoPreview::copyToWindow(VkCommandBuffer cmd, VkImage window, VkExtent2D windowExtent,
                                 VkImageLayout windowLayoutAfter) const {
    imageBarrier(vk_, cmd, window, 1, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_NONE,
                 VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    const VkClearColorValue clear{{0.045f, 0.045f, 0.05f, 1.0f}};
    const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vk_.vkCmdClearColorImage(cmd, window, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &clear, 1, &range);
    imageBarrier(vk_, cmd, window, 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                 VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    VkImageCopy regions[2]{};
    for (uint32_t e = 0; e < 2; ++e) {
        regions[e].srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, e, 1};
        regions[e].dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        regions[e].dstOffset = {int32_t(e * eye_.width), 0, 0};
        regions[e].extent = {std::min(eye_.width, windowExtent.width), std::min(eye_.height, windowExtent.height), 1};
    }
    vk_.vkCmdCopyImage(cmd, image_, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, window, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                       2, regions);
    const bool toCopy = windowLayoutAfter == VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    imageBarrier(vk_, cmd, window, 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, windowLayoutAfter,
                 VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                 toCopy ? VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT : VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                 toCopy ? VK_ACCESS_2_TRANSFER_READ_BIT
                        : VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
}

}  // namespace preskin::viewer
