// `preskin bench` end to end on a tiny image: it writes the JSON (every section, sane numbers,
// no pixel whose light list is shorter than its exact count, validation on) that
// scripts/plot-bench.py turns into a PNG plot, and refuses bad arguments before doing any work.
#include "support/Process.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <string>

namespace preskin::test {
namespace {

namespace fs = std::filesystem;

class BenchCli : public ::testing::Test {
protected:
    void SetUp() override {
        if (!fs::exists(PRESKIN_CLI_PATH)) GTEST_SKIP() << PRESKIN_CLI_PATH << " is not built";
        std::random_device entropy;
        dir_ = fs::temp_directory_path() / ("preskin_test_bench_cli_" + std::to_string(entropy()));
        fs::create_directories(dir_);
    }
    void TearDown() override {
        std::error_code ec;
        if (!dir_.empty()) fs::remove_all(dir_, ec);
    }

    int bench(const std::vector<std::string>& arguments, std::string& err) const {
        std::vector<std::string> all{std::string("bench"), std::string("--device"), test::testDevice()};
        all.insert(all.end(), arguments.begin(), arguments.end());
        const test::ProcessResult run = test::runCli(all, dir_);
        err = run.err;
        return run.exitCode;
    }

    fs::path dir_;
};

TEST_F(BenchCli, WritesJsonAndPlot) {
    const fs::path json = dir_ / "bench.json";
    const fs::path plot = dir_ / "bench.png";
    std::string err;
    // A budget no loaded machine reaches: every point gets its 2 frames (the JSON is checked for them).
    ASSERT_EQ(
        bench({"--budget-s", "600", "--width", "96", "--height", "64", "--counts", "0,8,32", "--skin-counts", "8",
               "--reps", "2", "--warmup", "0", "--validation", "--profile-lut-size", "16", "--out", json.string()},
              err),
        0)
        << err;
    const nlohmann::json j = nlohmann::json::parse(std::ifstream(json));
    EXPECT_EQ(j.at("width"), 96);
    EXPECT_GT(j.at("lut_bake").at("ms").get<double>(), 0.0);
    ASSERT_EQ(j.at("light_loop").size(), 3u);
    for (const auto& row : j.at("light_loop")) {
        for (const char* loop : {"clustered", "brute_force"}) {
            const auto& m = row.at(loop);
            EXPECT_EQ(m.at("frames"), 2) << loop;
            EXPECT_GT(m.at("wall_ms").get<double>(), 0.0) << loop;
            EXPECT_TRUE(m.at("gpu_pass_ms").contains("forward")) << loop;
        }
        EXPECT_EQ(row.at("clustered").at("overflowed_clusters"), 0);
        const auto& perPixel = row.at("per_pixel");
        EXPECT_GT(perPixel.at("pixels").get<int>(), 0);
        EXPECT_EQ(perPixel.at("pixels_listed_below_exact"), 0) << "a light missing from a list";
        EXPECT_GE(perPixel.at("listed_mean").get<double>(), perPixel.at("exact_mean").get<double>());
        if (row.at("lights") == 0) {
            EXPECT_EQ(perPixel.at("listed_mean").get<double>(), 0.0);
        }
    }
    ASSERT_EQ(j.at("cluster_build").size(), 3u);
    EXPECT_TRUE(j.at("cluster_build")[0].contains("cpu"));
    EXPECT_TRUE(j.at("cluster_build")[0].contains("gpu"));
    ASSERT_EQ(j.at("skin_vs_standard").size(), 1u);
    EXPECT_GT(j.at("skin_vs_standard")[0].at("skin_over_standard").get<double>(), 0.0);
    // Process CPU time per frame: every frame takes some (the renderer records and waits on the CPU).
    EXPECT_GT(j.at("skin_vs_standard")[0].at("skin_over_standard_cpu").get<double>(), 0.0);
    EXPECT_GT(j.at("skin_vs_standard")[0].at("skin").at("cpu_ms").get<double>(), 0.0);
    const auto& techniques = j.at("skin_techniques").at("cost_ms");
    for (const char* t : {"lut_diffuse", "normal_prefilter", "penumbra", "sh_ambient", "transmission", "dual_specular",
                          "normal_map_levels", "wide_penumbra", "lut_shadow_light", "full_shadow_filter",
                          "lut_other_lights", "light_curvature"}) {
        EXPECT_TRUE(techniques.at(t).at("wall").is_number()) << t;
        EXPECT_TRUE(techniques.at(t).at("cpu").is_number()) << t;
    }
    // What the depth prepass saves each frame, both frames measured without it in the same rounds.
    for (const char* frame : {"skin", "standard_material"})
        for (const char* measure : {"wall", "cpu", "forward_gpu"})
            EXPECT_TRUE(j.at("skin_techniques").at("depth_prepass_saves_ms").at(frame).at(measure).is_number())
                << frame << " " << measure;
    // The tiers below high, measured in the same rounds: each lighter than the skin frame in CPU time.
    for (const char* tier : {"medium", "low"}) {
        const auto& row = j.at("skin_techniques").at("tiers").at(tier);
        EXPECT_GT(row.at("over_standard").get<double>(), 0.0) << tier;
        EXPECT_GT(row.at("frame").at("cpu_ms").get<double>(), 0.0) << tier;
    }
    // The methods preskin replaces, beside it: their passes and targets as their frames report them.
    for (const char* row : {"mono", "stereo_msaa4"}) {
        const auto& methods = j.at("diffusion_methods").at(row);
        for (const char* m : {"preintegrated", "screen", "texture", "lambert"})
            EXPECT_EQ(methods.at(m).at("frames"), 2) << row << " " << m;
        EXPECT_FALSE(methods.at("preintegrated").contains("diffusion_passes")) << row;
        EXPECT_EQ(methods.at("screen").at("diffusion_passes"), 2) << row;
        EXPECT_EQ(methods.at("texture").at("diffusion_passes"), 13) << row;  // d'Eon's 6 Gaussians
        EXPECT_GT(methods.at("preintegrated_over_screen").get<double>(), 0.0) << row;
    }
    // The bundled head is not animated: the animation figures come from the animated head.
    const auto& animation = j.at("animation");
    EXPECT_NE(animation.at("scene").get<std::string>().find("head_animated.gltf"), std::string::npos);
    EXPECT_GT(animation.at("deformed_vertices").get<int>(), 0);
    EXPECT_GT(animation.at("deform_gpu_ms").get<double>(), 0.0);
    EXPECT_GT(animation.at("curvature_gpu_ms").get<double>(), 0.0);
    EXPECT_GT(animation.at("curvature_cpu_ms").get<double>(), 0.0);
    EXPECT_LT(animation.at("deform_and_curvature_share_gpu").get<double>(), 1.0);
    // Profiles: 64 baked into a fresh cache, then all 64 read back from it; 8 copies of the head.
    const auto& profiles = j.at("profiles");
    EXPECT_EQ(profiles.at("cached_profiles"), 64);
    EXPECT_GT(profiles.at("load_cached_ms").get<double>(), 0.0);
    EXPECT_GT(profiles.at("bake_one_ms").get<double>(), 0.0);
    EXPECT_EQ(profiles.at("frame_eight_profiles").at("frames"), 2);
    EXPECT_FALSE(j.at("goals").empty());
    const test::ProcessResult plotted =
        test::runProcess("/usr/bin/python3",
                         {PRESKIN_SOURCE_DIR "/scripts/plot-bench.py", json.string(), plot.string()}, {}, dir_, 120.0);
    ASSERT_EQ(plotted.exitCode, 0) << plotted.err;
    std::ifstream png(plot, std::ios::binary);
    char signature[8] = {};
    png.read(signature, 8);
    EXPECT_EQ(std::string(signature + 1, 3), "PNG");
}

// A scene whose skin materials name their own diffusion profiles renders with them, as
// `preskin render` renders it (the profiles baked at --profile-lut-size). The skin section alone:
// WritesJsonAndPlot runs every section.
TEST_F(BenchCli, MeasuresSceneWithItsOwnProfiles) {
    const fs::path json = dir_ / "bench.json";
    std::string err;
    ASSERT_EQ(bench({std::string(PRESKIN_SOURCE_DIR) + "/samples/assets/head/head_profiles.gltf",
                     "--width",
                     "64",
                     "--height",
                     "36",
                     "--counts",
                     "8",
                     "--skin-counts",
                     "8",
                     "--reps",
                     "1",
                     "--warmup",
                     "0",
                     "--only",
                     "skin",
                     "--no-techniques",
                     "--profile-lut-size",
                     "16",
                     "--validation",
                     "--out",
                     json.string()},
                    err),
              0)
        << err;
    const nlohmann::json j = nlohmann::json::parse(std::ifstream(json));
    ASSERT_EQ(j.at("skin_vs_standard").size(), 1u);
    EXPECT_GT(j.at("skin_vs_standard")[0].at("skin").at("wall_ms").get<double>(), 0.0);
}

// The report's sections (its top-level keys beyond the run's description and goals).
std::set<std::string> sections(const nlohmann::json& report) {
    static const std::set<std::string> header = {
        "tool", "device",        "driver",       "software_device",  "scene",  "width", "height",
        "seed", "light_density", "scene_lights", "cluster_settings", "method", "goals", "elapsed_s"};
    std::set<std::string> out;
    for (const auto& [key, value] : report.items())
        if (!header.count(key)) out.insert(key);
    return out;
}

// --only runs the named sections and nothing else (the docs' VR and animation benches rely on it).
TEST_F(BenchCli, OnlyRunsTheNamedSections) {
    const std::vector<std::string> tiny = {"--width",     "32", "--height", "18", "--vr-width",    "16",
                                           "--vr-height", "18", "--reps",   "1",  "--warmup",      "0",
                                           "--budget-s",  "1",  "--counts", "8",  "--skin-counts", "8"};
    struct Case {
        std::string only;
        std::set<std::string> expected;
    };
    for (const Case& c :
         {Case{"vr", {"vr"}},
          Case{"lights,skin", {"light_loop", "cluster_build", "skin_vs_standard", "skin_techniques"}}}) {
        const fs::path json = dir_ / ("only-" + c.only + ".json");
        std::vector<std::string> args = tiny;
        args.insert(args.end(), {"--only", c.only, "--out", json.string()});
        std::string err;
        ASSERT_EQ(bench(args, err), 0) << c.only << ": " << err;
        EXPECT_EQ(sections(nlohmann::json::parse(std::ifstream(json))), c.expected) << c.only;
    }
}

TEST_F(BenchCli, RefusesBadArgumentsBeforeWork) {
    std::string err;
    const fs::path json = dir_ / "bench.json";
    EXPECT_EQ(bench({"--only", "vr,lighting", "--out", json.string()}, err), 1);
    EXPECT_NE(err.find("--only vr,lighting: 'lighting' is not a section (sections: lut-bake, lights,"),
              std::string::npos)
        << err;
    EXPECT_EQ(bench({"--counts", "8,x", "--out", json.string()}, err), 1);
    EXPECT_NE(err.find("--counts"), std::string::npos) << err;
    { std::ofstream(dir_ / "a_file") << "x"; }  // a file where the report's folder should be
    EXPECT_EQ(bench({"--out", (dir_ / "a_file" / "b.json").string()}, err), 1);
    EXPECT_NE(err.find("is not a folder"), std::string::npos) << err;
    EXPECT_FALSE(fs::exists(json));
}

}  // namespace
}  // namespace preskin::test
