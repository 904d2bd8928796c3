// Embedding: preskin running on a host's Vulkan objects (Context::wrap) renders the same image
// as on its own context, never destroys the host's handles, and records into a host's frame:
// over the host's colour, against the host's depth, resizing without waiting for the device.
#include "support/GpuTest.h"
#include "support/TestScenes.h"

#include <preskin/Error.h>
#include <preskin/Renderer.h>

#include "vk/Device.h"
#include "vk/Resources.h"

#include <cmath>
#include <cstring>

#include <volk.h>

#include <glm/gtc/matrix_transform.hpp>

namespace preskin::test {
namespace {

class HostContext : public GpuTest {
protected:
    HostVulkan handles() {
        Context& host = context();
        HostVulkan h;
        h.getInstanceProcAddr = vkGetInstanceProcAddr;
        h.instance = host.instance();
        h.physicalDevice = host.physicalDevice();
        h.device = host.device();
        h.queue = host.queue();
        h.queueFamilyIndex = host.queueFamilyIndex();
        h.shaderOutputLayerEnabled = ContextAccess::core(host).shaderOutputLayer();
        return h;
    }
};

// The shadow-casting light of these scenes, from the upper right front.
Light keyLight() {
    Light light;
    light.directionWs = glm::normalize(glm::vec3(-0.3f, -0.6f, -0.7f));
    light.intensity = 2.0f;
    light.castsShadow = true;
    return light;
}

// A lit sphere in front of the camera, filling the middle of the picture.
Scene sphereScene(uint32_t segments = 48) {
    Material material;
    material.baseColorFactor = glm::vec4(0.7f, 0.5f, 0.4f, 1.0f);
    material.metallicFactor = 0.0f;
    material.roughnessFactor = 0.5f;
    Scene scene = makeScene({{makeSphere(1.0f, segments, segments / 2), glm::mat4(1.0f)}}, {material});
    scene.meshes[0].primitives[0].material = 0;
    scene.lights = {keyLight()};
    return scene;
}

uint8_t srgb8(float linear) {
    const float s = linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
    return static_cast<uint8_t>(std::lround(s * 255.0f));
}

TEST_F(HostContext, WrappedDeviceRendersLikeOwnedOne) {
    const Scene scene = sphereScene(64);
    const Environment env = Environment::constant(glm::vec3(0.1f));
    const View view = orbitView(scene.worldBounds(), 20.0f, 10.0f, 0.0f, 1.0f);

    // The "host" is the test's own context; a second Context wraps its handles.
    Context& host = context();
    const HostVulkan hostHandles = handles();

    RenderedImage owned;
    {
        Renderer renderer(host, scene, env, nullptr);
        owned = renderer.render(view, 64, 64, OutputEncoding::DisplaySrgb8);
    }
    RenderedImage wrapped;
    {
        auto guest = Context::wrap(hostHandles);
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

    HostVulkan incomplete = hostHandles;
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
    scene.lights = {keyLight()};
    const Environment env = Environment::constant(glm::vec3(0.1f));
    const View view = stereoFromMono(orbitView(scene.worldBounds(), 10.0f, 5.0f, 2.2f, 1.0f), 0.064f);
    constexpr uint32_t kSize = 48;

    Context& host = context();
    auto guest = Context::wrap(handles());
    const vk::Device& device = ContextAccess::core(host);

    for (uint32_t samples : {1u, 4u}) {
        RenderSettings settings;
        settings.msaaSamples = samples;
        Renderer renderer(*guest, scene, env, nullptr, settings);
        const RenderedImage headless = renderer.render(view, kSize, kSize, OutputEncoding::DisplaySrgb8);

        // The host's image, view and readback.
        vk::Image image(
            device,
            {VK_FORMAT_R8G8B8A8_SRGB, kSize, kSize, 1,
             VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, VK_IMAGE_ASPECT_COLOR_BIT, 2});
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
            vkCmdCopyImageToBuffer(cmd, image.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback.handle(), 1,
                                   &region);
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

// A host frame: the host opens its pass, clears its colour and depth and "draws" (clears a
// rectangle of its own colour, and near-plane depth over the left half), ends it, then
// preskin records into the same colour and depth. Where the host's depth is nearer (left
// half) nothing of preskin's shows; on the right the sphere is drawn where the headless frame
// has it, the host's colour stays where preskin draws nothing, and the sphere's depth lands in
// the host's depth image.
TEST_F(HostContext, RecordKeepsTheHostsColourAndUsesItsDepth) {
    const Scene scene = sphereScene();
    const Environment env = Environment::constant(glm::vec3(0.1f));
    const View view = orbitView(scene.worldBounds(), 0.0f, 0.0f, 0.0f, 1.0f);
    constexpr uint32_t kSize = 48;
    constexpr uint32_t kHalf = kSize / 2;
    auto guest = Context::wrap(handles());
    const vk::Device& device = ContextAccess::core(context());
    Renderer renderer(*guest, scene, env, nullptr);
    const RenderedImage headless = renderer.render(view, kSize, kSize, OutputEncoding::DisplaySrgb8);

    vk::Image color(device,
                    {VK_FORMAT_R8G8B8A8_SRGB, kSize, kSize, 1,
                     VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT});
    vk::Image depth(
        device,
        {VK_FORMAT_D32_SFLOAT, kSize, kSize, 1,
         VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, VK_IMAGE_ASPECT_DEPTH_BIT});
    vk::Buffer colorBytes(device, kSize * kSize * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    vk::Buffer depthBytes(device, kSize * kSize * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    const glm::vec4 background(0.2f, 0.5f, 0.8f, 1.0f);  // the host's clear colour
    const glm::vec4 panel(0.9f, 0.1f, 0.1f, 1.0f);       // what the host "draws": the top-right corner

    RenderTarget target;
    target.image = color.handle();
    target.view = color.view();
    target.format = VK_FORMAT_R8G8B8A8_SRGB;
    target.extent = {kSize, kSize};
    target.layoutBefore = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    target.layoutAfter = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    target.loadColor = true;
    target.depth.image = depth.handle();
    target.depth.view = depth.view();
    target.depth.format = VK_FORMAT_D32_SFLOAT;
    target.depth.layoutBefore = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    target.depth.layoutAfter = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    device.submitAndWait([&](VkCommandBuffer cmd) {
        vk::imageBarrier(cmd, color.handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                         VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                         VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
        vk::imageBarrier(cmd, depth.handle(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                         VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                         VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                         VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
        VkRenderingAttachmentInfo colorAttachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        colorAttachment.imageView = color.view();
        colorAttachment.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        colorAttachment.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        colorAttachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        colorAttachment.clearValue.color = {{background.r, background.g, background.b, background.a}};
        VkRenderingAttachmentInfo depthAttachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        depthAttachment.imageView = depth.view();
        depthAttachment.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
        depthAttachment.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        depthAttachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        depthAttachment.clearValue.depthStencil = {0.0f, 0};  // reversed Z: far
        VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
        info.renderArea = {{0, 0}, {kSize, kSize}};
        info.layerCount = 1;
        info.colorAttachmentCount = 1;
        info.pColorAttachments = &colorAttachment;
        info.pDepthAttachment = &depthAttachment;
        vkCmdBeginRendering(cmd, &info);
        VkClearAttachment clears[2]{};
        clears[0].aspectMask = VK_IMAGE_ASPECT_COLOR_BIT;
        clears[0].clearValue.color = {{panel.r, panel.g, panel.b, panel.a}};
        clears[1].aspectMask = VK_IMAGE_ASPECT_DEPTH_BIT;
        clears[1].clearValue.depthStencil = {1.0f, 0};  // the near plane over the left half
        const VkClearRect panelRect{{{int32_t(kSize - 8), 0}, {8, 8}}, 0, 1};
        const VkClearRect leftRect{{{0, 0}, {kHalf, kSize}}, 0, 1};
        vkCmdClearAttachments(cmd, 1, &clears[0], 1, &panelRect);
        vkCmdClearAttachments(cmd, 1, &clears[1], 1, &leftRect);
        vkCmdEndRendering(cmd);
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_GRAPHICS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_ALL_GRAPHICS_BIT,
                          VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);

        renderer.record(cmd, target, view, 1);

        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {kSize, kSize, 1};
        vkCmdCopyImageToBuffer(cmd, color.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, colorBytes.handle(), 1,
                               &region);
        region.imageSubresource.aspectMask = VK_IMAGE_ASPECT_DEPTH_BIT;
        vkCmdCopyImageToBuffer(cmd, depth.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, depthBytes.handle(), 1,
                               &region);
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    });
    std::vector<uint8_t> out(kSize * kSize * 4);
    std::memcpy(out.data(), colorBytes.mapped(), out.size());
    std::vector<float> z(kSize * kSize);
    std::memcpy(z.data(), depthBytes.mapped(), z.size() * sizeof(float));

    // Background of the headless frame: its corner pixel (the sphere does not reach the corners).
    const uint8_t* clear = headless.rgba8.data();
    auto isBackground = [&](size_t p) { return std::memcmp(headless.rgba8.data() + 4 * p, clear, 3) == 0; };
    auto near = [](uint8_t a, uint8_t b) { return std::abs(int(a) - int(b)) <= 1; };
    auto hasColor = [&](size_t p, const glm::vec4& c) {
        return near(out[4 * p], srgb8(c.r)) && near(out[4 * p + 1], srgb8(c.g)) && near(out[4 * p + 2], srgb8(c.b));
    };
    size_t sphereLeft = 0, sphereRight = 0, hostKeptLeft = 0, wrong = 0;
    for (uint32_t y = 0; y < kSize; ++y)
        for (uint32_t x = 0; x < kSize; ++x) {
            const size_t p = size_t(y) * kSize + x;
            const glm::vec4 host = (x >= kSize - 8 && y < 8) ? panel : background;
            if (x < kHalf) {  // behind the host's near-plane depth: the host's pixels, depth untouched
                if (!isBackground(p)) ++sphereLeft;
                if (hasColor(p, host) && z[p] == 1.0f)
                    ++hostKeptLeft;
                else
                    ++wrong;
            } else if (isBackground(p)) {  // preskin draws nothing here: the host's colour and depth stay
                if (!hasColor(p, host) || z[p] != 0.0f) ++wrong;
            } else {  // the sphere, as in the headless frame, its depth written
                ++sphereRight;
                const bool same = near(out[4 * p], headless.rgba8[4 * p]) &&
                    near(out[4 * p + 1], headless.rgba8[4 * p + 1]) && near(out[4 * p + 2], headless.rgba8[4 * p + 2]);
                if (!same || !(z[p] > 0.0f && z[p] < 1.0f)) ++wrong;
            }
        }
    EXPECT_EQ(wrong, 0u);
    EXPECT_GT(sphereLeft, 200u) << "the sphere should reach into the left half";
    EXPECT_GT(sphereRight, 200u) << "the sphere should reach into the right half";
    EXPECT_EQ(hostKeptLeft, size_t(kHalf) * kSize);

    // What record cannot do is refused before anything is recorded.
    RenderTarget undefinedColor = target;
    undefinedColor.layoutBefore = VK_IMAGE_LAYOUT_UNDEFINED;
    EXPECT_THROW(device.submitAndWait([&](VkCommandBuffer cmd) { renderer.record(cmd, undefinedColor, view, 1); }),
                 Error);
    RenderSettings msaa;
    msaa.msaaSamples = 4;
    renderer.setSettings(msaa);
    EXPECT_THROW(device.submitAndWait([&](VkCommandBuffer cmd) { renderer.record(cmd, target, view, 1); }), Error);
}

// Two frames of different sizes recorded into one command buffer before anything is submitted:
// the second replaces the depth the first still uses. Recording waits for nothing, the old
// attachment outlives the frame that uses it (the validation layers report a destroyed image in
// a submitted command buffer), and each frame equals its headless render.
TEST_F(HostContext, RecordResizesWithoutWaitingForTheDevice) {
    const Scene scene = sphereScene();
    const Environment env = Environment::constant(glm::vec3(0.1f));
    const View view = orbitView(scene.worldBounds(), 20.0f, 10.0f, 0.0f, 1.0f);
    auto guest = Context::wrap(handles());
    const vk::Device& device = ContextAccess::core(context());
    Renderer renderer(*guest, scene, env, nullptr);
    const uint32_t sizes[2] = {32, 40};
    RenderedImage headless[2];
    for (int i = 0; i < 2; ++i) headless[i] = renderer.render(view, sizes[i], sizes[i], OutputEncoding::DisplaySrgb8);

    std::vector<vk::Image> images;
    std::vector<vk::Buffer> readbacks;
    for (uint32_t size : sizes) {
        images.emplace_back(device,
                            vk::ImageDesc{VK_FORMAT_R8G8B8A8_SRGB, size, size, 1,
                                          VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT});
        readbacks.emplace_back(device, VkDeviceSize(size) * size * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    }
    device.submitAndWait([&](VkCommandBuffer cmd) {
        for (uint32_t i = 0; i < 2; ++i) {
            RenderTarget target;
            target.image = images[i].handle();
            target.view = images[i].view();
            target.format = VK_FORMAT_R8G8B8A8_SRGB;
            target.extent = {sizes[i], sizes[i]};
            target.layoutAfter = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
            renderer.record(cmd, target, view, i);
            VkBufferImageCopy region{};
            region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            region.imageExtent = {sizes[i], sizes[i], 1};
            vkCmdCopyImageToBuffer(cmd, images[i].handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readbacks[i].handle(),
                                   1, &region);
        }
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    });
    for (uint32_t i = 0; i < 2; ++i) {
        const auto* bytes = static_cast<const uint8_t*>(readbacks[i].mapped());
        size_t off = 0;
        for (size_t k = 0; k < headless[i].rgba8.size(); ++k)
            off += std::abs(int(bytes[k]) - int(headless[i].rgba8[k])) > 1;
        EXPECT_EQ(off, 0u) << "frame " << i << " (" << sizes[i] << " pixels)";
    }
}

}  // namespace
}  // namespace preskin::test
