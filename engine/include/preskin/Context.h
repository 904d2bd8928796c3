// The Vulkan context preskin renders with: either one it creates (instance, device, queue) or
// one a host engine hands over. Requirements on the device either way: Vulkan 1.3 with
// dynamicRendering, synchronization2, maintenance4 and multiview enabled, and a queue with
// graphics and compute.
#pragma once

#include <preskin/Export.h>

#include <vulkan/vulkan_core.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace preskin {

namespace vk {
class Device;
}

struct ContextDesc {
    // Enables VK_LAYER_KHRONOS_validation and a debug messenger. Every warning or error it
    // reports is printed and counted (Context::validationMessageCount).
    bool validation = false;
    // Which physical device: "" picks the best (discrete > integrated > virtual > CPU);
    // a number is an index into Context::listDevices(); anything else matches a substring
    // of the device name (e.g. "llvmpipe").
    std::string device;
    // Extra instance extensions (for example those GLFW needs for a surface).
    std::vector<std::string> instanceExtensions;
    // Extra device extensions (for example VK_KHR_swapchain).
    std::vector<std::string> deviceExtensions;
};

// What a host engine hands over when preskin should run on its device. The host keeps
// ownership; the Context never destroys these handles. The device must have Vulkan 1.3
// dynamicRendering, synchronization2 and maintenance4 (compute stages size their workgroups with
// specialization constants; every 1.3 device supports it) and Vulkan 1.1 multiview enabled.
struct HostVulkan {
    PFN_vkGetInstanceProcAddr getInstanceProcAddr = nullptr;
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t queueFamilyIndex = 0;
    // The host enabled Vulkan 1.2 shaderOutputLayer: stereo can then fall back to instanced
    // layered drawing on devices whose multiview is unsound (EyeDrawing in <preskin/Renderer.h>).
    bool shaderOutputLayerEnabled = false;
};

struct DeviceInfo {
    uint32_t index = 0;
    std::string name;
    std::string type;  // "discrete", "integrated", "virtual", "cpu", "other"
    uint32_t apiVersion = 0;
    bool suitable = false;  // Vulkan 1.3 with the features preskin needs
};

class PRESKIN_API Context {
public:
    // Creates an instance and a device. Throws preskin::Error when no suitable device exists.
    static std::unique_ptr<Context> create(const ContextDesc& desc = {});
    // Runs on a host's device (see HostVulkan).
    static std::unique_ptr<Context> wrap(const HostVulkan& host);
    // The physical devices visible to the Vulkan loader, in enumeration order.
    static std::vector<DeviceInfo> listDevices();

    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    VkInstance instance() const;
    VkPhysicalDevice physicalDevice() const;
    VkDevice device() const;
    VkQueue queue() const;
    uint32_t queueFamilyIndex() const;
    std::string deviceName() const;
    // The driver as it names itself (VkPhysicalDeviceDriverProperties: name and info), its
    // version number and the device's Vulkan version, e.g.
    // "NVIDIA 550.54.15 (driver version 0x89cd83c0, Vulkan 1.3.277)".
    std::string driverDescription() const;
    bool isSoftwareDevice() const;
    // The MSAA sample counts the device offers for a colour and depth target, ascending (1 first).
    std::vector<uint32_t> msaaSampleCounts() const;
    // Validation warnings and errors reported so far (0 when validation is off).
    uint32_t validationMessageCount() const;
    std::vector<std::string> validationMessages() const;
    void waitIdle() const;

private:
    friend struct ContextAccess;  // the library's own access to its Vulkan core
    explicit Context(std::unique_ptr<vk::Device> device);
    std::unique_ptr<vk::Device> device_;
};

}  // namespace preskin
