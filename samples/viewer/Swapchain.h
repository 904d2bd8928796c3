// The window's swapchain: surface format (an sRGB 8-bit format, so the renderer's tone-mapped
// output is display-encoded by the hardware), present mode (FIFO for vsync, else MAILBOX or
// IMMEDIATE when the surface offers them), images with views, and one "rendering finished"
// semaphore per image (a present may still wait on it until that image is acquired again).
// Recreated on resize, on an out-of-date or suboptimal present and on a vsync change.
// Limits: one queue that both renders and presents; no HDR or wide-gamut surfaces.
#pragma once

#include "VulkanFunctions.h"

#include <cstdint>
#include <string>
#include <vector>

namespace preskin::viewer {

class Swapchain {
public:
    Swapchain(const VulkanFunctions& vk, VkSurfaceKHR surface, uint32_t queueFamilyIndex);
    ~Swapchain();
    Swapchain(const Swapchain&) = delete;
    Swapchain& operator=(const Swapchain&) = delete;

    // (Re)creates the swapchain for a framebuffer of `sizePx`; the device must be idle.
    // Returns false (and keeps no swapchain) when the surface has no area, e.g. minimised.
    bool recreate(VkExtent2D sizePx, bool vsync);
    bool valid() const { return swapchain_ != VK_NULL_HANDLE; }

    VkSwapchainKHR handle() const { return swapchain_; }
    VkFormat format() const { return format_; }
    VkExtent2D extent() const { return extent_; }
    VkPresentModeKHR presentMode() const { return presentMode_; }
    bool srgb() const { return srgb_; }
    // Whether the images can be copied from (screenshots).
    bool transferSource() const { return transferSource_; }
    bool transferDestination() const { return transferDestination_; }
    uint32_t imageCount() const { return static_cast<uint32_t>(images_.size()); }
    VkImage image(uint32_t i) const { return images_[i]; }
    VkImageView view(uint32_t i) const { return views_[i]; }
    VkSemaphore renderFinished(uint32_t i) const { return renderFinished_[i]; }
    // Whether a non-FIFO mode exists, i.e. whether vsync can be switched off.
    bool canDisableVsync() const;

private:
    void destroyImages();

    const VulkanFunctions& vk_;
    VkSurfaceKHR surface_;
    VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    VkColorSpaceKHR colorSpace_ = VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
    VkExtent2D extent_{};
    VkPresentModeKHR presentMode_ = VK_PRESENT_MODE_FIFO_KHR;
    bool srgb_ = false;
    bool transferSource_ = false;
    bool transferDestination_ = false;
    std::vector<VkPresentModeKHR> modes_;
    std::vector<VkImage> images_;
    std::vector<VkImageView> views_;
    std::vector<VkSemaphore> renderFinished_;
};

const char* presentModeName(VkPresentModeKHR mode);

}  // namespace preskin::viewer
