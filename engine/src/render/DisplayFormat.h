// Which target formats get tone-mapped, display-encoded output (8- and 10-bit UNORM/SRGB); every
// other format gets linear radiance.
#pragma once

#include <vulkan/vulkan_core.h>

namespace preskin {

inline bool isDisplayFormat(VkFormat format) {
    switch (format) {
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R8G8B8A8_SRGB:
    case VK_FORMAT_B8G8R8A8_UNORM:
    case VK_FORMAT_B8G8R8A8_SRGB:
    case VK_FORMAT_A2B10G10R10_UNORM_PACK32:
    case VK_FORMAT_A2R10G10B10_UNORM_PACK32: return true;
    default: return false;
    }
}

}  // namespace preskin
