// Swapchain creation and recreation (see Swapchain.h).
#include "Swapchain.h"

#include <preskin/Error.h>

#include <fmt/core.h>

#include <algorithm>

namespace preskin::viewer {

namespace {

bool isSrgb(VkFormat f) { return f == VK_FORMAT_B8G8R8A8_SRGB || f == VK_FORMAT_R8G8B8A8_SRGB; }

}  // namespace

const char* presentModeName(VkPresentModeKHR mode) {
    switch (mode) {
    case VK_PRESENT_MODE_FIFO_KHR: return "FIFO (vsync)";
    case VK_PRESENT_MODE_FIFO_RELAXED_KHR: return "FIFO relaxed";
    case VK_PRESENT_MODE_MAILBOX_KHR: return "MAILBOX";
    case VK_PRESENT_MODE_IMMEDIATE_KHR: return "IMMEDIATE";
    default: return "other";
    }
}

Swapchain::Swapchain(const VulkanFunctions& vk, VkSurfaceKHR surface, uint32_t queueFamilyIndex)
    : vk_(vk), surface_(surface) {
    VkBool32 supported = VK_FALSE;
    check(vk_.vkGetPhysicalDeviceSurfaceSupportKHR(vk_.physicalDevice, queueFamilyIndex, surface_, &supported),
          "vkGetPhysicalDeviceSurfaceSupportKHR");
    if (!supported) throw Error("Vulkan: the device's queue cannot present to this window");

    uint32_t count = 0;
    check(vk_.vkGetPhysicalDeviceSurfaceFormatsKHR(vk_.physicalDevice, surface_, &count, nullptr), "surface formats");
    std::vector<VkSurfaceFormatKHR> formats(count);
    check(vk_.vkGetPhysicalDeviceSurfaceFormatsKHR(vk_.physicalDevice, surface_, &count, formats.data()),
          "surface formats");
    if (formats.empty()) throw Error("Vulkan: the window surface offers no formats");
    const VkSurfaceFormatKHR* chosen = &formats.front();
    for (const VkSurfaceFormatKHR& f : formats)
        if (isSrgb(f.format) && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) {
            chosen = &f;
            break;
        }
    format_ = chosen->format;
    colorSpace_ = chosen->colorSpace;
    srgb_ = isSrgb(format_);

    check(vk_.vkGetPhysicalDeviceSurfacePresentModesKHR(vk_.physicalDevice, surface_, &count, nullptr),
          "present modes");
    modes_.resize(count);
    check(vk_.vkGetPhysicalDeviceSurfacePresentModesKHR(vk_.physicalDevice, surface_, &count, modes_.data()),
          "present modes");
}

Swapchain::~Swapchain() {
    destroyImages();
    if (swapchain_) vk_.vkDestroySwapchainKHR(vk_.device, swapchain_, nullptr);
}

bool Swapchain::canDisableVsync() const {
    return std::any_of(modes_.begin(), modes_.end(), [](VkPresentModeKHR m) {
        return m == VK_PRESENT_MODE_MAILBOX_KHR || m == VK_PRESENT_MODE_IMMEDIATE_KHR;
    });
}

void Swapchain::destroyImages() {
    for (VkImageView v : views_) vk_.vkDestroyImageView(vk_.device, v, nullptr);
    for (VkSemaphore s : renderFinished_) vk_.vkDestroySemaphore(vk_.device, s, nullptr);
    views_.clear();
    renderFinished_.clear();
    images_.clear();
}

bool Swapchain::recreate(VkExtent2D sizePx, bool vsync) {
    VkSurfaceCapabilitiesKHR caps{};
    check(vk_.vkGetPhysicalDeviceSurfaceCapabilitiesKHR(vk_.physicalDevice, surface_, &caps), "surface capabilities");
    VkExtent2D extent = caps.currentExtent;
    if (extent.width == UINT32_MAX) {  // the surface takes the swapchain's size
        extent.width = std::clamp(sizePx.width, caps.minImageExtent.width, caps.maxImageExtent.width);
        extent.height = std::clamp(sizePx.height, caps.minImageExtent.height, caps.maxImageExtent.height);
    }
    destroyImages();
    if (extent.width == 0 || extent.height == 0 || sizePx.width == 0 || sizePx.height == 0) {
        if (swapchain_) vk_.vkDestroySwapchainKHR(vk_.device, swapchain_, nullptr);
        swapchain_ = VK_NULL_HANDLE;
        return false;
    }

    presentMode_ = VK_PRESENT_MODE_FIFO_KHR;  // always supported
    if (!vsync) {
        for (VkPresentModeKHR wanted : {VK_PRESENT_MODE_MAILBOX_KHR, VK_PRESENT_MODE_IMMEDIATE_KHR})
            if (std::find(modes_.begin(), modes_.end(), wanted) != modes_.end()) {
                presentMode_ = wanted;
                break;
            }
    }
    uint32_t imageCount = std::max(caps.minImageCount + 1, 3u);
    if (caps.maxImageCount > 0) imageCount = std::min(imageCount, caps.maxImageCount);
    transferSource_ = (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT) != 0;
    transferDestination_ = (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT) != 0;

    VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
    info.surface = surface_;
    info.minImageCount = imageCount;
    info.imageFormat = format_;
    info.imageColorSpace = colorSpace_;
    info.imageExtent = extent;
    info.imageArrayLayers = 1;
    info.imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
    if (transferSource_) info.imageUsage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    if (transferDestination_) info.imageUsage |= VK_IMAGE_USAGE_TRANSFER_DST_BIT;  // the stereo preview's copies
    info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.preTransform = (caps.supportedTransforms & VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR)
        ? VK_SURFACE_TRANSFORM_IDENTITY_BIT_KHR
        : caps.currentTransform;
    info.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
    for (VkCompositeAlphaFlagBitsKHR a :
         {VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR, VK_COMPOSITE_ALPHA_INHERIT_BIT_KHR,
          VK_COMPOSITE_ALPHA_PRE_MULTIPLIED_BIT_KHR, VK_COMPOSITE_ALPHA_POST_MULTIPLIED_BIT_KHR})
        if (caps.supportedCompositeAlpha & a) {
            info.compositeAlpha = a;
            break;
        }
    info.presentMode = presentMode_;
    info.clipped = VK_TRUE;
    info.oldSwapchain = swapchain_;
    VkSwapchainKHR created = VK_NULL_HANDLE;
    check(vk_.vkCreateSwapchainKHR(vk_.device, &info, nullptr, &created), "vkCreateSwapchainKHR");
    if (swapchain_) vk_.vkDestroySwapchainKHR(vk_.device, swapchain_, nullptr);
    swapchain_ = created;
    extent_ = extent;

    uint32_t count = 0;
    check(vk_.vkGetSwapchainImagesKHR(vk_.device, swapchain_, &count, nullptr), "vkGetSwapchainImagesKHR");
    images_.resize(count);
    check(vk_.vkGetSwapchainImagesKHR(vk_.device, swapchain_, &count, images_.data()), "vkGetSwapchainImagesKHR");
    for (VkImage image : images_) {
        VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        viewInfo.image = image;
        viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
        viewInfo.format = format_;
        viewInfo.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        VkImageView view = VK_NULL_HANDLE;
        check(vk_.vkCreateImageView(vk_.device, &viewInfo, nullptr, &view), "vkCreateImageView");
        views_.push_back(view);
        VkSemaphoreCreateInfo semaphoreInfo{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
        VkSemaphore semaphore = VK_NULL_HANDLE;
        check(vk_.vkCreateSemaphore(vk_.device, &semaphoreInfo, nullptr, &semaphore), "vkCreateSemaphore");
        renderFinished_.push_back(semaphore);
    }
    return true;
}

}  // namespace preskin::viewer
