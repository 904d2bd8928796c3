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

}  // namespace preskin::viewer
