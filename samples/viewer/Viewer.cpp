// preskin-viewer's window, Vulkan objects and frame loop (see Viewer.h); loading and swapping in
// content is in ViewerContent.cpp, the panels in ViewerPanels.cpp.
#include "Viewer.h"

#include <preskin/Error.h>
#include <preskin/LightScatter.h>
#include <preskin/View.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <exception>
#include <string>
#include <utility>

namespace preskin::viewer {

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

}  // namespace

Viewer::Viewer(ViewerOptions options) : options_(std::move(options)) {
    vsync_ = !options_.noVsync;
    showUi_ = !options_.hideUi;
    settings_ = cli::renderSettings(options_.common);  // throws on a bad --debug before any window opens
    stereo_ = options_.stereo.stereo;
    ipdM_ = options_.stereo.ipdM;
    if (!std::isfinite(ipdM_) || ipdM_ < 0.0f || ipdM_ > 1.0f)
        throw Error(fmt::format("--ipd {}: the interpupillary distance must be a finite 0..1 metres", ipdM_));
    lastGoodSettings_ = settings_;
    scatteredLights_ = options_.common.lights;
    scatterSeed_ = options_.common.seed;
    scatterDensity_ = options_.common.lightDensity;
    const auto albedo = cli::parseFloats(options_.albedo, 3, "--albedo");
    const auto mfp = cli::parseFloats(options_.mfp, 3, "--mfp");
    std::copy(albedo.begin(), albedo.end(), startEdit_.albedo.begin());
    std::copy(mfp.begin(), mfp.end(), startEdit_.mfpMm.begin());
    lutSize_ = options_.lutSize;
    try {
        createWindow();
        createVulkan();
        shaders_ = std::make_unique<ShaderReloader>(cli::dataDir() / "shaders");
        shaders_->setWatching(!options_.noShaderReload);
        if (options_.compileShaders) {
            if (shaders_->enabled())
                shaders_->requestBuild();
            else
                error("--compile-shaders: no shader sources to compile");
        }
        if (!shaders_->enabled())
            info(fmt::format("shader hot reload is off: {} does not exist (set PRESKIN_DATA_DIR to a source tree)",
                             shaders_->directory().string()));
        loadStartupContent();
        if (!options_.profile.empty()) {
            startEdit_.choice = options_.profile == "burley" ? ProfileChoice::Burley : ProfileChoice::DeonLuebke;
            layerEdits_.at(0) = startEdit_;
            requestBake(0);
        }
    } catch (...) {
        shutdown();
        throw;
    }
}

Viewer::~Viewer() { shutdown(); }

void Viewer::shutdown() noexcept {
    if (context_ && vk_.vkDeviceWaitIdle) vk_.vkDeviceWaitIdle(vk_.device);
    shaders_.reset();
    renderer_.reset();
    overlay_.reset();
    capture_.reset();
    stereoPreview_.reset();
    if (vk_.vkDestroyCommandPool) destroyFrames();
    swapchain_.reset();
    if (surface_) vk_.vkDestroySurfaceKHR(vk_.instance, surface_, nullptr);
    surface_ = VK_NULL_HANDLE;
    context_.reset();
    if (window_) glfwDestroyWindow(window_);
    window_ = nullptr;
    glfwTerminate();
}

void Viewer::createWindow() {
    // Until the window exists, GLFW's reason for a failure goes into the one error line that
    // ends the program; later GLFW errors are reported as they come.
    static std::string glfwReason;
    static bool windowOpen = false;
    glfwSetErrorCallback([](int code, const char* text) {
        if (windowOpen)
            fmt::print(stderr, "preskin-viewer: GLFW {}: {}\n", code, text);
        else
            glfwReason = text ? text : "";
    });
    auto failed = [](const char* field, const char* otherwise, const char* hint) {
        return Error(fmt::format("GLFW: {}: {}{}", field, glfwReason.empty() ? otherwise : glfwReason, hint));
    };
    if (!glfwInit()) throw failed("display", "cannot open it", " (without a display, run under xvfb-run)");
    if (!glfwVulkanSupported()) throw failed("Vulkan", "no Vulkan loader or driver found", "");
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    window_ = glfwCreateWindow(static_cast<int>(options_.widthPx), static_cast<int>(options_.heightPx),
                               "preskin-viewer", nullptr, nullptr);
    if (!window_) throw failed("window", "cannot create it", "");
    windowOpen = true;
    glfwSetWindowUserPointer(window_, this);
    glfwSetDropCallback(window_, [](GLFWwindow* w, int count, const char** paths) {
        auto* self = static_cast<Viewer*>(glfwGetWindowUserPointer(w));
        for (int i = 0; i < count; ++i) self->dropped_.emplace_back(paths[i]);
    });
    glfwSetFramebufferSizeCallback(window_, [](GLFWwindow* w, int, int) {
        static_cast<Viewer*>(glfwGetWindowUserPointer(w))->swapchainDirty_ = true;
    });
}

void Viewer::createVulkan() {
    ContextDesc desc = cli::contextDesc(options_.common);
    uint32_t count = 0;
    const char** required = glfwGetRequiredInstanceExtensions(&count);
    if (!required) throw Error("GLFW: this window system offers no Vulkan surface extensions");
    for (uint32_t i = 0; i < count; ++i) desc.instanceExtensions.emplace_back(required[i]);
    desc.deviceExtensions.emplace_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
    context_ = Context::create(desc);
    cli::checkMsaaOption(*context_, options_.common.msaa);
    vk_.load(context_->instance(), context_->physicalDevice(), context_->device());
    check(glfwCreateWindowSurface(context_->instance(), window_, nullptr, &surface_), "glfwCreateWindowSurface");
    swapchain_ = std::make_unique<Swapchain>(vk_, surface_, context_->queueFamilyIndex());
    int w = 0;
    int h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    swapchain_->recreate({uint32_t(std::max(w, 0)), uint32_t(std::max(h, 0))}, vsync_);
    if (!swapchain_->srgb())
        error("the window offers no 8-bit sRGB format: colours are shown without display encoding (too dark)");
    if (!swapchain_->transferSource()) error("the window's images cannot be copied: screenshots are unavailable");
    capture_ = std::make_unique<ImageCapture>(vk_, kFramesInFlight);
    stereoPreview_ = std::make_unique<StereoPreview>(vk_);
    createFrames();
    overlay_ = std::make_unique<Overlay>(vk_, window_, context_->queue(), context_->queueFamilyIndex(), *swapchain_,
                                         kFramesInFlight);
    uploadFonts();
}

void Viewer::createFrames() {
    for (Frame& f : frames_) {
        VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        poolInfo.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
        poolInfo.queueFamilyIndex = context_->queueFamilyIndex();
        check(vk_.vkCreateCommandPool(vk_.device, &poolInfo, nullptr, &f.pool), "vkCreateCommandPool");
        VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        alloc.commandPool = f.pool;
        alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        alloc.commandBufferCount = 1;
        check(vk_.vkAllocateCommandBuffers(vk_.device, &alloc, &f.cmd), "vkAllocateCommandBuffers");
        VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        check(vk_.vkCreateFence(vk_.device, &fenceInfo, nullptr, &f.fence), "vkCreateFence");
        VkSemaphoreCreateInfo semaphoreInfo{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
        check(vk_.vkCreateSemaphore(vk_.device, &semaphoreInfo, nullptr, &f.acquired), "vkCreateSemaphore");
    }
}

void Viewer::destroyFrames() {
    for (Frame& f : frames_) {
        if (f.acquired) vk_.vkDestroySemaphore(vk_.device, f.acquired, nullptr);
        if (f.fence) vk_.vkDestroyFence(vk_.device, f.fence, nullptr);
        if (f.pool) vk_.vkDestroyCommandPool(vk_.device, f.pool, nullptr);
        f = Frame{};
    }
}

void Viewer::uploadFonts() {
    Frame& f = frames_[0];
    check(vk_.vkResetCommandPool(vk_.device, f.pool, 0), "vkResetCommandPool");
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vk_.vkBeginCommandBuffer(f.cmd, &begin), "vkBeginCommandBuffer");
    overlay_->recordFontUpload(f.cmd);
    check(vk_.vkEndCommandBuffer(f.cmd), "vkEndCommandBuffer");
    VkCommandBufferSubmitInfo cmdInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cmdInfo.commandBuffer = f.cmd;
    VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &cmdInfo;
    check(vk_.vkQueueSubmit2(context_->queue(), 1, &submit, f.fence), "vkQueueSubmit2 (fonts)");
    check(vk_.vkWaitForFences(vk_.device, 1, &f.fence, VK_TRUE, UINT64_MAX), "vkWaitForFences (fonts)");
    check(vk_.vkResetFences(vk_.device, 1, &f.fence), "vkResetFences");
    overlay_->finishFontUpload();
}

void Viewer::loadStartupContent() {
    const std::filesystem::path scenePath =
        options_.scene.empty() ? cli::defaultScenePath() : std::filesystem::path(options_.scene);
    scenePathInput_ = scenePath.string();
    Scene scene;
    bool sceneLoaded = false;
    try {
        scene = cli::loadScene(scenePath, options_.common);
        sceneLoaded = true;
        for (const std::string& w : scene.warnings) info("warning: " + w);
        cli::applySkinOption(scene, options_.common);
    } catch (const std::exception& e) {
        error(fmt::format("scene not loaded: {}", e.what()));
        scene = Scene{};
    }

    environmentIntensity_ = options_.common.envIntensity >= 0.0f       ? options_.common.envIntensity
        : (options_.common.env.empty() && scene.hasEnvironmentImage()) ? scene.environmentIntensity
                                                                       : 1.0f;
    environmentFromScene_ = options_.common.env.empty();
    try {
        environment_ = cli::loadEnvironment(scene, options_.common);
        environmentRotationDeg_ = glm::degrees(environment_.rotationY());
        environmentName_ = !options_.common.env.empty() ? options_.common.env
            : scene.environmentPath                     ? scene.environmentPath->string()
            : scene.hasEnvironmentImage()               ? "the scene's embedded environment"
                                                        : "uniform grey";
    } catch (const std::exception& e) {
        error(fmt::format("environment not loaded: {} (using a uniform grey)", e.what()));
        environment_ = Environment::constant(glm::vec3(0.25f));
        environmentName_ = "uniform grey (fallback)";
        environmentFromScene_ = true;  // later intensity edits reload the scene's own (or the grey)
    }
    environmentPathInput_ = environmentName_;

    try {
        luts_ = cli::loadLuts(options_.common);
        lutsName_ = options_.common.luts.empty() ? "bundled d'Eon & Luebke set" : options_.common.luts;
    } catch (const std::exception& e) {
        error(fmt::format("LUTs not loaded: {} (using the default set)", e.what()));
        luts_ = LutSet::loadDefault();
        lutsName_ = "default d'Eon & Luebke set";
    }

    adoptScene(std::move(scene), scenePath, sceneLoaded ? "scene loaded" : "empty scene: the scene was not loaded");
    if (!options_.animation.empty() || options_.timeS || options_.play) {
        try {
            if (scene_.animations.empty()) throw Error("the scene has no animations");
            const Animation& a =
                findAnimation(scene_, options_.animation.empty() ? std::string("0") : options_.animation);
            animation_ = static_cast<int>(&a - scene_.animations.data());
            animationTimeS_ = options_.timeS.value_or(a.startS());
            playing_ = options_.play;
        } catch (const std::exception& e) {
            error(fmt::format("--animation: {}", e.what()));
        }
    }

    if (!options_.camera.empty()) {
        try {
            camera_.setSceneCamera(static_cast<int>(cli::findSceneCamera(scene_, scenePath, options_.camera)));
            camera_.setMode(CameraMode::Scene, aspect());
        } catch (const std::exception& e) {
            error(e.what());
        }
    } else if (!options_.orbit.empty()) {
        try {
            const auto v = cli::parseFloats(options_.orbit, 3, "--orbit");
            camera_.setOrbit(v[0], v[1], v[2]);
        } catch (const std::exception& e) {
            error(e.what());
        }
    }
}

float Viewer::aspect() const {
    if (!swapchain_ || !swapchain_->valid()) return 1.0f;
    const VkExtent2D extent = stereo_ ? StereoPreview::eyeExtent(swapchain_->extent()) : swapchain_->extent();
    return float(extent.width) / float(extent.height);
}

View Viewer::frameView() const {
    const View mono = camera_.view(aspect());
    if (stereo_) return stereoFromMono(mono, ipdM_);
    cli::StereoOptions eye = options_.stereo;
    eye.stereo = false;
    eye.ipdM = ipdM_;
    return cli::applyStereoOptions(mono, eye);
}

void Viewer::info(std::string text) {
    fmt::print("preskin-viewer: {}\n", text);
    std::fflush(stdout);  // scripts and tests follow the log while the viewer runs
    messages_.push_back({std::move(text), false, std::chrono::duration<double>(Clock::now() - start_).count()});
    while (messages_.size() > 200) messages_.pop_front();
}

void Viewer::error(std::string text) {
    fmt::print(stderr, "preskin-viewer: error: {}\n", text);
    messages_.push_back({std::move(text), true, std::chrono::duration<double>(Clock::now() - start_).count()});
    while (messages_.size() > 200) messages_.pop_front();
    ++scriptedErrors_;
}

// ---------------------------------------------------------------------------------------------
// Frame loop

bool Viewer::jobsPending() const {
    return sceneJob_.valid() || environmentJob_.valid() || !dropped_.empty() || baker_.busy() || shaders_->compiling();
}

int Viewer::run() {
    auto last = Clock::now();
    for (const std::string& file : options_.drops) dropped_.emplace_back(file);
    while (true) {
        glfwPollEvents();
        // Without --frames, --screenshot is taken from one more frame drawn once the window closes.
        const bool closing = glfwWindowShouldClose(window_);
        const bool closingShot = closing && options_.frames == 0 && !options_.screenshot.empty();
        if (closing && !closingShot) break;
        handleDrops();
        int w = 0;
        int h = 0;
        glfwGetFramebufferSize(window_, &w, &h);
        if (w == 0 || h == 0 || glfwGetWindowAttrib(window_, GLFW_ICONIFIED)) {  // minimised: nothing to show
            if (closing) break;
            pollJobs();
            glfwWaitEventsTimeout(0.1);
            continue;
        }
        if (swapchainDirty_ || !swapchain_->valid() || swapchain_->extent().width != uint32_t(w) ||
            swapchain_->extent().height != uint32_t(h))
            recreateSwapchain();
        if (!swapchain_->valid()) {  // the surface has no area right now
            if (closing) break;
            glfwWaitEventsTimeout(0.05);
            continue;
        }
        pollJobs();

        const auto now = Clock::now();
        const float dtS = std::min(std::chrono::duration<float>(now - last).count(), 0.25f);
        last = now;
        const auto uiBegin = Clock::now();
        overlay_->newFrame();
        handleInput(dtS);
        applyPose(dtS);
        drawUi();
        ImGui::Render();
        uiMs_ = msSince(uiBegin);

        const bool lastFrame =
            (options_.frames > 0 && framesDrawn_ + 1 >= options_.frames && !jobsPending()) || closingShot;
        if (!options_.screenshot.empty() && lastFrame && !captureNext_)
            requestScreenshot(std::filesystem::path(options_.screenshot), options_.screenshotUi);
        if (!drawFrame()) continue;
        if (++framesDrawn_ == 1) info(fmt::format("first frame drawn {:.0f} ms after start", msSince(start_)));
        if (lastFrame) break;
    }

    vk_.vkDeviceWaitIdle(vk_.device);
    for (uint32_t s = 0; s < kFramesInFlight; ++s)
        if (frames_[s].submitted) {
            finishSlot(s);
            frames_[s].submitted = false;
        }
    if (captureNext_) error(fmt::format("screenshot {} not taken: no frame was rendered", captureNext_->string()));
    printSummary();
    const uint32_t validation = context_->validationMessageCount();
    if (validation > 0) {
        fmt::print(stderr, "preskin-viewer: Vulkan validation reported {} message(s) (printed above)\n", validation);
        return 2;
    }
    if (options_.frames > 0 && scriptedErrors_ > 0) {
        fmt::print(stderr, "preskin-viewer: {} error(s) during the scripted run (printed above)\n", scriptedErrors_);
        return 1;
    }
    return 0;
}

void Viewer::handleDrops() {
    // One file at a time, in the order dropped: a scene that arrives starts its own environment's
    // load, and an environment dropped after the scene must replace that one, not race it.
    while (!dropped_.empty() && !sceneJob_.valid() && !environmentJob_.valid()) {
        const std::filesystem::path next = dropped_.front();
        dropped_.erase(dropped_.begin());
        loadFile(next);
    }
}

void Viewer::recreateSwapchain() {
    int w = 0;
    int h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    if (w == 0 || h == 0) return;
    check(vk_.vkDeviceWaitIdle(vk_.device), "vkDeviceWaitIdle");
    for (uint32_t s = 0; s < kFramesInFlight; ++s)
        if (frames_[s].submitted) {
            finishSlot(s);
            frames_[s].submitted = false;
        }
    const VkPresentModeKHR before = swapchain_->presentMode();
    swapchain_->recreate({uint32_t(w), uint32_t(h)}, vsync_);
    overlay_->onSwapchainRecreated();
    swapchainDirty_ = false;
    if (swapchain_->presentMode() != before)
        info(fmt::format("present mode: {}", presentModeName(swapchain_->presentMode())));
}

void Viewer::handleInput(float dtS) {
    const ImGuiIO& io = ImGui::GetIO();
    CameraInput input;
    if (!io.WantCaptureMouse) {
        if (ImGui::IsMouseDown(ImGuiMouseButton_Left) || ImGui::IsMouseDown(ImGuiMouseButton_Right))
            input.dragPx = {io.MouseDelta.x, io.MouseDelta.y};
        input.wheelSteps = io.MouseWheel;
    }
    if (!io.WantCaptureKeyboard) {
        auto axis = [](int plus, int minus) {
            return (ImGui::IsKeyDown(plus) ? 1.0f : 0.0f) - (ImGui::IsKeyDown(minus) ? 1.0f : 0.0f);
        };
        input.moveAxes = {axis(GLFW_KEY_D, GLFW_KEY_A), axis(GLFW_KEY_E, GLFW_KEY_Q), axis(GLFW_KEY_W, GLFW_KEY_S)};
        input.fast = ImGui::IsKeyDown(GLFW_KEY_LEFT_SHIFT) || ImGui::IsKeyDown(GLFW_KEY_RIGHT_SHIFT);
        if (ImGui::IsKeyPressed(GLFW_KEY_F1, false)) showUi_ = !showUi_;
        if (ImGui::IsKeyPressed(GLFW_KEY_F12, false) || ImGui::IsKeyPressed(GLFW_KEY_P, false))
            requestScreenshot(std::nullopt, screenshotWithUi_);
        if (ImGui::IsKeyPressed(GLFW_KEY_V, false)) {
            vsync_ = !vsync_;
            swapchainDirty_ = true;
        }
        if (ImGui::IsKeyPressed(GLFW_KEY_TAB, false))
            camera_.setMode(camera_.mode() == CameraMode::Fly ? CameraMode::Orbit : CameraMode::Fly, aspect());
        if (ImGui::IsKeyPressed(GLFW_KEY_HOME, false)) camera_.reset(scene_.worldBounds(), scene_.cameras);
        if (ImGui::IsKeyPressed(GLFW_KEY_F5, false)) shaders_->requestBuild();
    }
    camera_.update(input, dtS, aspect());
}

bool Viewer::drawFrame() {
    Frame& frame = frames_[slot_];
    const auto waitBegin = Clock::now();
    if (frame.submitted) {
        check(vk_.vkWaitForFences(vk_.device, 1, &frame.fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
        finishSlot(slot_);
        frame.submitted = false;
    }
    uint32_t imageIndex = 0;
    const VkResult acquired = vk_.vkAcquireNextImageKHR(vk_.device, swapchain_->handle(), UINT64_MAX, frame.acquired,
                                                        VK_NULL_HANDLE, &imageIndex);
    if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
        swapchainDirty_ = true;
        return false;
    }
    if (acquired == VK_SUBOPTIMAL_KHR)
        swapchainDirty_ = true;
    else
        check(acquired, "vkAcquireNextImageKHR");
    const double waitMs = msSince(waitBegin);

    const auto cpuBegin = Clock::now();
    check(vk_.vkResetFences(vk_.device, 1, &frame.fence), "vkResetFences");
    recordFrame(frame, imageIndex);
    submit(frame, imageIndex);
    frame.submitted = true;
    const double cpuMs = uiMs_ + msSince(cpuBegin);
    const auto presentBegin = Clock::now();
    present(imageIndex);

    Timing t;
    t.intervalMs = lastFrameStart_ == Clock::time_point{}
        ? 0.0
        : std::chrono::duration<double, std::milli>(waitBegin - lastFrameStart_).count();
    lastFrameStart_ = waitBegin;
    t.cpuMs = cpuMs;
    t.waitMs = waitMs;
    t.presentMs = msSince(presentBegin);
    t.gpuMs = lastStats_.gpuMs;
    t.passes = lastStats_.passes;
    lastTiming_ = t;
    timings_.push_back(t);
    while (timings_.size() > 240) timings_.pop_front();
    if (options_.frames > 0) scriptedTimings_.push_back(t);
    slot_ = (slot_ + 1) % kFramesInFlight;
    return true;
}

void Viewer::recordFrame(Frame& frame, uint32_t imageIndex) {
    check(vk_.vkResetCommandPool(vk_.device, frame.pool, 0), "vkResetCommandPool");
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vk_.vkBeginCommandBuffer(frame.cmd, &begin), "vkBeginCommandBuffer");

    const VkImage image = swapchain_->image(imageIndex);
    if (captureNext_ && !swapchain_->transferSource()) {
        error("screenshot: the window's images cannot be copied on this system");
        captureNext_.reset();
    }
    bool captureScene = captureNext_ && !captureNextUi_;
    bool captureUi = captureNext_ && captureNextUi_;

    if (stereo_ && !swapchain_->transferDestination()) {
        error("stereo preview: the window's images cannot be copied into on this system");
        stereo_ = false;
    }
    const VkImageLayout windowLayout =
        captureScene ? VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL : VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    RenderTarget target;
    target.image = image;
    target.view = swapchain_->view(imageIndex);
    target.format = swapchain_->format();
    target.extent = swapchain_->extent();
    target.layoutBefore = VK_IMAGE_LAYOUT_UNDEFINED;
    target.layoutAfter = windowLayout;
    if (stereo_) {  // both eyes into the preview's layers, copied side by side below
        target.extent = StereoPreview::eyeExtent(swapchain_->extent());
        stereoPreview_->ensure(target.extent, target.format);
        target.image = stereoPreview_->image();
        target.view = stereoPreview_->view();
        target.layoutAfter = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    }
    bool rendered = false;
    if (renderer_) {
        try {
            renderer_->setSettings(settings_);
            renderer_->record(frame.cmd, target, frameView(), slot_);
            if (stereo_) stereoPreview_->copyToWindow(frame.cmd, image, swapchain_->extent(), windowLayout);
            rendered = true;
            lastGoodSettings_ = settings_;
        } catch (const std::exception& e) {
            // Start the command buffer over: the failed recording may have stopped midway.
            error(fmt::format("frame not rendered, settings restored: {}", e.what()));
            settings_ = lastGoodSettings_;
            check(vk_.vkResetCommandPool(vk_.device, frame.pool, 0), "vkResetCommandPool");
            check(vk_.vkBeginCommandBuffer(frame.cmd, &begin), "vkBeginCommandBuffer");
        }
    }
    if (!rendered) captureScene = captureUi = false;  // keep the request for a frame that renders

    if (captureScene) {
        capture_->record(frame.cmd, slot_, image, target.format, swapchain_->extent(), *captureNext_, false);
        imageBarrier(vk_, frame.cmd, image, 1, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                     VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE,
                     VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                     VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
    }
    overlay_->record(frame.cmd, imageIndex, captureUi, !rendered);
    if (captureUi) {
        capture_->record(frame.cmd, slot_, image, target.format, swapchain_->extent(), *captureNext_, true);
        imageBarrier(vk_, frame.cmd, image, 1, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
                     VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE);
    }
    if (captureScene || captureUi) captureNext_.reset();
    check(vk_.vkEndCommandBuffer(frame.cmd), "vkEndCommandBuffer");
}

void Viewer::submit(Frame& frame, uint32_t imageIndex) {
    VkSemaphoreSubmitInfo wait{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
    wait.semaphore = frame.acquired;
    // Only writing the image has to wait for it; the shadow pass may start before.
    wait.stageMask = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
    VkSemaphoreSubmitInfo signal{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
    signal.semaphore = swapchain_->renderFinished(imageIndex);
    signal.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    VkCommandBufferSubmitInfo cmdInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cmdInfo.commandBuffer = frame.cmd;
    VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    submit.waitSemaphoreInfoCount = 1;
    submit.pWaitSemaphoreInfos = &wait;
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &cmdInfo;
    submit.signalSemaphoreInfoCount = 1;
    submit.pSignalSemaphoreInfos = &signal;
    check(vk_.vkQueueSubmit2(context_->queue(), 1, &submit, frame.fence), "vkQueueSubmit2");
}

void Viewer::present(uint32_t imageIndex) {
    const VkSwapchainKHR swapchain = swapchain_->handle();
    const VkSemaphore wait = swapchain_->renderFinished(imageIndex);
    VkPresentInfoKHR info{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
    info.waitSemaphoreCount = 1;
    info.pWaitSemaphores = &wait;
    info.swapchainCount = 1;
    info.pSwapchains = &swapchain;
    info.pImageIndices = &imageIndex;
    const VkResult presented = vk_.vkQueuePresentKHR(context_->queue(), &info);
    if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR)
        swapchainDirty_ = true;
    else
        check(presented, "vkQueuePresentKHR");
}

void Viewer::finishSlot(uint32_t slot) {
    if (renderer_) {
        FrameStats stats = renderer_->frameStats(slot);
        if (!stats.passes.empty() || stats.lightCount > 0) lastStats_ = std::move(stats);
    }
    if (capture_->pending(slot)) {
        try {
            if (auto written = capture_->finish(slot)) info(fmt::format("screenshot written: {}", written->string()));
        } catch (const std::exception& e) {
            error(fmt::format("screenshot: {}", e.what()));
        }
    }
}

void Viewer::printSummary() const {
    if (scriptedTimings_.empty()) return;
    // The first frames pay for pipeline creation and first uploads; report the rest.
    const size_t skip = std::min<size_t>(scriptedTimings_.size() / 2, 3);
    double interval = 0.0, cpu = 0.0, present = 0.0, gpu = 0.0;
    size_t n = 0, gpuN = 0;
    std::map<std::string, std::pair<double, size_t>> passes;
    for (size_t i = skip; i < scriptedTimings_.size(); ++i) {
        const Timing& t = scriptedTimings_[i];
        if (t.intervalMs <= 0.0) continue;
        interval += t.intervalMs;
        cpu += t.cpuMs;
        present += t.presentMs;
        ++n;
        if (t.gpuMs > 0.0) {
            gpu += t.gpuMs;
            ++gpuN;
        }
        for (const PassTime& p : t.passes) {
            passes[p.name].first += p.gpuMs;
            passes[p.name].second += 1;
        }
    }
    if (n == 0) return;
    std::string passText;
    for (const auto& [name, sum] : passes)
        passText += fmt::format("{}{} {:.2f}", passText.empty() ? "" : ", ", name, sum.first / double(sum.second));
    fmt::print(
        "preskin-viewer: {} frames at {}x{} on {} ({}): frame {:.2f} ms, cpu {:.2f} ms, present {:.2f} ms, "
        "gpu {:.2f} ms ({})\n",
        n, swapchain_->extent().width, swapchain_->extent().height, context_->deviceName(),
        presentModeName(swapchain_->presentMode()), interval / double(n), cpu / double(n), present / double(n),
        gpuN ? gpu / double(gpuN) : 0.0, passText.empty() ? "no timestamps" : passText);
}

}  // namespace preskin::viewer
