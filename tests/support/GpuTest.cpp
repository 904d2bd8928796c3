#include "support/GpuTest.h"

#include <cstdlib>
#include <memory>

namespace preskin::test {

Context& gpuContext() {
    static std::unique_ptr<Context> context = [] {
        ContextDesc desc;
        desc.validation = true;
        const char* device = std::getenv("PRESKIN_TEST_DEVICE");
        desc.device = device ? device : "llvmpipe";
        return Context::create(desc);
    }();
    return *context;
}

void GpuTest::SetUp() { messagesAtStart_ = gpuContext().validationMessageCount(); }

void GpuTest::TearDown() {
    const auto messages = gpuContext().validationMessages();
    EXPECT_EQ(messages.size(), messagesAtStart_)
        << "Vulkan validation reported messages during this test; first new: "
        << (messages.size() > messagesAtStart_ ? messages[messagesAtStart_] : std::string());
}

}  // namespace preskin::test
