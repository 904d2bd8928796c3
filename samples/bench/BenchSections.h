// The sections of `preskin bench` (BenchCommand.cpp runs them in this order), one file each: what
// one run shares (BenchRun), and each section, which measures, writes its part of the JSON report
// and adds its goals.
#pragma once

#include "BenchMeasure.h"

#include <preskin/Environment.h>
#include <preskin/LutSet.h>
#include <preskin/ProfileLibrary.h>
#include <preskin/Scene.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace preskin::cli::bench {

// One run: what every section reads, and the sections, in the order the report lists them.
struct BenchRun {
    const BenchOptions& o;
    const CommonOptions& common;  // device, validation, profile size: as `preskin render` takes them
    const std::filesystem::path& scenePath;
    const Scene& scene;
    const Scene& standardScene;  // the scene with its skin extension removed
    bool hasSkin;
    const Environment& environment;
    const LutSet& luts;  // the default set
    const ProfileLibrary& profiles;
    Context& context;
    const View& view;  // the scene framed as `preskin render` frames it, at o.width x o.height
    const RenderSettings& base;
    Renderer& renderer;  // the scene with `base`
    Bench& bench;
    JsonWriter& j;
    std::vector<Goal>& goals;

    void goal(std::string name, double measured, double target, bool atMost) {
        goals.push_back({std::move(name), measured, target, atMost});
    }

    void lutBakeSection();                                       // lut_bake (BenchProfiles.cpp)
    void lightLoopSection(const std::vector<uint32_t>& counts);  // light_loop, cluster_build (BenchLights.cpp)
    void areaLightsSection();                                    // area_lights (BenchAreaLights.cpp)
    void skinSection(const std::vector<uint32_t>& skinCounts);   // skin_vs_standard, skin_techniques (BenchSkin.cpp)
    void environmentSection();                                   // environment (BenchEnvironment.cpp)
    void diffusionSection();                                     // diffusion_methods (BenchDiffusion.cpp)
    void vrSection();                                            // vr (BenchVr.cpp)
    void animationSection();                                     // animation (BenchAnimation.cpp)
    void profilesSection();                                      // profiles (BenchProfiles.cpp)
};

}  // namespace preskin::cli::bench
