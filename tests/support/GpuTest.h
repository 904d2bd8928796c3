// Shared GPU test fixture: one Vulkan context for the whole test binary, created on the device
// named by PRESKIN_TEST_DEVICE (ctest sets "llvmpipe") with validation layers on. Every test
// fails if the validation layers reported anything while it ran.
#pragma once

#include <preskin/Context.h>

#include <gtest/gtest.h>

#include "vk/ContextAccess.h"  // ContextAccess::core: the tests reach the Vulkan core

namespace preskin::test {

Context& gpuContext();

class GpuTest : public ::testing::Test {
protected:
    void SetUp() override;
    void TearDown() override;
    Context& context() { return gpuContext(); }

private:
    uint32_t messagesAtStart_ = 0;
};

}  // namespace preskin::test
