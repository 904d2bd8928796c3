// One run of `preskin bench` (the CLI's command and the GPU kit's program call it): measures the
// renderer side by side and returns the JSON report.
//
// What it measures, on the bundled head scene (or the scene given) framed as `preskin render`
// frames it, with the scene's lights plus N scattered ones (scatterLights, --seed; with
// --light-density their ranges shrink as N grows, so a pixel's lights stay as many):
//   - clustered light loop vs brute force (LightLoop::All) at each --counts N;
//   - the cluster build: its CPU time and its compute pass, its share of the frame, and the
//     other build (CPU vs compute) at each N for comparison;
//   - lights listed per pixel (the fragment's cluster list) vs the exact number of lights whose
//     volume (range sphere, spot cone) contains the pixel's surface point: the light-count debug
//     view in linear output gives the list length and view depth per pixel; the point is
//     rebuilt from the depth on the pixel centre's ray and tested against every light on the
//     CPU (a world-space grid of the lights only narrows the candidates);
//   - the skin material vs the standard glTF metal-rough material on the same mesh, textures and
//     lights (the scene copied with its skin extension removed), plus the skin shader with every
//     technique off (SkinFeatures::none()) as a third column;
//   - the bake time of the default LUT set (LutSet::bake of d'Eon & Luebke's profile);
//   - preskin's diffusion against the baselines it replaces, screen-space and texture-space
//     (RenderSettings::diffusion), and against Lambert skin, mono at the bench size and stereo with
//     MSAA 4x at the VR size, with the passes, targets and bytes each baseline adds;
//   - diffusion profiles: one profile's bake at the default size, 64 profiles baked into a fresh
//     cache and loaded from it again (ProfileLibrary::forScene), and a frame of 8 copies of the
//     scene side by side whose skin materials use one profile against one profile per copy.
// Each frame is one Renderer::render (record, submit, wait, readback). Timing: the
// configurations compared at one light count (clustered, the other cluster build, brute force;
// or skin, standard, skin techniques off) are measured together: warm-up frames first, then
// rounds of one frame each, so a change in machine load hits all of them alike; reported are
// medians of --reps frames of wall time (CPU clock around the whole frame), of the process's CPU
// time over the frame (every thread: on a software device such as lavapipe its rendering threads,
// so the work a frame takes, less sensitive than wall time to other programs on a shared machine;
// on a GPU only the host's part) and of the GPU timestamps per pass. Slow points (brute force at
// many lights) get fewer frames: when the frame time predicted from the previous counts times
// the frames planned exceeds --budget-s, the warm-up is dropped and the repetitions cut (at
// least one); the JSON records what ran.
// Goals (docs/clustering.md) are evaluated on the wall-time medians.
// Limits: timings on a shared machine are noisy; compare numbers from one run.
// The sections live in Bench*.cpp (BenchSections.h), the measurement in BenchMeasure.h.
#include "BenchSections.h"

#include <preskin/Error.h>

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace preskin::cli::bench {

namespace {

std::vector<uint32_t> parseCounts(const std::string& text, const char* flag) {
    std::vector<uint32_t> out;
    for (float v : parseFloats(text, std::count(text.begin(), text.end(), ',') + 1, flag)) {
        if (v < 0.0f || v > float(1 << 20) || v != std::floor(v))
            throw Error(fmt::format("{} {}: light counts are whole numbers in 0..{}", flag, text, 1 << 20));
        out.push_back(static_cast<uint32_t>(v));
    }
    return out;
}

}  // namespace

BenchOptions selectSections(BenchOptions o) {
    if (o.only.empty()) return o;
    std::vector<std::string> named;
    std::stringstream list(o.only);
    for (std::string name; std::getline(list, name, ',');) {
        if (std::find_if(std::begin(kBenchSections), std::end(kBenchSections),
                         [&](const char* s) { return name == s; }) == std::end(kBenchSections)) {
            std::string valid;
            for (const char* s : kBenchSections) valid += (valid.empty() ? "" : ", ") + std::string(s);
            throw Error(fmt::format("--only {}: '{}' is not a section (sections: {})", o.only, name, valid));
        }
        named.push_back(name);
    }
    auto skipped = [&](const char* section) { return std::find(named.begin(), named.end(), section) == named.end(); };
    o.noLutBake = o.noLutBake || skipped("lut-bake");
    o.noLights = o.noLights || skipped("lights");
    o.noAreaLights = o.noAreaLights || skipped("area-lights");
    o.noSkin = o.noSkin || skipped("skin");
    o.noEnvironment = o.noEnvironment || skipped("environment");
    o.noDiffusion = o.noDiffusion || skipped("diffusion");
    o.noVr = o.noVr || skipped("vr");
    o.noAnimation = o.noAnimation || skipped("animation");
    o.noProfiles = o.noProfiles || skipped("profiles");
    return o;
}

std::string runBench(const BenchOptions& options) {
    const auto started = Clock::now();
    const BenchOptions o = selectSections(options);
    const std::vector<uint32_t> counts = o.noLights ? std::vector<uint32_t>{} : parseCounts(o.counts, "--counts");
    const std::vector<uint32_t> skinCounts =
        o.noSkin ? std::vector<uint32_t>{} : parseCounts(o.skinCounts, "--skin-counts");

    CommonOptions common;
    common.device = o.device;
    common.validation = o.validation;
    common.profileLutSize = uint32_t(o.profileLutSize);
    common.lightDensity = o.lightDensity;
    common.noCache = o.noCache;
    const std::filesystem::path scenePath = o.scene.empty() ? defaultScenePath() : std::filesystem::path(o.scene);
    const Scene scene = loadScene(scenePath, common);
    // A scene named for a later section is checked before any measurement.
    if (!o.noAnimation && !o.animatedScene.empty() && loadScene(o.animatedScene, common).animations.empty())
        throw Error(fmt::format("--animated-scene {}: animations: the scene has none", o.animatedScene));
    for (const std::string& warning : scene.warnings) fmt::print(stderr, "preskin: warning: {}\n", warning);
    Scene standardScene = scene;
    const bool hasSkin = removeSkin(standardScene);
    const Environment environment = loadEnvironment(scene, common);
    // The default LUT set, and the scene's own diffusion profiles as `preskin render` loads them.
    const auto defaultLuts = std::make_shared<const LutSet>(loadLuts(common));
    const LutSet& luts = *defaultLuts;
    const ProfileLibrary profiles = loadProfiles(scene, common, defaultLuts);
    auto context = Context::create(contextDesc(common));
    const View view = frameBoundsView(scene.worldBounds(), float(o.width) / float(o.height));

    RenderSettings base;
    base.clusters = o.clusters;
    base.clusters.fitListsToSurfaces = !o.noSurfaceFit;
    base.clusters.reuseSurfaces = !o.noSurfaceReuse;
    base.clusters.build = o.build == "cpu" ? ClusterBuild::Cpu
        : o.build == "gpu"                 ? ClusterBuild::Gpu
                                           : ClusterBuild::Auto;
    Renderer renderer(*context, scene, environment, profiles, base);
    Bench bench(o, *context, view);

    JsonWriter j;
    j.beginObject();
    j.field("tool", "preskin bench");
    j.field("device", context->deviceName());
    j.field("driver", context->driverDescription());
    j.field("software_device", context->isSoftwareDevice());
    j.field("scene", reportedPath(scenePath));
    j.field("width", o.width);
    j.field("height", o.height);
    j.field("seed", o.seed);
    j.field("light_density", o.lightDensity);
    j.field("scene_lights", scene.lights.size());
    j.key("cluster_settings");
    j.beginObject();
    j.field("tile_size_px", base.clusters.tileSizePx);
    j.field("depth_slices", base.clusters.depthSlices);
    j.field("near_slice_m", base.clusters.nearSliceM);
    j.field("fit_depth_to_scene", base.clusters.fitDepthToScene);
    j.field("fit_lists_to_surfaces", base.clusters.fitListsToSurfaces);
    j.field("reuse_surfaces", base.clusters.reuseSurfaces);
    j.field("max_lights_per_cluster", base.clusters.maxLightsPerCluster);
    j.field("max_light_indices", base.clusters.maxLightIndices);
    j.field("build", o.build);
    j.endObject();
    j.key("method");
    j.beginObject();
    j.field("frame", "Renderer::render at width x height: record, submit, wait, read back");
    j.field("timing",
            "configurations compared at one light count are interleaved frame by frame after their warm-up; "
            "medians of wall time and GPU timestamps per pass");
    j.field("reps", o.reps);
    j.field("warmup", o.warmup);
    j.field("budget_s_per_point", o.budgetS);
    j.field("speedup", "brute-force median wall ms / clustered median wall ms");
    j.field("cluster_build_share",
            "(build CPU ms + compute pass GPU ms when built on the GPU) / clustered median wall ms");
    j.field("per_pixel",
            "listed: the fragment's cluster list length; exact: lights whose range sphere (and spot cone) contains "
            "the pixel's surface point");
    j.field("standard_material", "the same scene with the skin extension removed (glTF metal-rough shading)");
    j.endObject();

    std::vector<Goal> goals;
    BenchRun r{o,        common,   scenePath, scene, standardScene, hasSkin, environment, luts,
               profiles, *context, view,      base,  renderer,      bench,   j,           goals};
    // The LUT bake first (lut_bake), the profiles' figures at the end (profiles).
    if (!o.noLutBake) r.lutBakeSection();
    if (!o.noLights) r.lightLoopSection(counts);
    if (!o.noAreaLights) r.areaLightsSection();
    r.skinSection(skinCounts);
    if (!o.noEnvironment) r.environmentSection();
    if (!o.noDiffusion) r.diffusionSection();
    if (!o.noVr) r.vrSection();
    if (!o.noAnimation) r.animationSection();
    if (!o.noProfiles) r.profilesSection();

    // Goals (docs/clustering.md and each section's), on this run's figures.
    j.key("goals");
    j.beginArray();
    for (const Goal& g : goals) {
        j.beginObject();
        j.field("goal", g.name);
        j.field("target", g.target);
        j.field("measured", g.measured);
        j.field("holds", std::isfinite(g.measured) && (g.atMost ? g.measured <= g.target : g.measured >= g.target));
        j.endObject();
    }
    j.endArray();
    j.field("elapsed_s", secondsSince(started));
    j.endObject();

    return j.text() + "\n";
}

}  // namespace preskin::cli::bench
