// Loads the viewer's Vulkan entry points (see VulkanFunctions.h).
#include "VulkanFunctions.h"

#include <preskin/Error.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <fmt/core.h>

namespace preskin::viewer {

void VulkanFunctions::load(VkInstance inst, VkPhysicalDevice physical, VkDevice dev) {
    instance = inst;
    physicalDevice = physical;
    device = dev;
    auto fromInstance = [&](const char* name) {
        const GLFWvkproc f = glfwGetInstanceProcAddress(instance, name);
        if (!f) throw Error(fmt::format("Vulkan: the loader has no {}", name));
        return f;
    };
#define PRESKIN_VIEWER_LOAD_INSTANCE(name) name = reinterpret_cast<PFN_##name>(fromInstance(#name));
    PRESKIN_VIEWER_INSTANCE_FUNCTIONS(PRESKIN_VIEWER_LOAD_INSTANCE)
#undef PRESKIN_VIEWER_LOAD_INSTANCE
    auto fromDevice = [&](const char* name) {
        const PFN_vkVoidFunction f = vkGetDeviceProcAddr(device, name);
        if (!f) throw Error(fmt::format("Vulkan: the device has no {} (is VK_KHR_swapchain enabled?)", name));
        return f;
    };
#define PRESKIN_VIEWER_LOAD_DEVICE(name) name = reinterpret_cast<PFN_##name>(fromDevice(#name));
    PRESKIN_VIEWER_DEVICE_FUNCTIONS(PRESKIN_VIEWER_LOAD_DEVICE)
#undef PRESKIN_VIEWER_LOAD_DEVICE
}

void check(VkResult result, const char* what) {
    if (result != VK_SUCCESS) throw Error(fmt::format("{}: VkResult {}", what, static_cast<int>(result)));
}

void imageBarrier(const VulkanFunctions& vk, VkCommandBuffer cmd, VkImage image, uint32_t layers, VkImageLayout from,
                  VkImageLayout to, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                  VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
    VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    b.srcStageMask = srcStage;
    b.srcAccessMask = srcAccess;
    b.dstStageMask = dstStage;
    b.dstAccessMask = dstAccess;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, layers};
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.imageMemoryBarrierCount = 1;
    dep.pImageMemoryBarriers = &b;
    vk.vkCmdPipelineBarrier2(cmd, &dep);
}

}  // namespace preskin::viewer
