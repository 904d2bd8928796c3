// `preskin render`: loads a glTF scene (the bundled head by default), renders one frame
// headless and writes it as PNG (tone-mapped) or EXR (linear), printing the frame time.
#include "Commands.h"
#include "Options.h"  // samples/common

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
    ViewOptions view;
    uint32_t frames = 1;
    CommonOptions common;
};

void run(const RenderOptions& o) {
    const std::filesystem::path outPath(o.out);
    const OutputEncoding encoding = encodingFor(outPath);
    checkOutputPath(outPath, encoding);
    const std::filesystem::path scenePath = o.scene.empty() ? defaultScenePath() : std::filesystem::path(o.scene);

    Scene scene = Scene::load(scenePath);
    for (const std::string& warning : scene.warnings) fmt::print(stderr, "preskin: warning: {}\n", warning);
    applySkinOption(scene, o.common);
    const Environment environment = loadEnvironment(scene, o.common);
    auto context = Context::create(contextDesc(o.common));
    const LutSet luts = loadLuts(o.common);
    Renderer renderer(*context, scene, environment, &luts, renderSettings(o.common));
    applyLightOptions(renderer, scene, o.common);

    const View view = makeView(scene, scenePath, o.view);
    const uint32_t width = o.view.width, height = o.view.height;

    // One warm-up frame (first-use costs), then the measured ones; the frame with the median
    // GPU time is reported (frames are identical, so any of them is the image).
    renderer.render(view, width, height, encoding);
    RenderedImage image;
    std::vector<FrameStats> frames;
    for (uint32_t i = 0; i < o.frames; ++i) {
        image = renderer.render(view, width, height, encoding);
        frames.push_back(renderer.frameStats());
    }
    std::sort(frames.begin(), frames.end(),
              [](const FrameStats& a, const FrameStats& b) { return a.gpuMs + a.wallMs < b.gpuMs + b.wallMs; });
    const FrameStats stats = frames[frames.size() / 2];
    writeImage(outPath, image);
    reportValidation(*context);
    fmt::print("preskin: wrote {} ({}x{})\n", outPath.string(), image.width, image.height);
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
    addViewOptions(*cmd, options->view);
    cmd->add_option("--frames", options->frames, "Measured frames after one warm-up; the median is reported")
        ->capture_default_str()
        ->check(CLI::Range(1, 1000));
    addCommonOptions(*cmd, options->common);
    cmd->callback([options] { run(*options); });
}

}  // namespace preskin::cli
