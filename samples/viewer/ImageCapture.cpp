// Swapchain image readback and PNG writing (see ImageCapture.h).
#include "ImageCapture.h"

#include <preskin/Error.h>

#include <fmt/core.h>

#include <cstring>
#include <utility>

namespace preskin::viewer {

ImageCapture::ImageCapture(const VulkanFunctions& vk, uint32_t slotCount) : vk_(vk), slots_(slotCount) {}

ImageCapture::~ImageCapture() {
    for (Slot& s : slots_) release(s);
}

void ImageCapture::release(Slot& slot) {
    if (slot.mapped) vk_.vkUnmapMemory(vk_.device, slot.memory);
    if (slot.buffer) vk_.vkDestroyBuffer(vk_.device, slot.buffer, nullptr);
    if (slot.memory) vk_.vkFreeMemory(vk_.device, slot.memory, nullptr);
    slot.mapped = nullptr;
    slot.buffer = VK_NULL_HANDLE;
    slot.memory = VK_NULL_HANDLE;
    slot.capacityBytes = 0;
}

void ImageCapture::reserve(Slot& slot, VkDeviceSize bytes) {
    if (slot.capacityBytes >= bytes) return;
    release(slot);
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = bytes;
    info.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    check(vk_.vkCreateBuffer(vk_.device, &info, nullptr, &slot.buffer), "vkCreateBuffer (screenshot)");
    VkMemoryRequirements req{};
    vk_.vkGetBufferMemoryRequirements(vk_.device, slot.buffer, &req);
    VkPhysicalDeviceMemoryProperties props{};
    vk_.vkGetPhysicalDeviceMemoryProperties(vk_.physicalDevice, &props);
    uint32_t type = UINT32_MAX;
    for (VkMemoryPropertyFlags wanted :
         {VkMemoryPropertyFlags(VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_CACHED_BIT),
          VkMemoryPropertyFlags(VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT)}) {
        for (uint32_t i = 0; i < props.memoryTypeCount && type == UINT32_MAX; ++i)
            if ((req.memoryTypeBits & (1u << i)) && (props.memoryTypes[i].propertyFlags & wanted) == wanted) type = i;
        if (type != UINT32_MAX) break;
    }
    if (type == UINT32_MAX) throw Error("Vulkan: no host-visible memory for screenshots");
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = type;
    check(vk_.vkAllocateMemory(vk_.device, &alloc, nullptr, &slot.memory), "vkAllocateMemory (screenshot)");
    check(vk_.vkBindBufferMemory(vk_.device, slot.buffer, slot.memory, 0), "vkBindBufferMemory (screenshot)");
    check(vk_.vkMapMemory(vk_.device, slot.memory, 0, VK_WHOLE_SIZE, 0, &slot.mapped), "vkMapMemory (screenshot)");
    slot.capacityBytes = bytes;
}

void ImageCapture::record(VkCommandBuffer cmd, uint32_t slotIndex, VkImage image, VkFormat format, VkExtent2D extent,
                          const std::filesystem::path& path, bool opaque) {
    Slot& slot = slots_[slotIndex];
    reserve(slot, VkDeviceSize(extent.width) * extent.height * 4);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {extent.width, extent.height, 1};
    vk_.vkCmdCopyImageToBuffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, slot.buffer, 1, &region);
    VkMemoryBarrier2 toHost{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    toHost.srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT;
    toHost.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    toHost.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
    toHost.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.memoryBarrierCount = 1;
    dep.pMemoryBarriers = &toHost;
    vk_.vkCmdPipelineBarrier2(cmd, &dep);
    slot.format = format;
    slot.extent = extent;
    slot.opaque = opaque;
    slot.path = path;
}

std::optional<std::filesystem::path> ImageCapture::finish(uint32_t slotIndex) {
    Slot& slot = slots_[slotIndex];
    if (!slot.path) return std::nullopt;
    const std::filesystem::path path = *std::exchange(slot.path, std::nullopt);
    VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE};
    range.memory = slot.memory;
    range.size = VK_WHOLE_SIZE;
    check(vk_.vkInvalidateMappedMemoryRanges(vk_.device, 1, &range), "vkInvalidateMappedMemoryRanges (screenshot)");

    RenderedImage image;
    image.width = slot.extent.width;
    image.height = slot.extent.height;
    image.encoding = OutputEncoding::DisplaySrgb8;
    const size_t bytes = size_t(image.width) * image.height * 4;
    image.rgba8.resize(bytes);
    std::memcpy(image.rgba8.data(), slot.mapped, bytes);
    const bool bgra = slot.format == VK_FORMAT_B8G8R8A8_SRGB || slot.format == VK_FORMAT_B8G8R8A8_UNORM;
    for (size_t i = 0; i < bytes; i += 4) {
        if (bgra) std::swap(image.rgba8[i], image.rgba8[i + 2]);
        if (slot.opaque) image.rgba8[i + 3] = 255;
    }
    writeImage(path, image);
    return path;
}

}  // namespace preskin::viewer
