// Screenshots of swapchain images: records a copy of an image (in TRANSFER_SRC_OPTIMAL) into a
// host-visible buffer, and once that frame's fence has signalled turns the bytes into a
// preskin::RenderedImage (RGBA, sRGB-encoded 8-bit) and writes it with preskin::writeImage
// (atomic: a temporary file renamed into place). One buffer per frame slot.
// Limits: 8-bit RGBA/BGRA swapchain formats only; the PNG keeps the alpha the frame has, except
// captures with the overlay, which are made opaque (the panels blend into alpha too).
#pragma once

#include "VulkanFunctions.h"

#include <preskin/Renderer.h>

#include <filesystem>
#include <optional>
#include <vector>

namespace preskin::viewer {

class ImageCapture {
public:
    ImageCapture(const VulkanFunctions& vk, uint32_t slotCount);
    ~ImageCapture();
    ImageCapture(const ImageCapture&) = delete;
    ImageCapture& operator=(const ImageCapture&) = delete;

    // Records the copy of `image` (TRANSFER_SRC_OPTIMAL) for frame slot `slot`, to be written to
    // `path` when finish(slot) runs after that frame completed.
    void record(VkCommandBuffer cmd, uint32_t slot, VkImage image, VkFormat format, VkExtent2D extent,
                const std::filesystem::path& path, bool opaque);
    bool pending(uint32_t slot) const { return slots_[slot].path.has_value(); }
    // Writes the slot's capture (its frame must have completed); returns the path written.
    // Throws preskin::Error when writing fails (the capture is dropped either way).
    std::optional<std::filesystem::path> finish(uint32_t slot);

private:
    struct Slot {
        VkBuffer buffer = VK_NULL_HANDLE;
        VkDeviceMemory memory = VK_NULL_HANDLE;
        VkDeviceSize capacityBytes = 0;
        void* mapped = nullptr;
        VkFormat format = VK_FORMAT_UNDEFINED;
        VkExtent2D extent{};
        bool opaque = false;
        std::optional<std::filesystem::path> path;
    };
    void reserve(Slot& slot, VkDeviceSize bytes);
    void release(Slot& slot);

    const VulkanFunctions& vk_;
    std::vector<Slot> slots_;
};

}  // namespace preskin::viewer
