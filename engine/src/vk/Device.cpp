#include "vk/Device.h"

#include "vk/Check.h"

#include <fmt/core.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <limits>

namespace preskin::vk {

const char* resultName(VkResult result) {
    switch (result) {
    case VK_SUCCESS: return "VK_SUCCESS";
    case VK_NOT_READY: return "VK_NOT_READY";
    case VK_TIMEOUT: return "VK_TIMEOUT";
    case VK_INCOMPLETE: return "VK_INCOMPLETE";
    case VK_ERROR_OUT_OF_HOST_MEMORY: return "VK_ERROR_OUT_OF_HOST_MEMORY";
    case VK_ERROR_OUT_OF_DEVICE_MEMORY: return "VK_ERROR_OUT_OF_DEVICE_MEMORY";
    case VK_ERROR_INITIALIZATION_FAILED: return "VK_ERROR_INITIALIZATION_FAILED";
    case VK_ERROR_DEVICE_LOST: return "VK_ERROR_DEVICE_LOST";
    case VK_ERROR_MEMORY_MAP_FAILED: return "VK_ERROR_MEMORY_MAP_FAILED";
    case VK_ERROR_LAYER_NOT_PRESENT: return "VK_ERROR_LAYER_NOT_PRESENT";
    case VK_ERROR_EXTENSION_NOT_PRESENT: return "VK_ERROR_EXTENSION_NOT_PRESENT";
    case VK_ERROR_FEATURE_NOT_PRESENT: return "VK_ERROR_FEATURE_NOT_PRESENT";
    case VK_ERROR_INCOMPATIBLE_DRIVER: return "VK_ERROR_INCOMPATIBLE_DRIVER";
    case VK_ERROR_TOO_MANY_OBJECTS: return "VK_ERROR_TOO_MANY_OBJECTS";
    case VK_ERROR_FORMAT_NOT_SUPPORTED: return "VK_ERROR_FORMAT_NOT_SUPPORTED";
    case VK_ERROR_OUT_OF_DATE_KHR: return "VK_ERROR_OUT_OF_DATE_KHR";
    case VK_SUBOPTIMAL_KHR: return "VK_SUBOPTIMAL_KHR";
    case VK_ERROR_SURFACE_LOST_KHR: return "VK_ERROR_SURFACE_LOST_KHR";
    default: return "VkResult(unknown)";
    }
}

void throwVkError(VkResult result, const char* call, const char* file, int line) {
    throw Error(fmt::format("Vulkan: {} failed with {} ({}:{})", call, resultName(result), file, line));
}

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

VKAPI_ATTR VkBool32 VKAPI_CALL debugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                             VkDebugUtilsMessageTypeFlagsEXT /*types*/,
                                             const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    const char* level = (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) ? "error" : "warning";
    const std::string message = fmt::format("validation {}: {}", level, data->pMessage ? data->pMessage : "");
    std::fprintf(stderr, "preskin: %s\n", message.c_str());
    static_cast<Device*>(user)->recordValidationMessage(message);
    return VK_FALSE;
}

const char* typeName(VkPhysicalDeviceType type) {
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
    default: return "other";
    }
}

int typeRank(VkPhysicalDeviceType type) {
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 1;
    default: return 0;
    }
}

// The queue family with graphics and compute, or UINT32_MAX.
uint32_t findQueueFamily(VkPhysicalDevice physical) {
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, families.data());
    for (uint32_t i = 0; i < count; ++i) {
        const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
        if ((families[i].queueFlags & need) == need) return i;
    }
    return std::numeric_limits<uint32_t>::max();
}

bool isSuitable(VkPhysicalDevice physical) {
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(physical, &props);
    if (props.apiVersion < VK_API_VERSION_1_3) return false;
    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceVulkan11Features f11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES, &f13};
    VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f11, {}};
    vkGetPhysicalDeviceFeatures2(physical, &f2);
    return f13.dynamicRendering && f13.synchronization2 && f11.multiview &&
        findQueueFamily(physical) != std::numeric_limits<uint32_t>::max();
}

void initializeLoader() {
    static const VkResult result = volkInitialize();
    if (result != VK_SUCCESS)
        throw Error(
            "Vulkan: the Vulkan loader (libvulkan.so.1) was not found; install libvulkan1 and a driver "
            "(mesa-vulkan-drivers for lavapipe)");
}

std::vector<VkPhysicalDevice> physicalDevices(VkInstance instance) {
    uint32_t count = 0;
    PRESKIN_VK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
    std::vector<VkPhysicalDevice> devices(count);
    PRESKIN_VK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
    return devices;
}

bool hasLayer(const char* name) {
    uint32_t count = 0;
    vkEnumerateInstanceLayerProperties(&count, nullptr);
    std::vector<VkLayerProperties> layers(count);
    vkEnumerateInstanceLayerProperties(&count, layers.data());
    return std::any_of(layers.begin(), layers.end(),
                       [&](const VkLayerProperties& l) { return std::strcmp(l.layerName, name) == 0; });
}

VkInstance createInstance(const std::vector<const char*>& layers, const std::vector<const char*>& extensions,
                          const void* next) {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "preskin";
    app.pEngineName = "preskin";
    app.apiVersion = VK_API_VERSION_1_3;
    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pNext = next;
    info.pApplicationInfo = &app;
    info.enabledLayerCount = static_cast<uint32_t>(layers.size());
    info.ppEnabledLayerNames = layers.data();
    info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    VkInstance instance = VK_NULL_HANDLE;
    PRESKIN_VK(vkCreateInstance(&info, nullptr, &instance));
    return instance;
}

}  // namespace

std::vector<DeviceInfo> Device::enumerate() {
    initializeLoader();
    const VkInstance instance = createInstance({}, {}, nullptr);
    volkLoadInstance(instance);
    std::vector<DeviceInfo> result;
    try {
        const auto devices = physicalDevices(instance);
        for (uint32_t i = 0; i < devices.size(); ++i) {
            VkPhysicalDeviceProperties props;
            vkGetPhysicalDeviceProperties(devices[i], &props);
            result.push_back(
                {i, props.deviceName, typeName(props.deviceType), props.apiVersion, isSuitable(devices[i])});
        }
    } catch (...) {
        vkDestroyInstance(instance, nullptr);
        throw;
    }
    vkDestroyInstance(instance, nullptr);
    return result;
}

std::unique_ptr<Device> Device::create(const ContextDesc& desc) {
    initializeLoader();
    std::unique_ptr<Device> self(new Device());
    self->ownsHandles_ = true;

    std::vector<const char*> layers;
    std::vector<const char*> extensions;
    for (const auto& e : desc.instanceExtensions) extensions.push_back(e.c_str());
    VkDebugUtilsMessengerCreateInfoEXT messengerInfo{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messengerInfo.messageSeverity =
        VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messengerInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
        VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    messengerInfo.pfnUserCallback = debugCallback;
    messengerInfo.pUserData = self.get();
    // Synchronization validation catches missing or wrong barriers, which lavapipe forgives.
    const VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = enables;
    features.pNext = &messengerInfo;
    const void* next = nullptr;
    if (desc.validation) {
        if (!hasLayer(kValidationLayer))
            throw Error(
                fmt::format("Vulkan: validation was requested but {} is not installed "
                            "(Debian package vulkan-validationlayers)",
                            kValidationLayer));
        layers.push_back(kValidationLayer);
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
        next = &features;
    }
    self->instance_ = createInstance(layers, extensions, next);
    volkLoadInstance(self->instance_);
    if (desc.validation) {
        PRESKIN_VK(vkCreateDebugUtilsMessengerEXT(self->instance_, &messengerInfo, nullptr, &self->messenger_));
        self->destroyMessenger_ = vkDestroyDebugUtilsMessengerEXT;
    }
    self->initializeDevice(desc);
    return self;
}

void Device::initializeDevice(const ContextDesc& desc) {
    const auto devices = physicalDevices(instance_);
    if (devices.empty()) throw Error("Vulkan: no physical device found (install mesa-vulkan-drivers for lavapipe)");

    VkPhysicalDevice chosen = VK_NULL_HANDLE;
    if (desc.device.empty()) {
        int bestRank = -1;
        for (VkPhysicalDevice d : devices) {
            if (!isSuitable(d)) continue;
            VkPhysicalDeviceProperties props;
            vkGetPhysicalDeviceProperties(d, &props);
            if (typeRank(props.deviceType) > bestRank) {
                bestRank = typeRank(props.deviceType);
                chosen = d;
            }
        }
        if (!chosen) throw Error("Vulkan: no device supports Vulkan 1.3 with dynamic rendering and synchronization2");
    } else {
        const bool numeric =
            std::all_of(desc.device.begin(), desc.device.end(), [](char c) { return c >= '0' && c <= '9'; });
        for (size_t i = 0; i < devices.size() && !chosen; ++i) {
            VkPhysicalDeviceProperties props;
            vkGetPhysicalDeviceProperties(devices[i], &props);
            const bool match = numeric ? std::to_string(i) == desc.device
                                       : std::string(props.deviceName).find(desc.device) != std::string::npos;
            if (!match) continue;
            if (!isSuitable(devices[i]))
                throw Error(fmt::format("--device {}: '{}' lacks Vulkan 1.3 dynamic rendering / synchronization2",
                                        desc.device, props.deviceName));
            chosen = devices[i];
        }
        if (!chosen) {
            std::string names;
            for (size_t i = 0; i < devices.size(); ++i) {
                VkPhysicalDeviceProperties props;
                vkGetPhysicalDeviceProperties(devices[i], &props);
                names += fmt::format("{}{}: {}", i ? ", " : "", i, props.deviceName);
            }
            throw Error(fmt::format("--device {}: no such device (available: {})", desc.device, names));
        }
    }
    physicalDevice_ = chosen;
    queueFamily_ = findQueueFamily(chosen);

    std::vector<const char*> extensions;
    for (const auto& e : desc.deviceExtensions) extensions.push_back(e.c_str());
    VkPhysicalDeviceFeatures supported;
    vkGetPhysicalDeviceFeatures(chosen, &supported);
    VkPhysicalDeviceVulkan13Features supported13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceFeatures2 supported2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &supported13, {}};
    vkGetPhysicalDeviceFeatures2(chosen, &supported2);
    VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    f13.dynamicRendering = VK_TRUE;
    f13.synchronization2 = VK_TRUE;
    // Required by Vulkan 1.3; lets compute shaders size workgroups with specialization constants.
    f13.maintenance4 = supported13.maintenance4;
    // Every eye of a view is drawn in one multiview pass (mono too, as one view).
    // Or, where multiview is unsound, as instances writing gl_Layer (render/MultiviewProbe.h).
    VkPhysicalDeviceVulkan12Features supported12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceFeatures2 query12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &supported12, {}};
    vkGetPhysicalDeviceFeatures2(chosen, &query12);
    VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES, &f13};
    f12.shaderOutputLayer = supported12.shaderOutputLayer;
    shaderOutputLayer_ = supported12.shaderOutputLayer == VK_TRUE;
    VkPhysicalDeviceVulkan11Features f11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES, &f12};
    f11.multiview = VK_TRUE;
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &f11, {}};
    features.features.samplerAnisotropy = supported.samplerAnisotropy;
    features.features.fragmentStoresAndAtomics = supported.fragmentStoresAndAtomics;
    // Alpha-to-coverage writes alpha 1 to the target where the device can.
    features.features.alphaToOne = supported.alphaToOne;
    alphaToOne_ = supported.alphaToOne == VK_TRUE;
    // The diffusion baselines' attachments blend and write differently (RenderSettings::diffusion).
    features.features.independentBlend = supported.independentBlend;
    independentBlend_ = supported.independentBlend == VK_TRUE;

    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queueInfo.queueFamilyIndex = queueFamily_;
    queueInfo.queueCount = 1;
    queueInfo.pQueuePriorities = &priority;
    VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    info.pNext = &features;
    info.queueCreateInfoCount = 1;
    info.pQueueCreateInfos = &queueInfo;
    info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    PRESKIN_VK(vkCreateDevice(chosen, &info, nullptr, &device_));
    vkGetDeviceQueue(device_, queueFamily_, 0, &queue_);
    loadProperties();
}

std::unique_ptr<Device> Device::wrap(const HostVulkan& host) {
    if (!host.getInstanceProcAddr || !host.instance || !host.physicalDevice || !host.device || !host.queue)
        throw Error("HostVulkan: getInstanceProcAddr, instance, physicalDevice, device and queue must all be set");
    volkInitializeCustom(host.getInstanceProcAddr);
    volkLoadInstance(host.instance);
    if (!isSuitable(host.physicalDevice))
        throw Error(
            "HostVulkan: the host's physical device lacks Vulkan 1.3 dynamic rendering / synchronization2 "
            "or multiview");
    std::unique_ptr<Device> self(new Device());
    self->ownsHandles_ = false;
    self->instance_ = host.instance;
    self->physicalDevice_ = host.physicalDevice;
    self->device_ = host.device;
    self->queue_ = host.queue;
    self->queueFamily_ = host.queueFamilyIndex;
    self->shaderOutputLayer_ = host.shaderOutputLayerEnabled;
    self->loadProperties();
    return self;
}

void Device::loadProperties() {
    VkPhysicalDeviceMultiviewProperties multiview{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MULTIVIEW_PROPERTIES};
    VkPhysicalDeviceProperties2 properties2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &multiview, {}};
    vkGetPhysicalDeviceProperties2(physicalDevice_, &properties2);
    properties_ = properties2.properties;
    maxMultiviewViews_ = std::max(multiview.maxMultiviewViewCount, 1u);
    vkGetPhysicalDeviceMemoryProperties(physicalDevice_, &memoryProperties_);
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice_, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice_, &count, families.data());
    timestampValidBits_ = queueFamily_ < count ? families[queueFamily_].timestampValidBits : 0;
    VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    poolInfo.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT | VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    poolInfo.queueFamilyIndex = queueFamily_;
    PRESKIN_VK(vkCreateCommandPool(device_, &poolInfo, nullptr, &transientPool_));
}

Device::~Device() {
    if (device_) {
        vkDeviceWaitIdle(device_);
        if (transientPool_) vkDestroyCommandPool(device_, transientPool_, nullptr);
    }
    if (!ownsHandles_) return;
    if (device_) vkDestroyDevice(device_, nullptr);
    if (messenger_) destroyMessenger_(instance_, messenger_, nullptr);
    if (instance_) vkDestroyInstance(instance_, nullptr);
}

uint32_t Device::findMemoryType(uint32_t typeBits, VkMemoryPropertyFlags required,
                                VkMemoryPropertyFlags preferred) const {
    uint32_t fallback = std::numeric_limits<uint32_t>::max();
    for (uint32_t i = 0; i < memoryProperties_.memoryTypeCount; ++i) {
        if (!(typeBits & (1u << i))) continue;
        const VkMemoryPropertyFlags flags = memoryProperties_.memoryTypes[i].propertyFlags;
        if ((flags & required) != required) continue;
        if ((flags & preferred) == preferred) return i;
        if (fallback == std::numeric_limits<uint32_t>::max()) fallback = i;
    }
    if (fallback == std::numeric_limits<uint32_t>::max())
        throw Error(fmt::format("Vulkan: no memory type with flags {:#x} among type bits {:#x}", required, typeBits));
    return fallback;
}

bool Device::supportsFormat(VkFormat format, VkFormatFeatureFlags2 optimalFeatures) const {
    VkFormatProperties3 props3{VK_STRUCTURE_TYPE_FORMAT_PROPERTIES_3};
    VkFormatProperties2 props{VK_STRUCTURE_TYPE_FORMAT_PROPERTIES_2, &props3, {}};
    vkGetPhysicalDeviceFormatProperties2(physicalDevice_, format, &props);
    return (props3.optimalTilingFeatures & optimalFeatures) == optimalFeatures;
}

void Device::submitAndWait(const std::function<void(VkCommandBuffer)>& record) const {
    std::lock_guard lock(submitMutex_);
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = transientPool_;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    PRESKIN_VK(vkAllocateCommandBuffers(device_, &alloc, &cmd));
    VkFence fence = VK_NULL_HANDLE;
    auto cleanup = [&] {
        if (fence) vkDestroyFence(device_, fence, nullptr);
        vkFreeCommandBuffers(device_, transientPool_, 1, &cmd);
    };
    try {
        VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
        PRESKIN_VK(vkBeginCommandBuffer(cmd, &begin));
        record(cmd);
        PRESKIN_VK(vkEndCommandBuffer(cmd));
        VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        PRESKIN_VK(vkCreateFence(device_, &fenceInfo, nullptr, &fence));
        VkCommandBufferSubmitInfo cmdInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
        cmdInfo.commandBuffer = cmd;
        VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
        submit.commandBufferInfoCount = 1;
        submit.pCommandBufferInfos = &cmdInfo;
        PRESKIN_VK(vkQueueSubmit2(queue_, 1, &submit, fence));
        PRESKIN_VK(vkWaitForFences(device_, 1, &fence, VK_TRUE, std::numeric_limits<uint64_t>::max()));
    } catch (...) {
        cleanup();
        throw;
    }
    cleanup();
}

uint32_t Device::validationMessageCount() const {
    std::lock_guard lock(messageMutex_);
    return static_cast<uint32_t>(messages_.size());
}

std::vector<std::string> Device::validationMessages() const {
    std::lock_guard lock(messageMutex_);
    return messages_;
}

void Device::recordValidationMessage(const std::string& message) {
    std::lock_guard lock(messageMutex_);
    messages_.push_back(message);
}

}  // namespace preskin::vk
