// The library's access to the Vulkan core behind a public Context (kept out of <preskin/Context.h>).
#pragma once

#include <preskin/Context.h>

#include "vk/Device.h"

namespace preskin {

struct ContextAccess {
    static vk::Device& core(const Context& context) { return *context.device_; }
};

}  // namespace preskin
