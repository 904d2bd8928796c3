// The Vulkan set-up any host already has, kept apart from what embedding preskin takes (main.cpp):
// an instance and a device with one graphics queue, memory, host-visible buffers, images and
// views, sampled textures with a linear mip chain, one-shot command buffers, image barriers.
#pragma once

#include <vulkan/vulkan.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace host {

// Levels of a full mip chain of a width x height image.
inline uint32_t mipCount(uint32_t width, uint32_t height) {
    uint32_t mips = 1;
    while (std::max(width, height) >> mips) ++mips;
    return mips;
}

inline void check(VkResult r, const char* what) {
    if (r != VK_SUCCESS) throw std::runtime_error(std::string(what) + " failed (VkResult " + std::to_string(r) + ")");
}

class Gpu {
public:
    explicit Gpu(const std::string& deviceName) {
        VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
        app.pApplicationName = "preskin-host";
        app.apiVersion = VK_API_VERSION_1_3;
        VkInstanceCreateInfo ii{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
        ii.pApplicationInfo = &app;
        check(vkCreateInstance(&ii, nullptr, &instance), "vkCreateInstance");
        uint32_t count = 0;
        vkEnumeratePhysicalDevices(instance, &count, nullptr);
        std::vector<VkPhysicalDevice> devices(count);
        vkEnumeratePhysicalDevices(instance, &count, devices.data());
        for (VkPhysicalDevice d : devices) {
            VkPhysicalDeviceProperties p;
            vkGetPhysicalDeviceProperties(d, &p);
            if (p.apiVersion >= VK_API_VERSION_1_3 && std::string(p.deviceName).find(deviceName) != std::string::npos) {
                physical = d;
                break;
            }
        }
        if (!physical) throw std::runtime_error("no Vulkan 1.3 device named like '" + deviceName + "'");
        vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, nullptr);
        std::vector<VkQueueFamilyProperties> families(count);
        vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, families.data());
        while (family < count && !(families[family].queueFlags & VK_QUEUE_GRAPHICS_BIT)) ++family;
        const float priority = 1.0f;
        VkDeviceQueueCreateInfo qi{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
        qi.queueFamilyIndex = family;
        qi.queueCount = 1;
        qi.pQueuePriorities = &priority;
        // What the host's own passes use (dynamic rendering, synchronization2), and what preskin's
        // renderer needs besides on a device it is handed (Context::wrap): multiview, maintenance4.
        VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
        f13.dynamicRendering = VK_TRUE;
        f13.synchronization2 = VK_TRUE;
        f13.maintenance4 = VK_TRUE;  // every Vulkan 1.3 device has it; preskin's compute stages need it
        VkPhysicalDeviceVulkan11Features f11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES, &f13};
        f11.multiview = VK_TRUE;
        VkDeviceCreateInfo di{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
        di.pNext = &f11;
        di.queueCreateInfoCount = 1;
        di.pQueueCreateInfos = &qi;
        check(vkCreateDevice(physical, &di, nullptr, &device), "vkCreateDevice");
        vkGetDeviceQueue(device, family, 0, &queue);
        VkCommandPoolCreateInfo pi{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pi.queueFamilyIndex = family;
        check(vkCreateCommandPool(device, &pi, nullptr, &pool), "vkCreateCommandPool");
    }
    ~Gpu() {
        vkDeviceWaitIdle(device);
        for (auto it = cleanup.rbegin(); it != cleanup.rend(); ++it) (*it)();
        vkDestroyCommandPool(device, pool, nullptr);
        vkDestroyDevice(device, nullptr);
        vkDestroyInstance(instance, nullptr);
    }

    VkDeviceMemory allocate(VkMemoryRequirements req, VkMemoryPropertyFlags flags) {
        VkPhysicalDeviceMemoryProperties mp;
        vkGetPhysicalDeviceMemoryProperties(physical, &mp);
        uint32_t type = 0;
        while (type < mp.memoryTypeCount &&
               (!(req.memoryTypeBits & (1u << type)) || (mp.memoryTypes[type].propertyFlags & flags) != flags))
            ++type;
        VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        ai.allocationSize = req.size;
        ai.memoryTypeIndex = type;
        VkDeviceMemory memory;
        check(vkAllocateMemory(device, &ai, nullptr, &memory), "vkAllocateMemory");
        cleanup.push_back([this, memory] { vkFreeMemory(device, memory, nullptr); });
        return memory;
    }

    // A host-visible buffer holding `bytes` (copied in when given); returns its mapping.
    VkBuffer buffer(VkDeviceSize size, VkBufferUsageFlags usage, const void* bytes, void** mapped = nullptr) {
        VkBufferCreateInfo bi{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
        bi.size = size;
        bi.usage = usage;
        VkBuffer buffer;
        check(vkCreateBuffer(device, &bi, nullptr, &buffer), "vkCreateBuffer");
        cleanup.push_back([this, buffer] { vkDestroyBuffer(device, buffer, nullptr); });
        VkMemoryRequirements req;
        vkGetBufferMemoryRequirements(device, buffer, &req);
        VkDeviceMemory memory =
            allocate(req, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
        vkBindBufferMemory(device, buffer, memory, 0);
        void* p = nullptr;
        vkMapMemory(device, memory, 0, size, 0, &p);
        if (bytes) std::memcpy(p, bytes, size);
        if (mapped) *mapped = p;
        return buffer;
    }

    struct Image {
        VkImage image;
        VkImageView view;
    };
    Image image(VkFormat format, uint32_t width, uint32_t height, uint32_t mips, VkImageUsageFlags usage,
                VkImageAspectFlags aspect, VkImageViewType viewType = VK_IMAGE_VIEW_TYPE_2D) {
        VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
        ci.imageType = VK_IMAGE_TYPE_2D;
        ci.format = format;
        ci.extent = {width, height, 1};
        ci.mipLevels = mips;
        ci.arrayLayers = 1;
        ci.samples = VK_SAMPLE_COUNT_1_BIT;
        ci.usage = usage;
        Image out;
        check(vkCreateImage(device, &ci, nullptr, &out.image), "vkCreateImage");
        VkMemoryRequirements req;
        vkGetImageMemoryRequirements(device, out.image, &req);
        vkBindImageMemory(device, out.image, allocate(req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT), 0);
        VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        vi.image = out.image;
        vi.viewType = viewType;
        vi.format = format;
        vi.subresourceRange = {aspect, 0, mips, 0, 1};
        check(vkCreateImageView(device, &vi, nullptr, &out.view), "vkCreateImageView");
        cleanup.push_back([this, out] {
            vkDestroyImageView(device, out.view, nullptr);
            vkDestroyImage(device, out.image, nullptr);
        });
        return out;
    }

    void submit(const std::function<void(VkCommandBuffer)>& record) {
        VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        ai.commandPool = pool;
        ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        ai.commandBufferCount = 1;
        VkCommandBuffer cmd;
        check(vkAllocateCommandBuffers(device, &ai, &cmd), "vkAllocateCommandBuffers");
        VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        vkBeginCommandBuffer(cmd, &bi);
        record(cmd);
        vkEndCommandBuffer(cmd);
        VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        si.commandBufferCount = 1;
        si.pCommandBuffers = &cmd;
        check(vkQueueSubmit(queue, 1, &si, VK_NULL_HANDLE), "vkQueueSubmit");
        check(vkQueueWaitIdle(queue), "vkQueueWaitIdle");
        vkFreeCommandBuffers(device, pool, 1, &cmd);
    }

    static void barrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, uint32_t mip, uint32_t mips,
                        VkImageLayout from, VkImageLayout to) {
        VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
        b.srcStageMask = b.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        b.srcAccessMask = b.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
        b.oldLayout = from;
        b.newLayout = to;
        b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.image = image;
        b.subresourceRange = {aspect, mip, mips, 0, 1};
        VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        dep.imageMemoryBarrierCount = 1;
        dep.pImageMemoryBarriers = &b;
        vkCmdPipelineBarrier2(cmd, &dep);
    }

    // A dynamic-rendering attachment cleared to `clear`, kept after the pass when `store`.
    static VkRenderingAttachmentInfo clearedAttachment(VkImageView view, VkImageLayout layout, VkClearValue clear,
                                                       bool store) {
        VkRenderingAttachmentInfo a{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        a.imageView = view;
        a.imageLayout = layout;
        a.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        a.storeOp = store ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_DONT_CARE;
        a.clearValue = clear;
        return a;
    }

    // A sampled texture from tightly packed rows, with a mip chain of linear blits when `mipmapped`.
    VkImageView texture(VkFormat format, uint32_t width, uint32_t height, const void* pixels, size_t bytes,
                        bool mipmapped, VkImageViewType viewType = VK_IMAGE_VIEW_TYPE_2D) {
        const uint32_t mips = mipmapped ? mipCount(width, height) : 1u;
        const Image img =
            image(format, width, height, mips,
                  VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                  VK_IMAGE_ASPECT_COLOR_BIT, viewType);
        const VkBuffer staging = buffer(bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, pixels);
        submit([&](VkCommandBuffer cmd) {
            barrier(cmd, img.image, VK_IMAGE_ASPECT_COLOR_BIT, 0, mips, VK_IMAGE_LAYOUT_UNDEFINED,
                    VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
            VkBufferImageCopy region{};
            region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            region.imageExtent = {width, height, 1};
            vkCmdCopyBufferToImage(cmd, staging, img.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
            for (uint32_t level = 1; level < mips; ++level) {
                barrier(cmd, img.image, VK_IMAGE_ASPECT_COLOR_BIT, level - 1, 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                        VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
                VkImageBlit blit{};
                blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level - 1, 0, 1};
                blit.srcOffsets[1] = {std::max(1, int32_t(width >> (level - 1))),
                                      std::max(1, int32_t(height >> (level - 1))), 1};
                blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, 1};
                blit.dstOffsets[1] = {std::max(1, int32_t(width >> level)), std::max(1, int32_t(height >> level)), 1};
                vkCmdBlitImage(cmd, img.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, img.image,
                               VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
                barrier(cmd, img.image, VK_IMAGE_ASPECT_COLOR_BIT, level - 1, 1, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                        VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
            }
            barrier(cmd, img.image, VK_IMAGE_ASPECT_COLOR_BIT, mips - 1, 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                    VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        });
        return img.view;
    }

    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t family = 0;
    VkCommandPool pool = VK_NULL_HANDLE;
    std::vector<std::function<void()>> cleanup;  // in creation order; destroyed in reverse below
};

inline VkShaderModule shaderModule(VkDevice device, const uint32_t* code, size_t bytes) {
    VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    ci.codeSize = bytes;
    ci.pCode = code;
    VkShaderModule module;
    check(vkCreateShaderModule(device, &ci, nullptr, &module), "vkCreateShaderModule");
    return module;
}
}  // namespace host
