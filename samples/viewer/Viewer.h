// preskin-viewer: a GLFW window whose swapchain images the preskin Renderer draws into
// (Renderer::record into the viewer's command buffer), with Dear ImGui panels on top.
//
// What it owns and how a frame goes:
//  - Two frames in flight (the Renderer's two frame slots): per slot a command pool, a fence and
//    an "image acquired" semaphore; per swapchain image a "rendering finished" semaphore.
//  - Per frame: wait for the slot's fence (then read its GPU timings and write its screenshot),
//    acquire, record the renderer (swapchain image UNDEFINED -> COLOR_ATTACHMENT, or
//    TRANSFER_SRC when a screenshot without panels is taken), the overlay pass, submit, present.
//  - Work that would stall a frame runs on worker threads: glTF and environment loading, LUT
//    baking, shader compilation; the main thread only swaps the results in.
//  - Material edits (curvature source and scale, normal-map LOD biases, ...) rebuild the
//    Renderer from the edited Scene, since the Renderer reads materials once.
//  - Bad input (a file that does not load, a missing environment, a shader that does not
//    compile) is shown in the Messages panel and the viewer keeps running with what it had.
// Scripted runs (--frames N) draw N frames and then on until no load, bake or shader build is
// pending; the screenshot (--screenshot) is taken from the last frame. Without --frames, the
// screenshot is taken from one more frame drawn when the window is closed.
// Exit status: 0; 1 on a start-up error or, in scripted runs, any error reported on the way
// (load, shader, screenshot); 2 when Vulkan validation reported anything.
// Stereo: --stereo (or the Camera panel) shows a stereo pair around the camera side by side,
// drawn in the renderer's one multi-eye pass (see StereoPreview.h); --eye shows one eye alone.
// Animation: a timeline (play, pause, scrub, speed) and morph-weight sliders pose the scene every
// frame through Renderer::setPose (--animation, --time, --play at start).
// Limits: one window; loads replace the whole scene.
#pragma once

#include "CameraController.h"
#include "ImageCapture.h"
#include "LutBaker.h"
#include "Overlay.h"
#include "ShaderReloader.h"
#include "StereoPreview.h"
#include "Swapchain.h"
#include "ViewerOptions.h"
#include "VulkanFunctions.h"

#include <preskin/Context.h>
#include <preskin/Environment.h>
#include <preskin/LutSet.h>
#include <preskin/ProfileLibrary.h>
#include <preskin/Renderer.h>
#include <preskin/Scene.h>

#include <array>
#include <chrono>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <future>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

struct GLFWwindow;

namespace preskin::viewer {

class Viewer {
public:
    // Creates the window, the device and everything on it, and loads the start-up content
    // (a scene or environment that fails to load is reported in the UI, not thrown).
    // Throws preskin::Error when the window or a Vulkan device cannot be had.
    explicit Viewer(ViewerOptions options);
    ~Viewer();
    Viewer(const Viewer&) = delete;
    Viewer& operator=(const Viewer&) = delete;

    // Runs until the window closes (or --frames are drawn); returns the exit status.
    int run();

private:
    static constexpr uint32_t kFramesInFlight = 2;

    struct Frame {
        VkCommandPool pool = VK_NULL_HANDLE;
        VkCommandBuffer cmd = VK_NULL_HANDLE;
        VkFence fence = VK_NULL_HANDLE;
        VkSemaphore acquired = VK_NULL_HANDLE;
        bool submitted = false;
    };
    struct Message {
        std::string text;
        bool error = false;
        double timeS = 0.0;
    };
    struct Timing {
        double intervalMs = 0.0;  // from the previous frame's start
        double cpuMs = 0.0;       // panels, recording, submission
        double waitMs = 0.0;      // waiting for the frame slot's fence and the swapchain image
        double presentMs = 0.0;   // in vkQueuePresentKHR
        double gpuMs = 0.0;
        std::vector<PassTime> passes;
    };
    struct SceneLoad {
        std::optional<Scene> scene;
        std::filesystem::path path;
        std::string error;
        double loadMs = 0.0;
    };
    struct EnvironmentLoad {
        std::optional<Environment> environment;
        std::string name;
        std::string error;
        float intensity = 1.0f;
        bool fromScene = false;
    };
    enum class ProfileChoice { Loaded, DeonLuebke, Burley };
    // The viewer's edit of one LUT layer (the default set, or one of the scene's profiles).
    struct LayerEdit {
        ProfileChoice choice = ProfileChoice::Loaded;
        std::array<float, 3> albedo{};
        std::array<float, 3> mfpMm{};
    };

    // Set-up and tear-down.
    void shutdown() noexcept;
    void createWindow();
    void createVulkan();
    void createFrames();
    void destroyFrames();
    void uploadFonts();
    void loadStartupContent();

    // The frame loop.
    bool drawFrame();
    void recordFrame(Frame& frame, uint32_t imageIndex);
    void submit(Frame& frame, uint32_t imageIndex);
    void present(uint32_t imageIndex);
    void finishSlot(uint32_t slot);
    void recreateSwapchain();
    void handleInput(float dtS);
    void handleDrops();
    void pollJobs();
    float aspect() const;    // of the window, or of one eye in the stereo preview
    View frameView() const;  // the camera's view, its stereo pair, or one eye of the pair
    bool jobsPending() const;
    void printSummary() const;

    // Content changes.
    void loadFile(const std::filesystem::path& path);
    void startSceneLoad(const std::filesystem::path& path);
    // rotationDeg: the turn about +Y; unset: --env-rotation's, or the scene's.
    void startEnvironmentLoad(std::optional<std::filesystem::path> path, float intensity,
                              std::optional<float> rotationDeg = std::nullopt);
    // `why`: said in the log line of the renderer's rebuild.
    void adoptScene(Scene scene, const std::filesystem::path& path, const char* why);
    void rebuildRenderer(const char* why);
    void applyLights();
    void applyPose(float dtS);  // advances playback and gives the renderer this frame's pose
    void applyShaderBuild(ShaderBuild build);
    void prepareProfiles();      // the scene's profiles as LUT layers (ProfileLibrary)
    size_t editedLayer() const;  // the LUT layer of the selected material's profile
    void requestBake(size_t layer);
    void applyBakedLayer(size_t layer, std::shared_ptr<const LutSet> luts);
    void requestScreenshot(std::optional<std::filesystem::path> path, bool withUi);

    // Panels (ViewerPanels.cpp).
    void drawUi();
    void panelScene();
    void panelCamera();
    void panelAnimation();
    void panelTechniques();
    void panelMaterial();
    void panelProfile();
    void panelLights();
    bool panelAreaLights();
    void panelDebug();
    void panelTiming();
    void panelShaders();
    void panelMessages();
    void statusBar();

    void info(std::string text);
    void error(std::string text);

    ViewerOptions options_;
    GLFWwindow* window_ = nullptr;
    std::unique_ptr<Context> context_;
    VulkanFunctions vk_;
    VkSurfaceKHR surface_ = VK_NULL_HANDLE;
    std::unique_ptr<Swapchain> swapchain_;
    std::unique_ptr<Overlay> overlay_;
    std::unique_ptr<ImageCapture> capture_;
    std::unique_ptr<StereoPreview> stereoPreview_;
    bool stereo_ = false;  // side-by-side preview of a stereo pair around the camera
    float ipdM_ = 0.063f;

    // Animation: which one (-1: the rest pose), its time, playback, and morph weights set by hand
    // (per scene instance; empty: the animation's).
    int animation_ = -1;
    float animationTimeS_ = 0.0f;
    bool playing_ = false;
    float playbackSpeed_ = 1.0f;
    std::vector<std::vector<float>> morphOverrides_;
    std::array<Frame, kFramesInFlight> frames_{};
    uint32_t slot_ = 0;
    bool swapchainDirty_ = false;
    bool vsync_ = true;
    bool showUi_ = true;
    std::vector<std::filesystem::path> dropped_;

    // Content and what the renderer was built from.
    Scene scene_;                            // with the viewer's material edits
    std::vector<Material> loadedMaterials_;  // as loaded, for "reset edits"
    std::filesystem::path scenePath_;
    Environment environment_;
    std::string environmentName_;
    bool environmentFromScene_ = false;
    float environmentIntensity_ = 1.0f;
    float environmentRotationDeg_ = 0.0f;  // the loaded environment's turn, as the panel's slider shows it
    std::optional<LutSet> luts_;           // the default set (layer 0) as loaded
    std::string lutsName_;
    std::optional<ProfileLibrary> profiles_;                     // what the renderer's LUT arrays hold
    std::vector<std::shared_ptr<const LutSet>> preparedLayers_;  // the layers as prepared, for "as loaded"
    std::vector<LayerEdit> layerEdits_;                          // per layer
    std::unique_ptr<Renderer> renderer_;
    RenderSettings settings_;
    RenderSettings lastGoodSettings_;
    std::vector<Light> sceneLights_;  // the scene's lights (or the default key light), with edits
    int keyLight_ = -1;               // index in sceneLights_ of the shadow-casting directional light
    bool showLightGizmos_ = true;     // area light outlines over the view (LightGizmos.h)
    uint32_t scatteredLights_ = 0;
    uint32_t scatterSeed_ = 1;
    float scatterDensity_ = 0.0f;  // lights per point (--light-density); 0: ranges of the scene's size
    int selectedMaterial_ = -1;
    CameraController camera_;

    // Workers.
    std::unique_ptr<ShaderReloader> shaders_;
    std::map<std::string, std::vector<uint32_t>> shaderOverrides_;
    std::string shaderLog_;
    bool shaderLogIsError_ = false;
    LutBaker baker_;
    LayerEdit startEdit_;  // --profile, --albedo, --mfp: the default layer's first edit
    int lutSize_ = 256;
    std::string lutStatus_;
    std::future<SceneLoad> sceneJob_;
    std::future<EnvironmentLoad> environmentJob_;
    std::string scenePathInput_;
    std::string environmentPathInput_;

    // Messages, timing, screenshots, scripted runs.
    std::deque<Message> messages_;
    std::deque<Timing> timings_;
    Timing lastTiming_;
    FrameStats lastStats_;  // of the last frame the GPU finished
    std::vector<Timing> scriptedTimings_;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
    std::chrono::steady_clock::time_point lastFrameStart_{};
    double uiMs_ = 0.0;
    std::optional<std::filesystem::path> captureNext_;
    bool captureNextUi_ = false;
    bool screenshotWithUi_ = false;  // for the screenshot key and button
    uint32_t screenshotCounter_ = 0;
    uint64_t framesDrawn_ = 0;
    uint32_t scriptedErrors_ = 0;
};

}  // namespace preskin::viewer
