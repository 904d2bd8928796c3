// The Dear ImGui overlay: ImGui context and style, its GLFW and Vulkan backends (Dear ImGui 1.86,
// which needs a VkRenderPass), and that render pass with one framebuffer per swapchain image.
// The pass loads the rendered frame (loadOp LOAD, COLOR_ATTACHMENT_OPTIMAL) and draws the panels
// on top; it ends in PRESENT_SRC, or in TRANSFER_SRC when the frame with its panels is captured.
// A third variant clears an UNDEFINED image first, for frames the renderer could not draw.
// The variants are compatible render passes: one framebuffer per image serves them all.
// Limits: one window, one subpass, no MSAA. On an sRGB swapchain the style colours are converted
// to linear once, so the panels look as designed.
#pragma once

#include "Swapchain.h"
#include "VulkanFunctions.h"

#include <vector>

struct GLFWwindow;

namespace preskin::viewer {

class Overlay {
public:
    // Installs the GLFW callbacks (after the viewer's own, which ImGui chains to).
    Overlay(const VulkanFunctions& vk, GLFWwindow* window, VkQueue queue, uint32_t queueFamilyIndex,
            const Swapchain& swapchain, uint32_t framesInFlight);
    ~Overlay();
    Overlay(const Overlay&) = delete;
    Overlay& operator=(const Overlay&) = delete;

    // Records the font atlas upload; call finishFontUpload once that command buffer has completed.
    void recordFontUpload(VkCommandBuffer cmd);
    void finishFontUpload();
    // New framebuffers after the swapchain was recreated (the device must be idle).
    void onSwapchainRecreated();
    // Starts an ImGui frame; panels are built after it, then ImGui::Render().
    void newFrame();
    // Draws ImGui's current draw data onto swapchain image `imageIndex`, which is in
    // COLOR_ATTACHMENT_OPTIMAL (or UNDEFINED with `clearFirst`, and is then cleared). It is left
    // in PRESENT_SRC, or TRANSFER_SRC when `forCapture`.
    // Must run exactly once per submitted frame: the backend rotates its vertex buffers per call.
    void record(VkCommandBuffer cmd, uint32_t imageIndex, bool forCapture, bool clearFirst);

private:
    VkRenderPass createRenderPass(VkImageLayout finalLayout, bool clear) const;
    void createFramebuffers();
    void destroyFramebuffers();

    const VulkanFunctions& vk_;
    const Swapchain& swapchain_;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    VkRenderPass toPresent_ = VK_NULL_HANDLE;
    VkRenderPass toTransfer_ = VK_NULL_HANDLE;
    VkRenderPass clearToPresent_ = VK_NULL_HANDLE;
    std::vector<VkFramebuffer> framebuffers_;
    bool glfwBackend_ = false;
    bool vulkanBackend_ = false;
};

}  // namespace preskin::viewer
