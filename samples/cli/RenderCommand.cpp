// `preskin render`: loads a glTF scene (the bundled head by default), renders one frame
// headless (mono, or both eyes of a stereo pair side by side) and writes it as PNG (tone-mapped)
// or EXR (linear), printing the frame time.
#include "Commands.h"
#include "CommandLine.h"  // samples/common
#include "Options.h"

#include <preskin/Context.h>
#include <preskin/Environment.h>
#include <preskin/Error.h>
#include <preskin/Renderer.h>
#include <preskin/Scene.h>
#include <preskin/View.h>

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <vector>
#include <memory>
#include <string>

namespace preskin::cli {

namespace {

struct RenderOptions {
    std::string scene;
    std::string out = "render.png";
    uint32_t width = 1280;
    uint32_t height = 720;
    std::string camera;
    std::string orbit;
    uint32_t frames = 1;
    StereoOptions stereo;
    CommonOptions common;
};

void run(const RenderOptions& o) {
    const std::filesystem::path outPath(o.out);
    const OutputEncoding encoding = encodingFor(outPath);
    checkOutputPath(outPath, encoding);
    const std::filesystem::path scenePath = o.scene.empty() ? defaultScenePath() : std::filesystem::path(o.scene);
    // Every option is checked before anything is loaded.
    const std::vector<float> orbit = o.orbit.empty() ? std::vector<float>{} : parseFloats(o.orbit, 3, "--orbit");

    Scene scene = loadScene(scenePath, o.common);
    for (const std::string& warning : scene.warnings) fmt::print(stderr, "preskin: warning: {}\n", warning);
    applySkinOption(scene, o.common);
    const Environment environment = loadEnvironment(scene, o.common);
    auto context = Context::create(contextDesc(o.common));
    const LutSet luts = loadLuts(o.common);
    Renderer renderer(*context, scene, environment, &luts, renderSettings(o.common));
    applyLightOptions(renderer, scene, o.common);

    const float aspect = float(o.width) / float(o.height);
    View view;
    if (!o.camera.empty()) {
        const Camera* camera = nullptr;
        for (const Camera& c : scene.cameras)
            if (c.name == o.camera) camera = &c;
        if (!camera) throw Error(fmt::format("--camera {}: {} has no camera of that name", o.camera, scenePath.string()));
        view = cameraView(*camera, aspect, scene.worldBounds());
    } else if (!o.orbit.empty()) {
        view = orbitView(scene.worldBounds(), orbit[0], orbit[1], orbit[2], aspect);
    } else {
        view = frameBoundsView(scene.worldBounds(), aspect);
    }
    view = applyStereoOptions(view, o.stereo);

    // One warm-up frame (first-use costs), then the measured ones; the frame with the median
    // GPU time is reported (frames are identical, so any of them is the image).
    renderer.render(view, o.width, o.height, encoding);
    RenderedImage image;
    std::vector<FrameStats> frames;
    for (uint32_t i = 0; i < o.frames; ++i) {
        image = renderer.render(view, o.width, o.height, encoding);
        frames.push_back(renderer.frameStats());
    }
    std::sort(frames.begin(), frames.end(),
              [](const FrameStats& a, const FrameStats& b) { return a.gpuMs + a.wallMs < b.gpuMs + b.wallMs; });
    const FrameStats stats = frames[frames.size() / 2];
    writeImage(outPath, image);
    reportValidation(*context);
    fmt::print("preskin: wrote {} ({}x{}{})\n", outPath.string(), image.width * image.eyes, image.height,
               image.eyes > 1 ? fmt::format(", {} eyes side by side", image.eyes) : "");
    fmt::print("preskin: frame time on {}{}: {}\n", context->deviceName(),
               o.frames > 1 ? fmt::format(" (median of {} frames)", o.frames) : "", formatStats(stats));
}

}  // namespace

void addRenderCommand(CLI::App& app) {
    auto options = std::make_shared<RenderOptions>();
    CLI::App* cmd = app.add_subcommand("render", "Render a glTF scene headless to a PNG or EXR image");
    cmd->add_option("scene", options->scene, "glTF scene (.gltf or .glb); default: the bundled head scene");
    cmd->add_option("--out,-o", options->out, "Output image: .png (tone-mapped) or .exr (linear)")
        ->capture_default_str();
    cmd->add_option("--width", options->width, "Image width in pixels")->capture_default_str()->check(wholeNumberIn(1, 16384));
    cmd->add_option("--height", options->height, "Image height in pixels")
        ->capture_default_str()
        ->check(wholeNumberIn(1, 16384));
    auto* camera = cmd->add_option("--camera", options->camera, "Use the scene's camera of this name");
    auto* orbit = cmd->add_option("--orbit", options->orbit,
                                  "Orbit the scene's centre: YAW,PITCH,DIST in degrees, degrees, metres (DIST 0: fit)");
    camera->excludes(orbit);
    cmd->add_option("--frames", options->frames, "Measured frames after one warm-up; the median is reported")
        ->capture_default_str()
        ->check(wholeNumberIn(1, 1000));
    addStereoOptions(*cmd, options->stereo);
    addCommonOptions(*cmd, options->common);
    cmd->callback([options] { run(*options); });
}

}  // namespace preskin::cli
