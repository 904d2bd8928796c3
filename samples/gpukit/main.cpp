// preskin-gpu-kit: the program of the GPU kit (scripts/gpu-kit.sh packs it with its libraries and
// data; the kit's run.sh starts it). One run of the bench's scenarios on one device, then
// gpu-report.json and gpu-report.md (GpuReport.h) in the output folder:
//   - the head at 1280x720 with 256 lights: standard frame against skin, skin with each technique
//     off, the screen-space and texture-space baselines, specular IBL and background;
//   - VR: stereo at 2 x 1832x1920 (one eye of a Quest 2) with MSAA 4x against two monos;
//   - 256, 4,096 and 65,536 lights at density 4 with the grid built on the GPU; 64 area lights
//     of each shape against 64 points;
//   - the animated head (deformation and curvature's share).
// Every figure is the median of 30 frames after 3 warm-up frames (GPU timestamps per pass).
// --quick: the same scenarios at a fraction of the size, 3 frames each (a smoke test of the kit,
// and what runs on lavapipe in the tests). It links the core library only (no OpenImageIO, no
// Embree): the profiles' LUTs come raw (the kit's data folder) or baked in-process.
#include "GpuReport.h"

#include "BenchMeasure.h"  // samples/bench
#include "CommandLine.h"   // samples/common
#include "Options.h"       // samples/common

#include <preskin/Error.h>
#include <preskin/OutputFile.h>

#include <fmt/core.h>
#include <CLI/CLI.hpp>

#include <chrono>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <string>

namespace {

struct KitOptions {
    std::string out = ".";
    std::string device;
    bool quick = false;
    bool validation = false;
};

std::string utcNow() {
    const std::time_t now = std::time(nullptr);
    std::tm utc{};
    gmtime_r(&now, &utc);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
    return text;
}

preskin::cli::bench::BenchOptions benchOptions(const KitOptions& k) {
    preskin::cli::bench::BenchOptions o;
    o.device = k.device;
    o.validation = k.validation;
    o.lightDensity = 4.0f;
    o.counts = "256,4096,65536";
    o.skinCounts = "256";
    o.vrLights = 256;
    o.vrMsaa = 4;
    o.noBrute = true;         // a loop over every light at 65,536: the clustered frames are the figures
    o.noBuildCompare = true;  // the grid is built where the kit says (below), not both ways
    o.noPerPixel = true;      // list lengths are the bench's correctness figure, not a GPU one
    o.noLutBake = true;       // a CPU figure
    o.noProfiles = true;      // a CPU figure
    o.noCache = true;         // no profile cache written on the machine
    o.budgetS = 60.0;
    if (k.quick) {
        o.width = 320;
        o.height = 180;
        o.vrWidth = 229;  // 1832 x 1920 at an eighth
        o.vrHeight = 240;
        o.warmup = 1;
        o.reps = 3;
        o.build = "auto";  // lavapipe builds the grid on the CPU, 35-150x faster there
    } else {
        o.width = 1280;
        o.height = 720;
        o.vrWidth = 1832;
        o.vrHeight = 1920;
        o.warmup = 3;
        o.reps = 30;
        o.build = "gpu";
    }
    return o;
}

void run(const KitOptions& k, const std::string& command) {
    const auto started = std::chrono::steady_clock::now();
    const std::filesystem::path out(k.out);
    preskin::checkOutputFile(out / "gpu-report.json");
    preskin::checkOutputFile(out / "gpu-report.md");
    const std::string benchJson = preskin::cli::bench::runBench(benchOptions(k));
    preskin::gpukit::ReportInfo info;
    info.command = command;
    info.mode = k.quick ? "quick" : "full";
    info.date = utcNow();
    info.elapsedS = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    // scripts/gpu-kit.sh writes the commit the kit was made from beside its data.
    std::ifstream sourceFile(preskin::cli::dataDir() / "kit-source.txt");
    if (!std::getline(sourceFile, info.source) || info.source.empty()) info.source = "a build folder";
    nlohmann::ordered_json report;
    try {
        report = preskin::gpukit::makeReport(nlohmann::json::parse(benchJson), info);
    } catch (const std::exception& e) {
        throw preskin::Error(fmt::format("{}: report: {}", (out / "gpu-report.json").string(), e.what()));
    }
    preskin::writeTextFile(out / "gpu-report.json", report.dump(2) + "\n");
    preskin::writeTextFile(out / "gpu-report.md", preskin::gpukit::reportMarkdown(report));
    fmt::print("preskin-gpu-kit: {} on {}: wrote {} and {} in {:.0f} s\n", info.mode,
               report["device"].get<std::string>(), (out / "gpu-report.json").string(),
               (out / "gpu-report.md").string(), info.elapsedS);
    for (const auto& g : report["goals"])
        fmt::print("  {} {}: {:.3f} (target {})\n", g["holds"].get<bool>() ? "met    " : "NOT MET",
                   g["goal"].get<std::string>(), g["measured"].get<double>(), g["target"].get<double>());
}

}  // namespace

int main(int argc, char** argv) {
    KitOptions k;
    CLI::App app{"preskin-gpu-kit: every performance goal of preskin measured on one device (GPU timestamps)"};
    app.add_option("--out", k.out, "Folder for gpu-report.json and gpu-report.md")->capture_default_str();
    app.add_option("--device", k.device, "Vulkan device: index or part of its name (default: the best GPU)");
    app.add_flag("--quick", k.quick, "Small sizes and 3 frames per figure: a check that the kit runs");
    app.add_flag("--validation", k.validation, "Vulkan validation layers on; any message fails the run");
    std::string command = "preskin-gpu-kit";
    for (int i = 1; i < argc; ++i) command += std::string(" ") + argv[i];
    return preskin::cli::runCommandLine(app, argc, argv, [&] {
        run(k, command);
        return 0;
    });
}
