// Embedding: preskin running on a host's Vulkan objects (Context::wrap) renders the same image
// as on its own context, and never destroys the host's handles.
#include "support/GpuTest.h"
#include "support/TestScenes.h"

#include <preskin/Error.h>
#include <preskin/Renderer.h>

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

}  // namespace
}  // namespace preskin::test
