// Public face of the Vulkan core (see vk/Device.h).
#include <preskin/Context.h>

#include "vk/Device.h"

#include <fmt/core.h>

namespace preskin {

Context::Context(std::unique_ptr<vk::Device> device) : device_(std::move(device)) {}
Context::~Context() = default;

std::unique_ptr<Context> Context::create(const ContextDesc& desc) {
    return std::unique_ptr<Context>(new Context(vk::Device::create(desc)));
}

std::unique_ptr<Context> Context::wrap(const HostVulkan& host) {
    return std::unique_ptr<Context>(new Context(vk::Device::wrap(host)));
}

std::vector<DeviceInfo> Context::listDevices() { return vk::Device::enumerate(); }

VkInstance Context::instance() const { return device_->instance(); }
VkPhysicalDevice Context::physicalDevice() const { return device_->physicalDevice(); }
VkDevice Context::device() const { return device_->device(); }
VkQueue Context::queue() const { return device_->queue(); }
uint32_t Context::queueFamilyIndex() const { return device_->queueFamilyIndex(); }
std::string Context::deviceName() const { return device_->properties().deviceName; }
std::string Context::driverDescription() const {
    VkPhysicalDeviceDriverProperties driver{};
    driver.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES;
    VkPhysicalDeviceProperties2 properties{};
    properties.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2;
    properties.pNext = &driver;
    vkGetPhysicalDeviceProperties2(device_->physicalDevice(), &properties);
    const uint32_t api = properties.properties.apiVersion;
    return fmt::format("{} {} (driver version 0x{:x}, Vulkan {}.{}.{})", driver.driverName, driver.driverInfo,
                       properties.properties.driverVersion, VK_API_VERSION_MAJOR(api), VK_API_VERSION_MINOR(api),
                       VK_API_VERSION_PATCH(api));
}
bool Context::isSoftwareDevice() const { return device_->properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU; }
std::vector<uint32_t> Context::msaaSampleCounts() const {
    std::vector<uint32_t> counts;
    for (uint32_t n = 1; n <= 64; n *= 2)
        if (device_->msaaSampleCounts() & n) counts.push_back(n);
    return counts;
}
uint32_t Context::validationMessageCount() const { return device_->validationMessageCount(); }
std::vector<std::string> Context::validationMessages() const { return device_->validationMessages(); }
void Context::waitIdle() const { vkDeviceWaitIdle(device_->device()); }

}  // namespace preskin
