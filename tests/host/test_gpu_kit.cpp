// The GPU kit as a machine without the build sees it: scripts/gpu-kit.sh writes it into a
// temporary folder, the folder is moved, and its run.sh runs under `env -i` (no build tree, no
// library path, nothing of this machine's environment) on lavapipe in quick mode with the
// validation layers on: exit 0, and every figure of the report present and finite. Every ELF
// file of the kit resolves its libraries inside the kit or to the C/C++ runtime (glibc,
// libstdc++, libgcc), and the kit holds at most 48 MiB.
#include "support/ElfClosure.h"
#include "support/Process.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace preskin::test {
namespace {

namespace fs = std::filesystem;

bool isElf(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    char magic[4] = {};
    in.read(magic, 4);
    return in.gcount() == 4 && magic[0] == 0x7f && magic[1] == 'E' && magic[2] == 'L' && magic[3] == 'F';
}

// Every number under `node` is finite; `where` names the first that is not (or a null: the
// report writes non-finite numbers as null).
void expectFinite(const nlohmann::json& node, const std::string& where, size_t& numbers) {
    if (node.is_object()) {
        for (auto it = node.begin(); it != node.end(); ++it) expectFinite(it.value(), where + "." + it.key(), numbers);
    } else if (node.is_array()) {
        for (size_t i = 0; i < node.size(); ++i) expectFinite(node[i], where + "[" + std::to_string(i) + "]", numbers);
    } else if (node.is_null()) {
        ADD_FAILURE() << where << " is null";
    } else if (node.is_number()) {
        ++numbers;
        EXPECT_TRUE(std::isfinite(node.get<double>())) << where;
    }
}

TEST(GpuKit, MovedKitRunsInAnEmptyEnvironmentAndReportsEveryFigure) {
    const fs::path work = fs::path(PRESKIN_BINARY_DIR) / "gpu-kit-test";
    std::error_code ec;
    fs::remove_all(work, ec);
    fs::create_directories(work);
    const ProcessResult made = runProcess(PRESKIN_SOURCE_DIR "/scripts/gpu-kit.sh",
                                          {(work / "made").string(), PRESKIN_BINARY_DIR}, {}, work, 600.0);
    ASSERT_EQ(made.exitCode, 0) << made.out << made.err;
    const fs::path kit = work / "moved";
    fs::rename(work / "made", kit);

    // Size, and every ELF file's libraries: in the kit or the runtime.
    uint64_t bytes = 0;
    std::vector<fs::path> elves;
    for (const auto& entry : fs::recursive_directory_iterator(kit)) {
        if (!entry.is_regular_file()) continue;
        bytes += entry.file_size();
        if (isElf(entry.path())) elves.push_back(entry.path());
    }
    std::printf("kit: %.1f MiB, %zu ELF files\n", double(bytes) / (1024.0 * 1024.0), elves.size());
    EXPECT_LE(bytes, 48ull << 20);
    EXPECT_GE(elves.size(), 4u);  // the program, libpreskin, its libraries, the Vulkan loader
    const std::string kitRoot = fs::canonical(kit).string() + "/";
    for (const fs::path& elf : elves) {
        const ElfClosure closure = elfClosure(elf, {kit / "lib", kit / "lib" / "glvnd", kit / "lib" / "vulkan"});
        for (const std::string& problem : closure.problems) ADD_FAILURE() << elf << ": " << problem;
        for (const auto& [name, library] : closure.libraries) {
            const auto& runtime = runtimeLibraries();
            const bool inRuntime = std::find(runtime.begin(), runtime.end(), name) != runtime.end();
            const bool inKit = library.path.string().rfind(kitRoot, 0) == 0;
            EXPECT_TRUE(inRuntime || inKit) << elf.filename() << " loads " << name << " from " << library.path;
        }
    }

    // What run.sh falls back on where the system lacks it: glvnd (NVIDIA's Vulkan driver loads
    // it) and the C/C++ runtime; --bundled-runtime starts the program on the kit's glibc.
    for (const char* name : {"glvnd/libGLdispatch.so.0", "glvnd/libEGL.so.1", "runtime/ld-linux-x86-64.so.2",
                             "runtime/libc.so.6", "runtime/libstdc++.so.6", "vulkan/libvulkan.so.1"})
        EXPECT_TRUE(fs::is_regular_file(kit / "lib" / name)) << name;
    const ProcessResult bundled =
        runProcess("/usr/bin/env", {"-i", "LD_DEBUG=libs", (kit / "run.sh").string(), "--bundled-runtime", "--help"},
                   {}, work, 60.0);
    EXPECT_EQ(bundled.exitCode, 0) << bundled.err.substr(0, 2000);
    EXPECT_NE(bundled.out.find("preskin-gpu-kit"), std::string::npos) << bundled.out;
    const std::string kitLibc = "calling init: " + (fs::canonical(kit) / "lib" / "runtime" / "libc.so.6").string();
    EXPECT_NE(bundled.err.find(kitLibc), std::string::npos) << bundled.err.substr(0, 2000);

    // The quick run in an empty environment, validation on.
    const fs::path report = work / "report";
    const ProcessResult ran = runProcess("/usr/bin/env",
                                         {"-i", "LP_NUM_THREADS=2", (kit / "run.sh").string(), "--device", testDevice(),
                                          "--quick", "--validation", "--out", report.string()},
                                         {}, work, 540.0);
    ASSERT_EQ(ran.exitCode, 0) << ran.out << ran.err;
    EXPECT_EQ((ran.out + ran.err).find("Validation"), std::string::npos) << ran.err;
    const std::string text = readFile(report / "gpu-report.json");
    const nlohmann::json r = nlohmann::json::parse(text, nullptr, false);
    ASSERT_FALSE(r.is_discarded()) << text.substr(0, 400);
    EXPECT_EQ(r.value("mode", ""), "quick");
    EXPECT_NE(r.value("device", "").find("llvmpipe"), std::string::npos);
    EXPECT_FALSE(r.value("driver", "").empty());
    EXPECT_NE(r.value("source", "").find(" (20"), std::string::npos) << r.value("source", "");  // commit (date)
    size_t numbers = 0;
    for (const char* section : {"head", "vr", "lights", "animation", "goals"}) {
        ASSERT_TRUE(r.contains(section)) << section;
        expectFinite(r[section], section, numbers);
    }
    EXPECT_GT(numbers, 100u);
    // The figures the kit exists for, each one a goal with its measure.
    EXPECT_EQ(r["goals"].size(), 6u);
    for (const char* technique : {"lut_diffuse", "normal_prefilter", "penumbra", "sh_ambient", "transmission",
                                  "dual_specular", "normal_map_levels", "wide_penumbra", "lut_shadow_light",
                                  "full_shadow_filter", "lut_other_lights", "light_curvature"})
        EXPECT_TRUE(r["head"]["technique_cost_forward_gpu_ms"].contains(technique)) << technique;
    for (const char* tier : {"high", "medium", "low"})
        EXPECT_GT(r["head"]["tier_over_standard"].value(tier, 0.0), 0.0) << tier;
    EXPECT_EQ(r["vr"]["msaa_samples"], 4);
    EXPECT_EQ(r["lights"]["counts"].size(), 3u);
    EXPECT_GT(r["animation"]["deform_gpu_ms"].get<double>(), 0.0);
    const std::string markdown = readFile(report / "gpu-report.md");
    EXPECT_EQ(markdown.rfind("# preskin GPU report", 0), 0u);
    EXPECT_NE(markdown.find("## Goals"), std::string::npos);
}

}  // namespace
}  // namespace preskin::test
