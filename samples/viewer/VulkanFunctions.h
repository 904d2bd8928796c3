// The Vulkan entry points the viewer calls itself (swapchain, frame sync, overlay render pass,
// screenshot readback), loaded through GLFW's vkGetInstanceProcAddr. libpreskin builds with
// VK_NO_PROTOTYPES (it keeps its own loader private), so the viewer resolves what it needs here:
// instance-level functions from the instance, device-level ones from the device.
// Limits: only the functions listed below; Dear ImGui's Vulkan backend links the loader itself.
#pragma once

#include <vulkan/vulkan_core.h>

namespace preskin::viewer {

#define PRESKIN_VIEWER_INSTANCE_FUNCTIONS(X)     \
    X(vkGetDeviceProcAddr)                       \
    X(vkDestroySurfaceKHR)                       \
    X(vkGetPhysicalDeviceSurfaceSupportKHR)      \
    X(vkGetPhysicalDeviceSurfaceCapabilitiesKHR) \
    X(vkGetPhysicalDeviceSurfaceFormatsKHR)      \
    X(vkGetPhysicalDeviceSurfacePresentModesKHR) \
    X(vkGetPhysicalDeviceMemoryProperties)

#define PRESKIN_VIEWER_DEVICE_FUNCTIONS(X) \
    X(vkDeviceWaitIdle)                    \
    X(vkCreateSwapchainKHR)                \
    X(vkDestroySwapchainKHR)               \
    X(vkGetSwapchainImagesKHR)             \
    X(vkAcquireNextImageKHR)               \
    X(vkQueuePresentKHR)                   \
    X(vkQueueSubmit2)                      \
    X(vkCreateImageView)                   \
    X(vkDestroyImageView)                  \
    X(vkCreateSemaphore)                   \
    X(vkDestroySemaphore)                  \
    X(vkCreateFence)                       \
    X(vkDestroyFence)                      \
    X(vkWaitForFences)                     \
    X(vkResetFences)                       \
    X(vkCreateCommandPool)                 \
    X(vkDestroyCommandPool)                \
    X(vkResetCommandPool)                  \
    X(vkAllocateCommandBuffers)            \
    X(vkBeginCommandBuffer)                \
    X(vkEndCommandBuffer)                  \
    X(vkCmdPipelineBarrier2)               \
    X(vkCmdCopyImageToBuffer)              \
    X(vkCmdBeginRenderPass)                \
    X(vkCmdEndRenderPass)                  \
    X(vkCreateRenderPass)                  \
    X(vkDestroyRenderPass)                 \
    X(vkCreateFramebuffer)                 \
    X(vkDestroyFramebuffer)                \
    X(vkCreateDescriptorPool)              \
    X(vkDestroyDescriptorPool)             \
    X(vkCreateBuffer)                      \
    X(vkDestroyBuffer)                     \
    X(vkGetBufferMemoryRequirements)       \
    X(vkAllocateMemory)                    \
    X(vkFreeMemory)                        \
    X(vkBindBufferMemory)                  \
    X(vkMapMemory)                         \
    X(vkUnmapMemory)                       \
    X(vkInvalidateMappedMemoryRanges)      \
    X(vkCreateImage)                       \
    X(vkDestroyImage)                      \
    X(vkGetImageMemoryRequirements)        \
    X(vkBindImageMemory)                   \
    X(vkCmdCopyImage)                      \
    X(vkCmdClearColorImage)

struct VulkanFunctions {
#define PRESKIN_VIEWER_DECLARE(name) PFN_##name name = nullptr;
    PRESKIN_VIEWER_INSTANCE_FUNCTIONS(PRESKIN_VIEWER_DECLARE)
    PRESKIN_VIEWER_DEVICE_FUNCTIONS(PRESKIN_VIEWER_DECLARE)
#undef PRESKIN_VIEWER_DECLARE

    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;

    // Resolves every function above; throws preskin::Error naming the first one missing.
    void load(VkInstance instance, VkPhysicalDevice physicalDevice, VkDevice device);
};

// Throws preskin::Error "<what>: <VkResult>" unless `result` is VK_SUCCESS.
void check(VkResult result, const char* what);

// One layout transition of the first `layers` layers of a colour image's first mip level.
void imageBarrier(const VulkanFunctions& vk, VkCommandBuffer cmd, VkImage image, uint32_t layers, VkImageLayout from,
                  VkImageLayout to, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                  VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess);

}  // namespace preskin::viewer
