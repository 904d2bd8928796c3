// The measurement behind `preskin bench` (BenchCommand.cpp): its options, a configuration's
// frames and their medians (Measurement), and Bench, which measures configurations side by side:
// warm-up frames first, then rounds of one frame each, so a change in machine load hits all of
// them alike; slow points get fewer frames within --budget-s. A Goal is what a section promises,
// evaluated when the report is written.
#pragma once

#include "CommandLine.h"
#include "JsonWriter.h"
#include "Options.h"  // samples/common

#include <preskin/Animation.h>
#include <preskin/ClusterGrid.h>
#include <preskin/Context.h>
#include <preskin/Renderer.h>
#include <preskin/Scene.h>
#include <preskin/View.h>

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace preskin::cli::bench {

using Clock = std::chrono::steady_clock;

inline double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// CPU time of the whole process (all threads), ms.
double processCpuMs();

struct BenchOptions {
    std::string scene;
    std::string out;
    uint32_t width = 1280;
    uint32_t height = 720;
    std::string counts = "16,64,256,1024,4096";
    std::string skinCounts = "256,1024";
    uint32_t seed = 1;
    float lightDensity = 0.0f;  // lights per point of the scattered lights (scatterLights); 0: scene-sized ranges
    uint32_t warmup = 1;
    uint32_t reps = 5;
    double budgetS = 15.0;
    ClusterSettings clusters;
    std::string build = "auto";
    bool noBuildCompare = false;
    bool noSurfaceFit = false;    // --no-surface-fit: ClusterSettings::fitListsToSurfaces off
    bool noSurfaceReuse = false;  // --no-surface-reuse: ClusterSettings::reuseSurfaces off
    bool noBrute = false;
    bool noSkin = false;
    bool noPerPixel = false;
    bool noLutBake = false;
    bool noVr = false;
    bool noAnimation = false;
    bool noTechniques = false;
    bool noProfiles = false;
    bool noAreaLights = false;
    bool noEnvironment = false;
    bool noDiffusion = false;
    bool noLights = false;  // the light-loop section (clustered, brute force, the other build, per pixel)
    // --only: the sections to run, comma-separated (kBenchSections); every other one is skipped.
    // Empty: every section not turned off by its own flag.
    std::string only;
    int profileLutSize = 256;
    bool noCache = false;  // the profiles' LUT cache off (CommonOptions::noCache)
    std::string animatedScene;
    uint32_t vrWidth = 640;
    uint32_t vrHeight = 720;
    uint32_t vrLights = 256;
    uint32_t vrMsaa = 1;  // samples of the stereo frame and its two mono frames (when the device offers them)
    float ipdM = 0.063f;
    std::string device;
    bool validation = false;
    // The CPU deformation (the reference library's deformPrimitive, which the CLI links): the
    // animation section's CPU curvature figures use it; without it (the GPU kit links no
    // reference) they are left out.
    void (*cpuDeform)(const Primitive&, const InstancePose&, std::vector<Vertex>&) = nullptr;
};

// The sections of the report, in the order they run, as --only names them.
inline constexpr const char* kBenchSections[] = {"lut-bake",  "lights", "area-lights", "skin",    "environment",
                                                 "diffusion", "vr",     "animation",   "profiles"};

// `o` with --only applied: every section it does not name turned off (Error naming an unknown one).
BenchOptions selectSections(BenchOptions o);

// Runs the sections `o` asks for and returns the JSON report (BenchRun.cpp).
std::string runBench(const BenchOptions& o);

// A scene path as the JSON reports it: relative to the data folder for bundled assets, so results
// do not carry the machine's folders.
std::string reportedPath(const std::filesystem::path& path);

double median(std::vector<double> v);

// The frames of one configuration; its figures are medians.
struct Measurement {
    uint32_t warmup = 0;
    std::vector<FrameStats> frames;
    std::vector<double> cpuMsEach;  // the process's CPU time over each frame

    double cpuMs() const { return median(cpuMsEach); }
    double wallMs() const {
        return medianOf([](const FrameStats& s) { return s.wallMs; });
    }
    double gpuMs() const {
        return medianOf([](const FrameStats& s) { return s.gpuMs; });
    }
    double buildCpuMs() const {
        return medianOf([](const FrameStats& s) { return s.clusterBuildCpuMs; });
    }
    double recordCpuMs() const {
        return medianOf([](const FrameStats& s) { return s.recordCpuMs; });
    }
    double passMs(const std::string& name) const {
        return medianOf([&](const FrameStats& s) {
            for (const PassTime& p : s.passes)
                if (p.name == name) return p.gpuMs;
            return std::numeric_limits<double>::quiet_NaN();
        });
    }
    // The whole light-list build: its CPU part plus, for the compute build, its pass.
    double buildMs() const {
        return medianOf([](const FrameStats& s) {
            double ms = s.clusterBuildCpuMs;
            for (const PassTime& p : s.passes)
                if (p.name == "clusters" && s.clusterBuildGpu) ms += p.gpuMs;
            return ms;
        });
    }
    bool buildGpu() const { return !frames.empty() && frames.back().clusterBuildGpu; }
    uint32_t overflows() const { return frames.empty() ? 0 : frames.back().clusterOverflows; }

    template <typename F>
    double medianOf(F f) const {
        std::vector<double> v;
        for (const FrameStats& s : frames) v.push_back(f(s));
        return median(v);
    }
};

void writeMeasurement(JsonWriter& j, const Measurement& m);

// One configuration measured in a set: a renderer and its settings, and optionally its own view
// and per-eye image size (else the bench's).
struct Config {
    Renderer* renderer = nullptr;
    RenderSettings settings;
    std::string label;
    double predictedMs = 0.0;  // <= 0: unknown
    const View* view = nullptr;
    uint32_t width = 0;
    uint32_t height = 0;
    const std::vector<Light>* lights = nullptr;  // this configuration's own lights (set before each of its frames)
};

class Bench {
public:
    Bench(const BenchOptions& o, Context& context, const View& view) : o_(o), context_(context), view_(view) {}

    // Frames planned for one configuration: the full warm-up and repetitions unless the
    // predicted frame time (ms, <= 0: unknown) says they would take longer than the budget.
    std::pair<uint32_t, uint32_t> plan(double predictedMs) const {
        uint32_t warmup = o_.warmup;
        uint32_t reps = std::max<uint32_t>(o_.reps, 1);
        if (predictedMs <= 0.0) return {warmup, reps};
        const double budgetMs = o_.budgetS * 1000.0;
        if (predictedMs * double(warmup + reps) <= budgetMs) return {warmup, reps};
        reps = std::clamp<uint32_t>(static_cast<uint32_t>(budgetMs / predictedMs), 1, reps);
        warmup = predictedMs * double(reps + warmup) <= budgetMs ? warmup : 0;
        return {warmup, reps};
    }

    // Measures configurations side by side with the same lights (or each its own, Config::lights,
    // set before each of its frames; the frame's wall time does not include it): the warm-ups first, then
    // rounds in which each configuration renders one frame (one with fewer planned frames takes
    // part in evenly spread rounds), so drifts in machine load hit all of them alike.
    std::vector<Measurement> measure(const std::vector<Config>& configs, const std::vector<Light>& lights) {
        const auto start = Clock::now();
        std::vector<Measurement> out(configs.size());
        std::vector<uint32_t> reps(configs.size());
        uint32_t rounds = 0;
        for (size_t i = 0; i < configs.size(); ++i) {
            const auto [warmup, n] = plan(configs[i].predictedMs);
            out[i].warmup = warmup;
            reps[i] = n;
            rounds = std::max(rounds, n);
            fmt::print(stderr, "preskin bench: {} ({} warm-up, {} measured)\n", configs[i].label, warmup, n);
        }
        for (const Config& c : configs) c.renderer->setLights(lights);
        auto frame = [&](const Config& c) {
            if (c.lights) c.renderer->setLights(*c.lights);
            c.renderer->setSettings(c.settings);
            c.renderer->render(c.view ? *c.view : view_, c.width ? c.width : o_.width, c.height ? c.height : o_.height,
                               OutputEncoding::DisplaySrgb8);
        };
        for (size_t i = 0; i < configs.size(); ++i)
            for (uint32_t w = 0; w < out[i].warmup; ++w) frame(configs[i]);
        for (uint32_t r = 0; r < rounds; ++r)
            for (size_t i = 0; i < configs.size(); ++i) {
                if ((uint64_t(r) + 1) * reps[i] / rounds == uint64_t(r) * reps[i] / rounds) continue;
                const double cpuStart = processCpuMs();
                frame(configs[i]);
                out[i].cpuMsEach.push_back(processCpuMs() - cpuStart);
                out[i].frames.push_back(configs[i].renderer->frameStats());
            }
        for (size_t i = 0; i < configs.size(); ++i)
            fmt::print(stderr, "preskin bench:   {}: {:.1f} ms median wall\n", configs[i].label, out[i].wallMs());
        fmt::print(stderr, "preskin bench:   ({:.1f} s)\n", secondsSince(start));
        reportValidation(context_);
        return out;
    }

private:
    const BenchOptions& o_;
    Context& context_;
    const View& view_;
};

// Linear fit (a + b n) through the last two (n, ms) points, for planning the next one.
double predictFrameMs(const std::vector<std::pair<double, double>>& points, double n);

// A goal of the report: holds when `measured` is at most (or at least) `target`.
struct Goal {
    std::string name;
    double measured = 0.0;
    double target = 0.0;
    bool atMost = true;
};

}  // namespace preskin::cli::bench
