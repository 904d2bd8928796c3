// `preskin render`: loads a glTF scene (the bundled head by default), renders one frame
// headless (mono, or both eyes of a stereo pair side by side) and writes it as PNG (tone-mapped)
// or EXR (linear), printing the frame time. Animated scenes: --animation and --time pose the
// scene; --sequence renders a range of times into numbered files, with a progress bar.
#include "CommandLine.h"  // samples/common
#include "Commands.h"
#include "Options.h"

#include <preskin/Context.h>
#include <preskin/Environment.h>
#include <preskin/Error.h>
#include <preskin/Renderer.h>
#include <preskin/Scene.h>
#include <preskin/View.h>

#include <fmt/core.h>

#include <unistd.h>

#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>  // client requests: no-ops outside valgrind
#define PRESKIN_CALLGRIND_START() CALLGRIND_START_INSTRUMENTATION
#define PRESKIN_CALLGRIND_STOP() CALLGRIND_STOP_INSTRUMENTATION
#else
#define PRESKIN_CALLGRIND_START() ((void)0)
#define PRESKIN_CALLGRIND_STOP() ((void)0)
#endif

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace preskin::cli {

namespace {

struct RenderOptions {
    std::string scene;
    std::string out = "render.png";
    ViewOptions view;
    uint32_t frames = 1;
    std::string animation;  // name or index; "" with --time/--sequence: the scene's first
    std::optional<float> timeS;
    std::string sequence;  // START:END:FPS
    StereoOptions stereo;
    CommonOptions common;
};

// The times of --sequence START:END:FPS: START, START + 1/FPS, ... up to END.
std::vector<float> sequenceTimes(const std::string& text) {
    std::vector<float> v;
    std::string part;
    std::string rest = text;
    for (int i = 0; i < 3; ++i) {
        const size_t colon = rest.find(':');
        part = i < 2 ? rest.substr(0, colon) : rest;
        if ((i < 2 && colon == std::string::npos) || (i == 2 && rest.find(':') != std::string::npos))
            throw Error(fmt::format("--sequence {}: expected START:END:FPS", text));
        char* end = nullptr;
        const float x = std::strtof(part.c_str(), &end);
        if (part.empty() || *end != '\0' || !std::isfinite(x))
            throw Error(fmt::format("--sequence {}: '{}' is not a finite number", text, part));
        v.push_back(x);
        if (i < 2) rest = rest.substr(colon + 1);
    }
    if (!(v[2] > 0.0f) || v[2] > 1000.0f) throw Error(fmt::format("--sequence {}: FPS must be in (0, 1000]", text));
    if (v[1] < v[0]) throw Error(fmt::format("--sequence {}: END is before START", text));
    const double frames = std::floor(double(v[1] - v[0]) * double(v[2]) + 1e-6) + 1.0;
    if (frames > 100000.0) throw Error(fmt::format("--sequence {}: {} frames (at most 100000)", text, frames));
    std::vector<float> times;
    for (uint32_t i = 0; i < uint32_t(frames); ++i) times.push_back(v[0] + float(i) / v[2]);
    return times;
}

// --out for a sequence: one printf integer field (%d or %0Nd) numbering the frames.
std::filesystem::path framePath(const std::string& pattern, uint32_t frame) {
    const size_t percent = pattern.find('%');
    size_t d = percent == std::string::npos ? std::string::npos : pattern.find('d', percent);
    bool valid = d != std::string::npos && pattern.find('%', percent + 1) == std::string::npos;
    for (size_t i = percent + 1; valid && i < d; ++i) valid = std::isdigit(static_cast<unsigned char>(pattern[i])) != 0;
    if (!valid || d - percent > 3)
        throw Error(
            fmt::format("--out {}: a sequence needs one frame-number field such as %04d in the file name", pattern));
    const int width = d - percent > 1 ? std::stoi(pattern.substr(percent + 1, d - percent - 1)) : 0;
    return pattern.substr(0, percent) + fmt::format("{:0{}}", frame, width) + pattern.substr(d + 1);
}

void renderSequence(Renderer& renderer, Context& context, const View& view, const RenderOptions& o,
                    const std::vector<float>& times, const std::function<void(float)>& poseAt,
                    OutputEncoding encoding) {
    std::vector<std::filesystem::path> written;
    const bool tty = ::isatty(2) != 0;
    const auto start = std::chrono::steady_clock::now();
    double gpuMs = 0.0;
    try {
        for (uint32_t i = 0; i < times.size(); ++i) {
            const std::filesystem::path path = framePath(o.out, i);
            checkOutputPath(path, encoding);
            poseAt(times[i]);
            const RenderedImage image = renderer.render(view, o.view.width, o.view.height, encoding);
            gpuMs += renderer.frameStats().gpuMs;
            writeImage(path, image);
            written.push_back(path);
            const uint32_t done = i + 1;
            if (tty || done == times.size() || done * 10 / times.size() != i * 10 / times.size()) {
                const int filled = int(30 * done / times.size());
                fmt::print(stderr, "{}preskin: frame {}/{} [{}{}] t = {:.3f} s{}", tty ? "\r" : "", done, times.size(),
                           std::string(size_t(filled), '#'), std::string(size_t(30 - filled), '.'), times[i],
                           tty && done < times.size() ? "" : "\n");
                std::fflush(stderr);
            }
        }
        reportValidation(context);
    } catch (...) {
        // No partial sequence is left behind.
        std::error_code ec;
        for (const auto& path : written) std::filesystem::remove(path, ec);
        if (tty) fmt::print(stderr, "\n");
        throw;
    }
    const double wallS = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    fmt::print("preskin: wrote {} frames {} .. {} ({}x{})\n", times.size(), written.front().string(),
               written.back().string(), o.view.width * uint32_t(view.eyeCount()), o.view.height);
    fmt::print("preskin: {:.2f} s on {}, gpu {:.2f} ms per frame\n", wallS, context.deviceName(),
               gpuMs / double(times.size()));
}

void run(const RenderOptions& o) {
    const std::vector<float> times = o.sequence.empty() ? std::vector<float>{} : sequenceTimes(o.sequence);
    const std::filesystem::path outPath = times.empty() ? std::filesystem::path(o.out) : framePath(o.out, 0);
    const OutputEncoding encoding = encodingFor(outPath);
    checkOutputPath(outPath, encoding);
    if (!times.empty() && o.frames > 1) throw Error("--frames: not with --sequence (every frame is rendered once)");
    const std::filesystem::path scenePath = o.scene.empty() ? defaultScenePath() : std::filesystem::path(o.scene);
    // Every option is checked before anything is loaded.
    checkViewOptions(o.view);

    Scene scene = loadScene(scenePath, o.common);
    for (const std::string& warning : scene.warnings) fmt::print(stderr, "preskin: warning: {}\n", warning);
    applySkinOption(scene, o.common);
    const Environment environment = loadEnvironment(scene, o.common);
    const ProfileLibrary profiles = loadProfiles(scene, o.common);  // every input file is read before any GPU work
    const View view = applyStereoOptions(makeView(scene, scenePath, o.view), o.stereo);  // and the camera checked
    auto context = Context::create(contextDesc(o.common));
    checkMsaaOption(*context, o.common.msaa);
    Renderer renderer(*context, scene, environment, profiles, renderSettings(o.common));
    applyLightOptions(renderer, scene, o.common);
    const bool sceneShadow = std::any_of(renderer.lights().begin(), renderer.lights().end(), [](const Light& l) {
        return l.type == LightType::Directional && l.castsShadow;
    });
    for (const Light& l : renderer.environmentLights())
        fmt::print("preskin: {}: towards ({:.3f}, {:.3f}, {:.3f}), {:.3g} lux{}{}\n", l.name, -l.directionWs.x,
                   -l.directionWs.y, -l.directionWs.z, l.intensity,
                   l.angularRadius > 0.0f ? fmt::format(", {:.2f} degrees in radius", glm::degrees(l.angularRadius))
                                          : std::string(),
                   !sceneShadow && &l == &renderer.environmentLights().front() ? ", casts the shadow" : "");
    const uint32_t width = o.view.width, height = o.view.height;

    const Animation* animation = nullptr;
    if (!o.animation.empty() || o.timeS || !times.empty()) {
        if (scene.animations.empty()) throw Error(fmt::format("--animation: {} has no animations", scenePath.string()));
        animation = &findAnimation(scene, o.animation.empty() ? std::string("0") : o.animation);
    }
    auto poseAt = [&](float t) { renderer.setPose(posedScene(scene, animationNodePose(scene, *animation, t))); };
    if (!times.empty()) {
        renderSequence(renderer, *context, view, o, times, poseAt, encoding);
        return;
    }
    if (animation) poseAt(o.timeS.value_or(0.0f));

    // One warm-up frame (first-use costs), then the measured ones; the frame with the median
    // GPU time is reported (frames are identical, so any of them is the image).
    // Under valgrind's callgrind with --instr-atstart=no, only the measured frames are counted
    // (scripts/skin-cost.sh: instructions per frame without start-up, shader compiles and warm-up).
    renderer.render(view, width, height, encoding);
    RenderedImage image;
    std::vector<FrameStats> frames;
    PRESKIN_CALLGRIND_START();
    for (uint32_t i = 0; i < o.frames; ++i) {
        image = renderer.render(view, width, height, encoding);
        frames.push_back(renderer.frameStats());
    }
    PRESKIN_CALLGRIND_STOP();
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
    addViewOptions(*cmd, options->view);
    cmd->add_option("--frames", options->frames, "Measured frames after one warm-up; the median is reported")
        ->capture_default_str()
        ->check(wholeNumberIn(1, 1000));
    cmd->add_option("--animation", options->animation,
                    "Pose the scene with this animation (name or index; default with --time or --sequence: the first)");
    cmd->add_option("--time", options->timeS, "Time in the animation, seconds (clamped to its keys)")
        ->check(numberIn(-1e6, 1e6));
    cmd->add_option("--sequence", options->sequence,
                    "Render the animation from START to END seconds at FPS frames per second into numbered files: "
                    "START:END:FPS with --out DIR/name_%04d.png");
    addStereoOptions(*cmd, options->stereo);
    addCommonOptions(*cmd, options->common);
    addProfileChoiceOptions(*cmd, options->common);
    cmd->callback([options] { run(*options); });
}

}  // namespace preskin::cli
