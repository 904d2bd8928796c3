// Embedding: preskin running on a host's Vulkan objects (Context::wrap) renders the same image
// as on its own context, and never destroys the host's handles.
#include "support/GpuTest.h"
#include "support/TestScenes.h"

#include <preskin/Error.h>
#include <preskin/Renderer.h>

#include "vk/Device.h"
#include "vk/Resources.h"

#include <cstring>

#include <volk.h>

#include <glm/gtc/matrix_transform.hpp>

namespace preskin::test {
namespace {

class HostContext : public GpuTest {};

TEST_F(HostContext, WrappedDeviceRendersLikeOwnedOne) {
    Material material;
    material.baseColorFactor = glm::vec4(0.7f, 0.5f, 0.4f, 1.0f);
    material.metallicFactor = 0.0f;
    material.roughnessFactor = 0.5f;
    Scene scene = makeScene({{makeSphere(1.0f, 64, 32), glm::mat4(1.0f)}}, {material});
    scene.meshes[0].primitives[0].material = 0;
    Light light;
    light.directionWs = glm::normalize(glm::vec3(-0.3f, -0.6f, -0.7f));
    light.intensity = 2.0f;
    light.castsShadow = true;
    scene.lights = {light};
    const Environment env = Environment::constant(glm::vec3(0.1f));
    const View view = orbitView(scene.worldBounds(), 20.0f, 10.0f, 0.0f, 1.0f);

    // The "host" is the test's own context; a second Context wraps its handles.
    Context& host = context();
    HostVulkan handles;
    handles.getInstanceProcAddr = vkGetInstanceProcAddr;
    handles.instance = host.instance();
    handles.physicalDevice = host.physicalDevice();
    handles.device = host.device();
    handles.queue = host.queue();
    handles.queueFamilyIndex = host.queueFamilyIndex();

    RenderedImage owned;
    {
        Renderer renderer(host, scene, env, nullptr);
        owned = renderer.render(view, 64, 64, OutputEncoding::DisplaySrgb8);
    }
    RenderedImage wrapped;
    {
        auto guest = Context::wrap(handles);
        EXPECT_EQ(guest->device(), host.device());
        Renderer renderer(*guest, scene, env, nullptr);
        wrapped = renderer.render(view, 64, 64, OutputEncoding::DisplaySrgb8);
    }
    ASSERT_EQ(owned.rgba8.size(), wrapped.rgba8.size());
    EXPECT_EQ(owned.rgba8, wrapped.rgba8);
    size_t lit = 0;
    for (size_t i = 0; i < owned.rgba8.size(); i += 4) lit += owned.rgba8[i] > 60 ? 1 : 0;
    EXPECT_GT(lit, 500u) << "the sphere should be in the picture";
    // The host's device is still alive and usable after the wrapping context is gone.
    EXPECT_EQ(vkDeviceWaitIdle(host.device()), VK_SUCCESS);
    Renderer again(host, scene, env, nullptr);
    EXPECT_EQ(again.render(view, 64, 64, OutputEncoding::DisplaySrgb8).rgba8, owned.rgba8);

    HostVulkan incomplete = handles;
    incomplete.queue = VK_NULL_HANDLE;
    EXPECT_THROW(Context::wrap(incomplete), Error);
}

// A host's 2-layer array colour image (what an OpenXR multiview swapchain hands out), in the
// layouts the host names: Renderer::record draws eye e into layer e, resolving MSAA into it,
// on a wrapped device, and each layer equals the headless render of that eye.
TEST_F(HostContext, RecordsEveryEyeIntoTheHostsArrayLayers) {
    Material material;
    material.baseColorFactor = glm::vec4(0.6f, 0.5f, 0.45f, 1.0f);
    material.metallicFactor = 0.0f;
    material.roughnessFactor = 0.4f;
    Scene scene = makeScene({{makeSphere(0.5f, 48, 24), glm::mat4(1.0f)},
                             {makeQuad(8.0f, 1), glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, -0.8f))}},
                            {material});
    for (Mesh& m : scene.meshes) m.primitives[0].material = 0;
    Light light;
    light.directionWs = glm::normalize(glm::vec3(-0.3f, -0.6f, -0.7f));
    light.intensity = 2.0f;
    light.castsShadow = true;
    scene.lights = {light};
    const Environment env = Environment::constant(glm::vec3(0.1f));
    const View view = stereoFromMono(orbitView(scene.worldBounds(), 10.0f, 5.0f, 2.2f, 1.0f), 0.064f);
    constexpr uint32_t kSize = 48;

    Context& host = context();
    HostVulkan handles;
    handles.getInstanceProcAddr = vkGetInstanceProcAddr;
    handles.instance = host.instance();
    handles.physicalDevice = host.physicalDevice();
    handles.device = host.device();
    handles.queue = host.queue();
    handles.queueFamilyIndex = host.queueFamilyIndex();
    handles.shaderOutputLayerEnabled = ContextAccess::core(host).shaderOutputLayer();
    auto guest = Context::wrap(handles);
    const vk::Device& device = ContextAccess::core(host);

    for (uint32_t samples : {1u, 4u}) {
        RenderSettings settings;
        settings.msaaSamples = samples;
        Renderer renderer(*guest, scene, env, nullptr, settings);
        const RenderedImage headless = renderer.render(view, kSize, kSize, OutputEncoding::DisplaySrgb8);

        // The host's image, view and readback.
        vk::Image image(device, {VK_FORMAT_R8G8B8A8_SRGB, kSize, kSize, 1,
                                 VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                                 VK_IMAGE_ASPECT_COLOR_BIT, 2});
        vk::Buffer readback(device, kSize * kSize * 4 * 2, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
        RenderTarget target;
        target.image = image.handle();
        target.view = image.view();
        target.format = VK_FORMAT_R8G8B8A8_SRGB;
        target.extent = {kSize, kSize};
        target.layoutBefore = VK_IMAGE_LAYOUT_UNDEFINED;
        target.layoutAfter = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
        device.submitAndWait([&](VkCommandBuffer cmd) {
            renderer.record(cmd, target, view, 1);
            VkBufferImageCopy region{};
            region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 2};
            region.imageExtent = {kSize, kSize, 1};
            vkCmdCopyImageToBuffer(cmd, image.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback.handle(), 1, &region);
            vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                              VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
        });
        std::vector<uint8_t> recorded(kSize * kSize * 4 * 2);
        std::memcpy(recorded.data(), readback.mapped(), recorded.size());
        ASSERT_EQ(recorded.size(), headless.rgba8.size());
        size_t off = 0, lit = 0;
        for (size_t i = 0; i < recorded.size(); ++i) off += std::abs(int(recorded[i]) - int(headless.rgba8[i])) > 1;
        for (size_t i = 0; i < recorded.size(); i += 4) lit += recorded[i] > 90;
        EXPECT_EQ(off, 0u) << samples << " samples";
        EXPECT_GT(lit, 400u) << samples << " samples: the sphere in both layers";
        // The eyes differ (parallax), so each layer holds its own eye.
        EXPECT_NE(std::memcmp(recorded.data(), recorded.data() + kSize * kSize * 4, kSize * kSize * 4), 0);
        const FrameStats stats = renderer.frameStats(1);
        EXPECT_EQ(stats.eyes, 2u);
    }
}

}  // namespace
}  // namespace preskin::test
