// Turns a failed Vulkan call into a preskin::Error naming the call and the VkResult.
#pragma once

#include <preskin/Error.h>

#include <volk.h>

#include <string>

namespace preskin::vk {

const char* resultName(VkResult result);

[[noreturn]] void throwVkError(VkResult result, const char* call, const char* file, int line);

}  // namespace preskin::vk

#define PRESKIN_VK(call)                                                                                              \
    do {                                                                                                              \
        const VkResult preskinVkResult_ = (call);                                                                     \
        if (preskinVkResult_ != VK_SUCCESS) ::preskin::vk::throwVkError(preskinVkResult_, #call, __FILE__, __LINE__); \
    } while (false)
