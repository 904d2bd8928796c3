// The viewer's side-by-side stereo preview: the renderer draws both eyes of a stereo view in its
// one forward pass into a 2-layer array image owned here (as it would into an OpenXR multiview
// swapchain image), then each layer is copied into its half of the window's image, left eye on
// the left. The window image must allow transfer writes (Swapchain::transferDestination).
// Limits: a preview only (no lens distortion, no head tracking); an odd window width leaves the
// last column with the clear colour.
#pragma once

#include "VulkanFunctions.h"

#include <vulkan/vulkan_core.h>

#include <cstdint>

namespace preskin::viewer {

class StereoPreview {
public:
    explicit StereoPreview(const VulkanFunctions& vk) : vk_(vk) {}
    ~StereoPreview() { release(); }
    StereoPreview(const StereoPreview&) = delete;
    StereoPreview& operator=(const StereoPreview&) = delete;

    // Per-eye extent for a window of `window` pixels: half its width, its height.
    static VkExtent2D eyeExtent(VkExtent2D window) {
        return {window.width / 2 > 0 ? window.width / 2 : 1, window.height};
    }

    // The 2-layer image (and its 2D_ARRAY view) for eyes of `eye` pixels in `format`; recreated
    // when either changes (the device must be idle then, as after a swapchain change).
    void ensure(VkExtent2D eye, VkFormat format);
    VkImage image() const { return image_; }
    VkImageView view() const { return view_; }

    // After the renderer left the layers in TRANSFER_SRC_OPTIMAL: clears the window image and
    // copies layer e into its half e, leaving the window image in `windowLayoutAfter`.
    void copyToWindow(VkCommandBuffer cmd, VkImage window, VkExtent2D windowExtent,
                      VkImageLayout windowLayoutAfter) const;

private:
    void release();

    const VulkanFunctions& vk_;
    VkImage image_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkImageView view_ = VK_NULL_HANDLE;
    VkExtent2D eye_{};
    VkFormat format_ = VK_FORMAT_UNDEFINED;
};

}  // namespace preskin::viewer
