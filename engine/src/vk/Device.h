// The small Vulkan core: instance, physical-device choice, device and queue, debug messenger,
// memory types, and one-shot command submission. Function pointers come from volk; device-level
// calls go through the loader's trampolines (volkLoadInstance), so several devices may coexist in one process.
#pragma once

#include <preskin/Context.h>

#include <volk.h>

#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace preskin::vk {

class Device {
public:
    static std::unique_ptr<Device> create(const ContextDesc& desc);
    static std::unique_ptr<Device> wrap(const HostVulkan& host);
    static std::vector<DeviceInfo> enumerate();
    ~Device();
    Device(const Device&) = delete;
    Device& operator=(const Device&) = delete;

    VkInstance instance() const { return instance_; }
    VkPhysicalDevice physicalDevice() const { return physicalDevice_; }
    VkDevice device() const { return device_; }
    VkQueue queue() const { return queue_; }
    uint32_t queueFamilyIndex() const { return queueFamily_; }
    const VkPhysicalDeviceProperties& properties() const { return properties_; }
    bool timestampsSupported() const { return timestampValidBits_ > 0; }
    float timestampPeriodNs() const { return properties_.limits.timestampPeriod; }
    // Views one multiview render pass may draw (VkPhysicalDeviceMultiviewProperties).
    uint32_t maxMultiviewViews() const { return maxMultiviewViews_; }
    // Sample counts usable for a colour target together with D32 depth.
    VkSampleCountFlags msaaSampleCounts() const {
        return properties_.limits.framebufferColorSampleCounts & properties_.limits.framebufferDepthSampleCounts;
    }
    // The alphaToOne feature is enabled (never on a host's device: its features are unknown).
    bool alphaToOne() const { return alphaToOne_; }
    // The independentBlend feature is enabled (likewise never on a host's device).
    bool independentBlend() const { return independentBlend_; }
    // Vertex shaders may write gl_Layer (the Vulkan 1.2 shaderOutputLayer feature is enabled;
    // on a host's device when the host says so in HostVulkan).
    bool shaderOutputLayer() const { return shaderOutputLayer_; }
    // The multiview clipping probe's result, once it ran (render/MultiviewProbe.h).
    std::optional<bool> multiviewClipping() const {
        std::lock_guard lock(probeMutex_);
        return multiviewClipping_;
    }
    void setMultiviewClipping(bool works) const {
        std::lock_guard lock(probeMutex_);
        multiviewClipping_ = works;
    }

    // A memory type that has every `required` flag (and `preferred` ones when possible).
    uint32_t findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags required,
                            VkMemoryPropertyFlags preferred = 0) const;
    bool supportsFormat(VkFormat format, VkFormatFeatureFlags2 optimalFeatures) const;
    // Records commands into a transient command buffer, submits, and waits for completion.
    void submitAndWait(const std::function<void(VkCommandBuffer)>& record) const;

    uint32_t validationMessageCount() const;
    std::vector<std::string> validationMessages() const;
    void recordValidationMessage(const std::string& message);

private:
    Device() = default;
    void initializeDevice(const ContextDesc& desc);
    void loadProperties();

    bool ownsHandles_ = false;
    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    // Kept per device: volk's global pointers follow the most recently created instance.
    PFN_vkDestroyDebugUtilsMessengerEXT destroyMessenger_ = nullptr;
    VkPhysicalDevice physicalDevice_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    uint32_t queueFamily_ = 0;
    uint32_t maxMultiviewViews_ = 1;
    bool alphaToOne_ = false;
    bool independentBlend_ = false;
    bool shaderOutputLayer_ = false;
    mutable std::mutex probeMutex_;
    mutable std::optional<bool> multiviewClipping_;
    uint32_t timestampValidBits_ = 0;
    VkPhysicalDeviceProperties properties_{};
    VkPhysicalDeviceMemoryProperties memoryProperties_{};
    VkCommandPool transientPool_ = VK_NULL_HANDLE;
    mutable std::mutex submitMutex_;

    mutable std::mutex messageMutex_;
    std::vector<std::string> messages_;
};

}  // namespace preskin::vk
