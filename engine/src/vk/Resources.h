// GPU buffers and images with their memory (one allocation each: scenes here hold few, large
// resources), plus the barrier and upload helpers every pass uses.
#pragma once

#include "vk/Device.h"

#include <cstddef>
#include <span>
#include <utility>

namespace preskin::vk {

class Buffer {
public:
    Buffer() = default;
    // hostVisible: mapped persistently (uniforms, per-frame data, readback); else device-local.
    Buffer(const Device& device, VkDeviceSize size, VkBufferUsageFlags usage, bool hostVisible);
    ~Buffer() { release(); }
    Buffer(Buffer&& o) noexcept { *this = std::move(o); }
    Buffer& operator=(Buffer&& o) noexcept;
    Buffer(const Buffer&) = delete;
    Buffer& operator=(const Buffer&) = delete;

    VkBuffer handle() const { return buffer_; }
    VkDeviceSize size() const { return size_; }
    void* mapped() const { return mapped_; }
    explicit operator bool() const { return buffer_ != VK_NULL_HANDLE; }
    // Host-visible buffers: copies bytes in. Device-local ones: through a staging buffer.
    void upload(const void* data, VkDeviceSize bytes, VkDeviceSize offset = 0);

private:
    void release();
    const Device* device_ = nullptr;
    VkBuffer buffer_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkDeviceSize size_ = 0;
    void* mapped_ = nullptr;
};

struct ImageDesc {
    VkFormat format = VK_FORMAT_R8G8B8A8_UNORM;
    uint32_t width = 1;
    uint32_t height = 1;
    uint32_t mipLevels = 1;
    VkImageUsageFlags usage = VK_IMAGE_USAGE_SAMPLED_BIT;
    VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
    uint32_t layers = 1;  // > 1: a 2D array image with a 2D_ARRAY view of every layer
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
    bool arrayView = false;  // a 2D_ARRAY view even for one layer (sampler2DArray)
    bool cube = false;       // 6 layers, cube compatible, a CUBE view (samplerCube)
};

class Image {
public:
    Image() = default;
    Image(const Device& device, const ImageDesc& desc);
    ~Image() { release(); }
    Image(Image&& o) noexcept { *this = std::move(o); }
    Image& operator=(Image&& o) noexcept;
    Image(const Image&) = delete;
    Image& operator=(const Image&) = delete;

    VkImage handle() const { return image_; }
    VkImageView view() const { return view_; }
    const ImageDesc& desc() const { return desc_; }
    VkExtent2D extent() const { return {desc_.width, desc_.height}; }
    explicit operator bool() const { return image_ != VK_NULL_HANDLE; }

    // Uploads mip 0 (tightly packed rows) and, when the image has more levels, fills the chain
    // with linear blits (sRGB formats are filtered in linear space). Ends SHADER_READ_ONLY.
    void uploadAndGenerateMips(const void* pixels, size_t bytes);
    // Replaces mip 0 of one array layer (images with one mip level) and leaves it
    // SHADER_READ_ONLY_OPTIMAL; `oldLayout` is the layer's layout now (UNDEFINED when new).
    void uploadLayer(const void* pixels, size_t bytes, uint32_t layer, VkImageLayout oldLayout);

private:
    void release();
    const Device* device_ = nullptr;
    ImageDesc desc_;
    VkImage image_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkImageView view_ = VK_NULL_HANDLE;
};

uint32_t mipLevelCount(uint32_t width, uint32_t height);

// One image layout transition with a synchronization2 barrier covering all mips of layers
// [0, layerCount).
void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, VkImageLayout oldLayout,
                  VkImageLayout newLayout, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                  VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess, uint32_t layerCount = 1);
// Begins dynamic rendering into `colors` (no depth) over the whole extent, `layerCount` layers
// (or the views of `viewMask`), and sets the viewport and scissor to it.
void beginColorRendering(VkCommandBuffer cmd, VkExtent2D extent, std::span<const VkRenderingAttachmentInfo> colors,
                         uint32_t viewMask = 0, uint32_t layerCount = 1);
void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess);

}  // namespace preskin::vk
