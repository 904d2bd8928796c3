// preskin-viewer's window, Vulkan frame loop and content handling (see Viewer.h); the panels
// are in ViewerPanels.cpp.
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

std::string lowerExtension(const std::filesystem::path& p) {
    std::string ext = p.extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

// The shadow-casting directional light (as the renderer picks it), else the first directional.
int findKeyLight(const std::vector<Light>& lights) {
    for (size_t i = 0; i < lights.size(); ++i)
        if (lights[i].type == LightType::Directional && lights[i].castsShadow) return static_cast<int>(i);
    for (size_t i = 0; i < lights.size(); ++i)
        if (lights[i].type == LightType::Directional) return static_cast<int>(i);
    return -1;
}

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
            if (shaders_->enabled()) shaders_->requestBuild();
            else error("--compile-shaders: no shader sources to compile");
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
        if (windowOpen) fmt::print(stderr, "preskin-viewer: GLFW {}: {}\n", code, text);
        else glfwReason = text ? text : "";
    });
    auto failed = [](const char* field, const char* otherwise, const char* hint) {
        return Error(fmt::format("GLFW: {}: {}{}", field, glfwReason.empty() ? otherwise : glfwReason, hint));
    };
    if (!glfwInit()) throw failed("display", "cannot open it", " (without a display, run under xvfb-run)");
    if (!glfwVulkanSupported()) throw failed("Vulkan", "no Vulkan loader or driver found", "");
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    window_ = glfwCreateWindow(static_cast<int>(options_.widthPx), static_cast<int>(options_.heightPx), "preskin-viewer",
                               nullptr, nullptr);
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
    try {
        scene = cli::loadScene(scenePath, options_.common);
        for (const std::string& w : scene.warnings) info("warning: " + w);
        cli::applySkinOption(scene, options_.common);
    } catch (const std::exception& e) {
        error(fmt::format("scene not loaded: {}", e.what()));
        scene = Scene{};
    }

    environmentIntensity_ = options_.common.envIntensity >= 0.0f ? options_.common.envIntensity
                            : (options_.common.env.empty() && scene.environmentPath) ? scene.environmentIntensity
                                                                                     : 1.0f;
    environmentFromScene_ = options_.common.env.empty();
    try {
        environment_ = cli::loadEnvironment(scene, options_.common);
        environmentRotationDeg_ = glm::degrees(environment_.rotationY());
        environmentName_ = !options_.common.env.empty() ? options_.common.env
                           : scene.environmentPath      ? scene.environmentPath->string()
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

    adoptScene(std::move(scene), scenePath);
    if (!options_.animation.empty() || options_.timeS || options_.play) {
        try {
            if (scene_.animations.empty()) throw Error("the scene has no animations");
            const Animation& a = findAnimation(scene_, options_.animation.empty() ? std::string("0") : options_.animation);
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
// Content

void Viewer::adoptScene(Scene scene, const std::filesystem::path& path) {
    scene_ = std::move(scene);
    loadedMaterials_ = scene_.materials;
    scenePath_ = path;
    cli::CommonOptions withoutScatter = options_.common;
    withoutScatter.lights = 0;
    sceneLights_ = cli::sceneLights(scene_, withoutScatter);
    settings_.environmentLights = cli::environmentLightCount(scene_, options_.common);
    keyLight_ = findKeyLight(sceneLights_);
    selectedMaterial_ = -1;
    for (size_t i = 0; i < scene_.materials.size() && selectedMaterial_ < 0; ++i)
        if (scene_.materials[i].skin) selectedMaterial_ = static_cast<int>(i);
    if (selectedMaterial_ < 0 && !scene_.materials.empty()) selectedMaterial_ = 0;
    camera_.reset(scene_.worldBounds(), scene_.cameras);
    morphOverrides_.clear();
    animation_ = scene_.animations.empty() ? -1 : 0;
    animationTimeS_ = animation_ >= 0 ? scene_.animations[0].startS() : 0.0f;
    playing_ = false;
    prepareProfiles();
    rebuildRenderer("scene loaded");
}

void Viewer::prepareProfiles() {
    const auto begin = Clock::now();
    auto defaultLuts = std::make_shared<const LutSet>(luts_ ? *luts_ : LutSet::loadDefault());
    try {
        profiles_ = cli::loadProfiles(scene_, options_.common, defaultLuts);
        for (const std::string& w : profiles_->warnings()) info("warning: " + w);
        if (!scene_.profiles.empty()) {
            const ProfileLoadStats& st = profiles_->stats();
            info(fmt::format("{} profiles ready in {:.0f} ms ({} from the cache, {} baked, {} LUT folders)",
                             scene_.profiles.size(), msSince(begin), st.cacheHits, st.baked, st.lutFolders));
        }
    } catch (const std::exception& e) {
        error(fmt::format("profiles: {} (only the default set is loaded)", e.what()));
        profiles_.emplace(defaultLuts);
    }
    preparedLayers_.clear();
    for (size_t i = 0; i < profiles_->layerCount(); ++i) preparedLayers_.push_back(profiles_->layerPointer(i));
    LayerEdit fresh = startEdit_;
    fresh.choice = ProfileChoice::Loaded;
    layerEdits_.assign(profiles_->layerCount(), fresh);
}

size_t Viewer::editedLayer() const {
    if (selectedMaterial_ < 0 || size_t(selectedMaterial_) >= scene_.materials.size()) return 0;
    const Material& m = scene_.materials[size_t(selectedMaterial_)];
    const size_t layer = m.skin ? size_t(m.skin->profile + 1) : 0;
    return profiles_ && layer < profiles_->layerCount() ? layer : 0;
}

void Viewer::applyBakedLayer(size_t layer, std::shared_ptr<const LutSet> luts) {
    if (!profiles_ || layer >= profiles_->layerCount()) return;
    profiles_->setLayer(layer, luts);
    if (layer == 0) luts_ = *luts;
    if (!renderer_) return;
    try {
        renderer_->setProfileLayer(layer, *luts);  // only this layer is uploaded
    } catch (const std::exception&) {
        renderer_->setProfiles(*profiles_);  // larger tables than the arrays': rebuild them
    }
}

void Viewer::rebuildRenderer(const char* why) {
    const auto begin = Clock::now();
    renderer_.reset();  // waits for the device; frees the old scene's memory before the upload
    try {
        renderer_ = profiles_ ? std::make_unique<Renderer>(*context_, scene_, environment_, *profiles_, settings_)
                              : std::make_unique<Renderer>(*context_, scene_, environment_, luts_ ? &*luts_ : nullptr, settings_);
    } catch (const std::exception& e) {
        error(fmt::format("renderer: {}", e.what()));
        return;
    }
    applyLights();
    if (!shaderOverrides_.empty()) {
        try {
            renderer_->setShaderOverrides(shaderOverrides_);
        } catch (const std::exception& e) {
            error(fmt::format("reloaded shaders dropped, built-in ones used: {}", e.what()));
            shaderOverrides_.clear();
        }
    }
    info(fmt::format("renderer built ({}) in {:.0f} ms", why, msSince(begin)));
}

void Viewer::applyPose(float dtS) {
    if (!renderer_) return;
    const Animation* animation =
        animation_ >= 0 && size_t(animation_) < scene_.animations.size() ? &scene_.animations[size_t(animation_)] : nullptr;
    if (animation && playing_) {
        const float start = animation->startS();
        const float length = animation->endS() - start;
        animationTimeS_ += dtS * playbackSpeed_;
        if (length > 0.0f) animationTimeS_ = start + std::fmod(std::fmod(animationTimeS_ - start, length) + length, length);
        else animationTimeS_ = start;
    }
    ScenePose pose = posedScene(scene_, animation ? animationNodePose(scene_, *animation, animationTimeS_) : restNodePose(scene_));
    for (size_t i = 0; i < pose.instances.size() && i < morphOverrides_.size(); ++i)
        if (!morphOverrides_[i].empty()) pose.instances[i].morphWeights = morphOverrides_[i];
    try {
        renderer_->setPose(pose);
    } catch (const std::exception& e) {
        error(fmt::format("pose: {}", e.what()));
        morphOverrides_.clear();
    }
}

void Viewer::applyLights() {
    if (!renderer_) return;
    std::vector<Light> lights = sceneLights_;
    if (scatteredLights_ > 0) {
        const auto scattered = scatterLights(scene_.worldBounds(), scatteredLights_, scatterSeed_);
        lights.insert(lights.end(), scattered.begin(), scattered.end());
    }
    renderer_->setLights(lights);
}

void Viewer::loadFile(const std::filesystem::path& path) {
    const std::string ext = lowerExtension(path);
    if (ext == ".gltf" || ext == ".glb") startSceneLoad(path);
    else if (ext == ".hdr" || ext == ".exr") startEnvironmentLoad(path, environmentIntensity_);
    else error(fmt::format("{}: not a scene (.gltf, .glb) or an environment (.hdr, .exr)", path.string()));
}

void Viewer::startSceneLoad(const std::filesystem::path& path) {
    if (sceneJob_.valid()) {
        error(fmt::format("{}: a scene is still loading; try again when it is done", path.string()));
        return;
    }
    info(fmt::format("loading {}", path.string()));
    const cli::CommonOptions common = options_.common;
    sceneJob_ = std::async(std::launch::async, [path, common] {
        SceneLoad result;
        result.path = path;
        const auto begin = Clock::now();
        try {
            Scene scene = cli::loadScene(path, common);
            cli::applySkinOption(scene, common);
            result.scene = std::move(scene);
        } catch (const std::exception& e) {
            result.error = e.what();
        }
        result.loadMs = msSince(begin);
        return result;
    });
}

void Viewer::startEnvironmentLoad(std::optional<std::filesystem::path> path, float intensity,
                                  std::optional<float> rotationDeg) {
    if (environmentJob_.valid()) {
        error("an environment is still loading; try again when it is done");
        return;
    }
    // Loads like `preskin render` does (cli::loadEnvironment): a file, else the scene's own.
    cli::CommonOptions common = options_.common;
    common.env = path ? path->string() : std::string();
    common.envIntensity = intensity;
    if (rotationDeg) common.envRotationDeg = rotationDeg;
    Scene sceneEnvironment;  // only the scene's environment fields
    sceneEnvironment.environmentPath = scene_.environmentPath;
    sceneEnvironment.environmentIntensity = scene_.environmentIntensity;
    sceneEnvironment.environmentRotation = scene_.environmentRotation;
    const std::string name = path                      ? path->string()
                             : scene_.environmentPath ? scene_.environmentPath->string()
                                                      : std::string("uniform grey");
    environmentJob_ = std::async(std::launch::async, [common, sceneEnvironment, name, intensity, fromScene = !path] {
        EnvironmentLoad result;
        result.name = name;
        result.intensity = intensity;
        result.fromScene = fromScene;
        try {
            result.environment = cli::loadEnvironment(sceneEnvironment, common);
        } catch (const std::exception& e) {
            result.error = e.what();
        }
        return result;
    });
}

void Viewer::applyShaderBuild(ShaderBuild build) {
    const std::string changed = build.changedFiles.empty() ? std::string("requested") : [&] {
        std::string list;
        for (const std::string& f : build.changedFiles) list += (list.empty() ? "" : ", ") + f;
        return list;
    }();
    if (!build.ok) {
        shaderLog_ = build.log;
        shaderLogIsError_ = true;
        error(fmt::format("shaders ({}) did not compile; the last good pipelines keep running", changed));
        return;
    }
    try {
        if (renderer_) renderer_->setShaderOverrides(build.spirvByFile);
        shaderOverrides_ = std::move(build.spirvByFile);
        shaderLog_ = build.log.empty() ? fmt::format("compiled {} stages in {:.0f} ms", shaderOverrides_.size(),
                                                     build.compileMs)
                                       : build.log;
        shaderLogIsError_ = false;
        info(fmt::format("shaders reloaded ({}) in {:.0f} ms", changed, build.compileMs));
    } catch (const std::exception& e) {
        shaderLog_ = std::string(e.what()) + "\n" + build.log;
        shaderLogIsError_ = true;
        error(fmt::format("reloaded shaders rejected, the last good pipelines keep running: {}", e.what()));
    }
}

void Viewer::requestBake(size_t layer) {
    if (!profiles_ || layer >= layerEdits_.size()) return;
    const LayerEdit& edit = layerEdits_[layer];
    if (edit.choice == ProfileChoice::Loaded) {
        applyBakedLayer(layer, preparedLayers_.at(layer));
        lutStatus_ = "using " + (layer == 0 ? lutsName_ : scene_.profiles[layer - 1].name + " as loaded");
        return;
    }
    try {
        const DiffusionProfile profile =
            edit.choice == ProfileChoice::Burley
                ? DiffusionProfile::burley(glm::dvec3(edit.albedo[0], edit.albedo[1], edit.albedo[2]),
                                           glm::dvec3(edit.mfpMm[0], edit.mfpMm[1], edit.mfpMm[2]))
                : DiffusionProfile::deonLuebke();
        baker_.request(layer, profile, LutBakeSettings::withSize(lutSize_));
    } catch (const std::exception& e) {
        error(fmt::format("profile: {}", e.what()));
    }
}

void Viewer::requestScreenshot(std::optional<std::filesystem::path> path, bool withUi) {
    if (!path) {
        char stamp[32];
        const std::time_t now = std::time(nullptr);
        std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", std::localtime(&now));
        path = fmt::format("preskin-viewer-{}-{}.png", stamp, ++screenshotCounter_);
    }
    try {
        checkOutputPath(*path, OutputEncoding::DisplaySrgb8);
    } catch (const std::exception& e) {
        error(fmt::format("screenshot: {}", e.what()));
        return;
    }
    captureNext_ = *path;
    captureNextUi_ = withUi;
}

void Viewer::pollJobs() {
    shaders_->poll();
    if (auto build = shaders_->takeResult()) applyShaderBuild(std::move(*build));

    if (auto baked = baker_.poll()) {
        if (baked->luts) {
            const auto begin = Clock::now();
            auto luts = std::make_shared<const LutSet>(std::move(*baked->luts));
            applyBakedLayer(baked->layer, luts);
            lutStatus_ = fmt::format("{} (layer {}): baked in {:.0f} ms, uploaded in {:.0f} ms", luts->profile().name(),
                                     baked->layer, baked->bakeMs, msSince(begin));
            info("LUTs " + lutStatus_);
        } else {
            error(fmt::format("LUT bake failed: {}", baked->error));
        }
    }

    if (sceneJob_.valid() && sceneJob_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
        SceneLoad loaded = sceneJob_.get();
        if (!loaded.scene) {
            error(fmt::format("scene not loaded, keeping the current one: {}", loaded.error));
        } else {
            for (const std::string& w : loaded.scene->warnings) info("warning: " + w);
            info(fmt::format("{} loaded in {:.0f} ms", loaded.path.string(), loaded.loadMs));
            const bool newEnvironment = environmentFromScene_ && (loaded.scene->environmentPath || scene_.environmentPath);
            scenePathInput_ = loaded.path.string();
            adoptScene(std::move(*loaded.scene), loaded.path);
            if (newEnvironment) startEnvironmentLoad(std::nullopt, scene_.environmentIntensity);
        }
    }

    if (environmentJob_.valid() && environmentJob_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
        EnvironmentLoad loaded = environmentJob_.get();
        if (!loaded.environment) {
            error(fmt::format("environment not loaded, keeping the current one: {}", loaded.error));
        } else {
            environment_ = std::move(*loaded.environment);
            environmentName_ = loaded.name;
            environmentPathInput_ = loaded.name;
            environmentIntensity_ = loaded.intensity;
            environmentFromScene_ = loaded.fromScene;
            environmentRotationDeg_ = glm::degrees(environment_.rotationY());
            if (renderer_) renderer_->setEnvironment(environment_);
            info(fmt::format("environment {} (intensity {:.2f})", loaded.name, loaded.intensity));
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Frame loop

bool Viewer::jobsPending() const {
    return sceneJob_.valid() || environmentJob_.valid() || baker_.busy() || shaders_->compiling();
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
    for (const std::filesystem::path& p : std::exchange(dropped_, {})) loadFile(p);
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
    if (swapchain_->presentMode() != before) info(fmt::format("present mode: {}", presentModeName(swapchain_->presentMode())));
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
    const VkResult acquired =
        vk_.vkAcquireNextImageKHR(vk_.device, swapchain_->handle(), UINT64_MAX, frame.acquired, VK_NULL_HANDLE, &imageIndex);
    if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
        swapchainDirty_ = true;
        return false;
    }
    if (acquired == VK_SUBOPTIMAL_KHR) swapchainDirty_ = true;
    else check(acquired, "vkAcquireNextImageKHR");
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
        imageBarrier(vk_, frame.cmd, image, 1, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                     VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
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
    if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR) swapchainDirty_ = true;
    else check(presented, "vkQueuePresentKHR");
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
    fmt::print("preskin-viewer: {} frames at {}x{} on {} ({}): frame {:.2f} ms, cpu {:.2f} ms, present {:.2f} ms, "
               "gpu {:.2f} ms ({})\n",
               n, swapchain_->extent().width, swapchain_->extent().height, context_->deviceName(),
               presentModeName(swapchain_->presentMode()), interval / double(n), cpu / double(n), present / double(n),
               gpuN ? gpu / double(gpuN) : 0.0, passText.empty() ? "no timestamps" : passText);
}

}  // namespace preskin::viewer
