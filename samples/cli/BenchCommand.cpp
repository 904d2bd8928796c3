// `preskin bench`: measures the renderer side by side in one run and writes JSON (stdout or
// --out); scripts/plot-bench.py draws frame time against light count from it. What it measures:
// samples/bench/BenchRun.cpp.
#include "BenchSections.h"
#include "Commands.h"

#include <preskin/Deformation.h>
#include <preskin/Error.h>
#include <preskin/OutputFile.h>

#include <fmt/core.h>

#include <cstdio>
#include <memory>
#include <string>

namespace preskin::cli {

namespace {

void run(bench::BenchOptions o) {
    if (!o.out.empty()) checkOutputFile(o.out);
    o.cpuDeform = &deformPrimitive;  // the reference's CPU deformation: the CPU curvature figures
    const std::string json = bench::runBench(o);
    if (o.out.empty()) {
        std::fwrite(json.data(), 1, json.size(), stdout);
    } else {
        writeTextFile(o.out, json);
        fmt::print(stderr, "preskin bench: wrote {}\n", o.out);
    }
}

}  // namespace

void addBenchCommand(CLI::App& app) {
    auto o = std::make_shared<bench::BenchOptions>();
    CLI::App* cmd = app.add_subcommand(
        "bench", "Measure clustered vs brute-force lighting, the light grid, skin vs standard and the LUT bake (JSON)");
    cmd->add_option("scene", o->scene, "glTF scene; default: the bundled head scene");
    cmd->add_option("--out,-o", o->out, "Write the JSON here instead of stdout");
    cmd->add_option("--width", o->width, "Image width in pixels")
        ->capture_default_str()
        ->check(wholeNumberIn(1, 16384));
    cmd->add_option("--height", o->height, "Image height in pixels")
        ->capture_default_str()
        ->check(wholeNumberIn(1, 16384));
    cmd->add_option("--counts", o->counts, "Scattered light counts, comma-separated")->capture_default_str();
    cmd->add_option("--skin-counts", o->skinCounts, "Light counts for skin vs standard material")
        ->capture_default_str();
    cmd->add_option("--light-density", o->lightDensity,
                    "Scattered lights' ranges scaled so that a point of the scene lies in about this many lights' "
                    "volumes at every count (0: ranges of the scene's size)")
        ->check(numberIn(0.0, 1000.0))
        ->capture_default_str();
    cmd->add_option("--seed", o->seed, "Seed of the scattered lights")
        ->capture_default_str()
        ->check(wholeNumberIn(0, UINT32_MAX));
    cmd->add_option("--warmup", o->warmup, "Warm-up frames per point")
        ->capture_default_str()
        ->check(wholeNumberIn(0, 100));
    cmd->add_option("--reps", o->reps, "Measured frames per point (median)")
        ->capture_default_str()
        ->check(wholeNumberIn(1, 1000));
    cmd->add_option("--budget-s", o->budgetS,
                    "Seconds per point before warm-up and repetitions are cut (at least one frame)")
        ->capture_default_str()
        ->check(numberIn(0.0, 1e6));
    cmd->add_option("--tile", o->clusters.tileSizePx,
                    "Cluster tile size in pixels; 0 chooses it from the lights' projected size (16, 8 or 4)")
        ->capture_default_str()
        ->check(zeroOrWholeNumberIn(4, 256));
    cmd->add_option("--slices", o->clusters.depthSlices, "Cluster depth slices")
        ->capture_default_str()
        ->check(wholeNumberIn(2, 256));
    cmd->add_option("--near-slice", o->clusters.nearSliceM, "Depth where the first slice ends at the earliest (m)")
        ->capture_default_str()
        ->check(numberIn(0.0, 1e6));
    cmd->add_flag("--no-surface-fit", o->noSurfaceFit,
                  "Light lists for whole froxels, not bounded by where the scene's surfaces are");
    cmd->add_flag("--no-surface-reuse", o->noSurfaceReuse,
                  "Find where the surfaces are every frame, as for a moving view (else a still view reuses it)");
    cmd->add_option("--max-per-cluster", o->clusters.maxLightsPerCluster, "Lights kept per cluster")
        ->capture_default_str()
        ->check(wholeNumberIn(1, 1 << 20));
    cmd->add_option("--build", o->build, "Light-list build: auto, cpu or gpu (compute pass)")
        ->check(oneOf({"auto", "cpu", "gpu"}))
        ->capture_default_str();
    cmd->add_option("--only", o->only,
                    "Run only these sections, comma-separated: lut-bake, lights, area-lights, skin, environment, "
                    "diffusion, vr, animation, profiles (the --no-* flags still turn parts of them off)");
    cmd->add_flag("--no-lights", o->noLights,
                  "Skip the light-loop section (clustered vs brute force, the other build, lights per pixel)");
    cmd->add_flag("--no-build-compare", o->noBuildCompare, "Skip measuring the other light-list build");
    cmd->add_flag("--no-brute", o->noBrute, "Skip brute force");
    cmd->add_flag("--no-skin", o->noSkin, "Skip skin vs standard material");
    cmd->add_flag("--no-per-pixel", o->noPerPixel, "Skip lights listed per pixel vs exact");
    cmd->add_flag("--no-lut-bake", o->noLutBake, "Skip timing the LUT bake");
    cmd->add_flag("--no-vr", o->noVr, "Skip stereo vs two mono frames, the stereo light grid and MSAA 4x vs 1x");
    cmd->add_flag("--no-techniques", o->noTechniques, "Skip the skin frame with each technique off in turn");
    cmd->add_flag("--no-animation", o->noAnimation, "Skip the deformation and curvature passes of an animated scene");
    cmd->add_flag("--no-environment", o->noEnvironment,
                  "Skip the prefiltered specular and background against neither, and the environment's update");
    cmd->add_flag("--no-diffusion", o->noDiffusion,
                  "Skip preskin's diffusion against the screen-space and texture-space baselines (mono, and stereo "
                  "with MSAA 4x)");
    cmd->add_flag("--no-area-lights", o->noAreaLights,
                  "Skip the frame with 64 sphere, tube, rectangle or disc lights against 64 point lights");
    cmd->add_flag("--no-profiles", o->noProfiles,
                  "Skip the diffusion-profile figures (one bake, 64 cached profiles, 8 profiles in view)");
    cmd->add_option("--profile-lut-size", o->profileLutSize, "Table size of the profiles baked for the profile figures")
        ->capture_default_str()
        ->check(wholeNumberIn(LutBakeSettings::kMinSize, LutBakeSettings::kMaxSize));
    cmd->add_option("--animated-scene", o->animatedScene,
                    "Animated glTF scene for the animation figures; default: the bench scene when it is animated, "
                    "else the bundled animated head");
    cmd->add_option("--vr-width", o->vrWidth, "Stereo: width per eye")
        ->capture_default_str()
        ->check(wholeNumberIn(1, 16384));
    cmd->add_option("--vr-height", o->vrHeight, "Stereo: height per eye")
        ->capture_default_str()
        ->check(wholeNumberIn(1, 16384));
    cmd->add_option("--vr-msaa", o->vrMsaa, "Stereo: MSAA samples of the stereo frame and its two mono frames")
        ->capture_default_str()
        ->check(CLI::IsMember({1, 2, 4, 8}));
    cmd->add_option("--vr-lights", o->vrLights, "Stereo and MSAA: scattered lights")
        ->capture_default_str()
        ->check(wholeNumberIn(0, 1 << 20));
    cmd->add_option("--ipd", o->ipdM, "Stereo: interpupillary distance, metres")
        ->capture_default_str()
        ->check(numberIn(0.0, 1.0));
    cmd->add_option("--device", o->device,
                    "Vulkan device: index or part of its name (default: best GPU, else lavapipe)");
    cmd->add_flag("--validation", o->validation, "Enable Vulkan validation layers; any message makes the run fail");
    cmd->callback([o] { run(*o); });
}

}  // namespace preskin::cli
