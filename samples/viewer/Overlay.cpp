// Dear ImGui setup and drawing on the swapchain (see Overlay.h).
#include "Overlay.h"

#include <preskin/Error.h>

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>
#include <imgui.h>

#include <cmath>
#include <cstdio>

namespace preskin::viewer {

namespace {

void checkImGuiVk(VkResult result) {
    if (result != VK_SUCCESS) std::fprintf(stderr, "preskin-viewer: Dear ImGui Vulkan backend: VkResult %d\n", result);
}

float srgbToLinear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

}  // namespace

Overlay::Overlay(const VulkanFunctions& vk, GLFWwindow* window, VkQueue queue, uint32_t queueFamilyIndex,
                 const Swapchain& swapchain, uint32_t framesInFlight)
    : vk_(vk), swapchain_(swapchain) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;  // panel layout is not persisted (no files written next to the user's data)
    ImGui::StyleColorsDark();
    ImGuiStyle& style = ImGui::GetStyle();
    style.WindowRounding = 4.0f;
    style.FrameRounding = 3.0f;
    style.GrabRounding = 3.0f;
    style.Colors[ImGuiCol_WindowBg].w = 0.92f;
    if (swapchain.srgb())
        for (ImVec4& c : style.Colors) {
            c.x = srgbToLinear(c.x);
            c.y = srgbToLinear(c.y);
            c.z = srgbToLinear(c.z);
        }

    const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16}};
    VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    poolInfo.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
    poolInfo.maxSets = 16;
    poolInfo.poolSizeCount = 1;
    poolInfo.pPoolSizes = sizes;
    check(vk_.vkCreateDescriptorPool(vk_.device, &poolInfo, nullptr, &pool_), "vkCreateDescriptorPool (overlay)");
    toPresent_ = createRenderPass(VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, false);
    toTransfer_ = createRenderPass(VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, false);
    clearToPresent_ = createRenderPass(VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, true);
    createFramebuffers();

    if (!ImGui_ImplGlfw_InitForVulkan(window, true)) throw Error("Dear ImGui: the GLFW backend failed to start");
    glfwBackend_ = true;
    ImGui_ImplVulkan_InitInfo info{};
    info.Instance = vk_.instance;
    info.PhysicalDevice = vk_.physicalDevice;
    info.Device = vk_.device;
    info.QueueFamily = queueFamilyIndex;
    info.Queue = queue;
    info.DescriptorPool = pool_;
    info.Subpass = 0;
    // The backend keeps this many vertex/index buffer sets and rotates them once per frame; with
    // exactly one draw per submitted frame, a set is reused only after its frame's fence.
    info.MinImageCount = framesInFlight;
    info.ImageCount = framesInFlight;
    info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
    info.CheckVkResultFn = checkImGuiVk;
    if (!ImGui_ImplVulkan_Init(&info, toPresent_)) throw Error("Dear ImGui: the Vulkan backend failed to start");
    vulkanBackend_ = true;
}

Overlay::~Overlay() {
    if (vulkanBackend_) ImGui_ImplVulkan_Shutdown();
    if (glfwBackend_) ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    destroyFramebuffers();
    if (toPresent_) vk_.vkDestroyRenderPass(vk_.device, toPresent_, nullptr);
    if (toTransfer_) vk_.vkDestroyRenderPass(vk_.device, toTransfer_, nullptr);
    if (clearToPresent_) vk_.vkDestroyRenderPass(vk_.device, clearToPresent_, nullptr);
    if (pool_) vk_.vkDestroyDescriptorPool(vk_.device, pool_, nullptr);
}

VkRenderPass Overlay::createRenderPass(VkImageLayout finalLayout, bool clear) const {
    VkAttachmentDescription color{};
    color.format = swapchain_.format();
    color.samples = VK_SAMPLE_COUNT_1_BIT;
    color.loadOp = clear ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    color.initialLayout = clear ? VK_IMAGE_LAYOUT_UNDEFINED : VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    color.finalLayout = finalLayout;
    const VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &ref;
    // The three variants must stay compatible (one framebuffer and one ImGui pipeline serve them
    // all), so their dependencies are identical; only layouts and load ops differ.
    VkSubpassDependency deps[2]{};
    // Before: the frame was written as a colour attachment (the renderer's forward pass, or a
    // layout transition after a capture copy, both ending in the colour-output stage); when
    // clearing, the image comes from acquisition, whose semaphore wait is at that stage.
    deps[0].srcSubpass = VK_SUBPASS_EXTERNAL;
    deps[0].dstSubpass = 0;
    deps[0].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    deps[0].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    deps[0].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    deps[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    // After: a copy to the host (captures with the panels); presentation is ordered by the
    // submission's semaphore.
    deps[1].srcSubpass = 0;
    deps[1].dstSubpass = VK_SUBPASS_EXTERNAL;
    deps[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    deps[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    deps[1].dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
    deps[1].dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    info.attachmentCount = 1;
    info.pAttachments = &color;
    info.subpassCount = 1;
    info.pSubpasses = &subpass;
    info.dependencyCount = 2;
    info.pDependencies = deps;
    VkRenderPass pass = VK_NULL_HANDLE;
    check(vk_.vkCreateRenderPass(vk_.device, &info, nullptr, &pass), "vkCreateRenderPass (overlay)");
    return pass;
}

void Overlay::createFramebuffers() {
    for (uint32_t i = 0; i < swapchain_.imageCount(); ++i) {
        const VkImageView view = swapchain_.view(i);
        VkFramebufferCreateInfo info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
        info.renderPass = toPresent_;
        info.attachmentCount = 1;
        info.pAttachments = &view;
        info.width = swapchain_.extent().width;
        info.height = swapchain_.extent().height;
        info.layers = 1;
        VkFramebuffer fb = VK_NULL_HANDLE;
        check(vk_.vkCreateFramebuffer(vk_.device, &info, nullptr, &fb), "vkCreateFramebuffer (overlay)");
        framebuffers_.push_back(fb);
    }
}

void Overlay::destroyFramebuffers() {
    for (VkFramebuffer fb : framebuffers_) vk_.vkDestroyFramebuffer(vk_.device, fb, nullptr);
    framebuffers_.clear();
}

void Overlay::onSwapchainRecreated() {
    destroyFramebuffers();
    if (swapchain_.valid()) createFramebuffers();
}

void Overlay::recordFontUpload(VkCommandBuffer cmd) {
    if (!ImGui_ImplVulkan_CreateFontsTexture(cmd)) throw Error("Dear ImGui: could not create the font texture");
}

void Overlay::finishFontUpload() { ImGui_ImplVulkan_DestroyFontUploadObjects(); }

void Overlay::newFrame() {
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
}

void Overlay::record(VkCommandBuffer cmd, uint32_t imageIndex, bool forCapture, bool clearFirst) {
    VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    begin.renderPass = clearFirst ? clearToPresent_ : forCapture ? toTransfer_ : toPresent_;
    VkClearValue clear{};
    clear.color = {{0.02f, 0.02f, 0.025f, 1.0f}};
    begin.clearValueCount = clearFirst ? 1u : 0u;
    begin.pClearValues = &clear;
    begin.framebuffer = framebuffers_[imageIndex];
    begin.renderArea = {{0, 0}, swapchain_.extent()};
    vk_.vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
    ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
    vk_.vkCmdEndRenderPass(cmd);
}

}  // namespace preskin::viewer
