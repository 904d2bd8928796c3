// `preskin bench`: measures the renderer side by side in one run and writes JSON (stdout or
// --out); scripts/plot-bench.py draws frame time against light count from it.
//
// What it measures, on the bundled head scene (or the scene given) framed as `preskin render`
// frames it, with the scene's lights plus N scattered ones (scatterLights, --seed):
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
#include "Commands.h"
#include "CommandLine.h"
#include "JsonWriter.h"
#include "Options.h"  // samples/common

#include <preskin/Animation.h>
#include <preskin/ClusterGrid.h>
#include <preskin/Context.h>
#include <preskin/Curvature.h>
#include <preskin/Deformation.h>
#include <preskin/DiffusionProfile.h>
#include <preskin/Environment.h>
#include <preskin/Error.h>
#include <preskin/OutputFile.h>
#include <preskin/LightScatter.h>
#include <preskin/LutSet.h>
#include <preskin/ProfileLibrary.h>
#include <preskin/Renderer.h>
#include <preskin/Scene.h>
#include <preskin/View.h>

#include <fmt/core.h>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace preskin::cli {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// CPU time of the whole process (all threads), ms.
double processCpuMs() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

// ---- measurement -----------------------------------------------------------------------------

struct BenchOptions {
    std::string scene;
    std::string out;
    uint32_t width = 1280;
    uint32_t height = 720;
    std::string counts = "16,64,256,1024,4096";
    std::string skinCounts = "256,1024";
    uint32_t seed = 1;
    uint32_t warmup = 1;
    uint32_t reps = 5;
    double budgetS = 15.0;
    ClusterSettings clusters;
    std::string build = "auto";
    bool noBuildCompare = false;
    bool noBrute = false;
    bool noSkin = false;
    bool noPerPixel = false;
    bool noLutBake = false;
    bool noVr = false;
    bool noAnimation = false;
    bool noTechniques = false;
    bool noProfiles = false;
    bool noEnvironment = false;
    int profileLutSize = 256;
    std::string animatedScene;
    uint32_t vrWidth = 640;
    uint32_t vrHeight = 720;
    uint32_t vrLights = 256;
    float ipdM = 0.063f;
    std::string device;
    bool validation = false;
};

// A scene path as the JSON reports it: relative to the data folder for bundled assets, so results
// do not carry the machine's folders.
std::string reportedPath(const std::filesystem::path& path) {
    const std::filesystem::path relative = path.lexically_relative(dataDir());
    return !relative.empty() && *relative.begin() != ".." ? relative.generic_string() : path.string();
}

double median(std::vector<double> v) {
    if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct Measurement {
    uint32_t warmup = 0;
    std::vector<FrameStats> frames;
    std::vector<double> cpuMsEach;  // the process's CPU time over each frame

    double cpuMs() const { return median(cpuMsEach); }
    double wallMs() const { return medianOf([](const FrameStats& s) { return s.wallMs; }); }
    double gpuMs() const { return medianOf([](const FrameStats& s) { return s.gpuMs; }); }
    double buildCpuMs() const { return medianOf([](const FrameStats& s) { return s.clusterBuildCpuMs; }); }
    double recordCpuMs() const { return medianOf([](const FrameStats& s) { return s.recordCpuMs; }); }
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

void writeMeasurement(JsonWriter& j, const Measurement& m) {
    j.beginObject();
    j.field("warmup_frames", m.warmup);
    j.field("frames", m.frames.size());
    j.field("wall_ms", m.wallMs());
    j.field("cpu_ms", m.cpuMs());
    j.field("gpu_ms", m.gpuMs());
    j.key("gpu_pass_ms");
    j.beginObject();
    if (!m.frames.empty())
        for (const PassTime& p : m.frames.front().passes) j.field(p.name, m.passMs(p.name));
    j.endObject();
    j.field("cluster_build_cpu_ms", m.buildCpuMs());
    j.field("cluster_build_ms", m.buildMs());
    j.field("cluster_build", m.buildGpu() ? "gpu" : "cpu");
    j.field("record_cpu_ms", m.recordCpuMs());
    if (!m.frames.empty()) {
        j.field("eyes", m.frames.back().eyes);
        j.field("eye_drawing", m.frames.back().eyeDrawing == EyeDrawing::InstancedLayers ? "instanced layers" : "multiview");
    }
    j.field("overflowed_clusters", m.overflows());
    j.key("wall_ms_each");
    j.beginArray();
    for (const FrameStats& s : m.frames) j.number(s.wallMs);
    j.endArray();
    j.endObject();
}

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

    // Measures configurations side by side with the same lights: the warm-ups first, then
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
double predictFrameMs(const std::vector<std::pair<double, double>>& points, double n) {
    if (points.empty()) return 0.0;
    if (points.size() == 1) return points.back().second * std::max(1.0, n / std::max(points.back().first, 1.0));
    const auto [n0, t0] = points[points.size() - 2];
    const auto [n1, t1] = points.back();
    const double slope = n1 > n0 ? std::max((t1 - t0) / (n1 - n0), 0.0) : 0.0;
    return t1 + slope * (n - n1);
}

// ---- lights per pixel --------------------------------------------------------------------------

struct PerPixel {
    uint64_t pixels = 0;
    double listedMean = 0.0;
    double exactMean = 0.0;
    uint32_t listedMax = 0;
    uint32_t exactMax = 0;
    uint64_t listedBelowExact = 0;  // pixels whose list is shorter than the exact count (a bug)
    double otherListedMean = 0.0;   // the list length another grid (countPerPixel's `other`) gives
};

// Does the light's volume contain p? Range sphere (the attenuation window is zero at the range)
// and, for spots, the outer cone (the cone attenuation is zero at its edge).
bool lightTouches(const Light& l, const glm::dvec3& p) {
    const glm::dvec3 toPoint = p - glm::dvec3(l.positionWs);
    const double d2 = glm::dot(toPoint, toPoint);
    if (l.range > 0.0f && d2 >= double(l.range) * double(l.range)) return false;
    if (l.type != LightType::Spot) return true;
    const double d = std::sqrt(d2);
    if (d <= 0.0) return true;
    const glm::dvec3 dir = glm::length(l.directionWs) > 0.0f ? glm::normalize(glm::dvec3(l.directionWs))
                                                             : glm::dvec3(0.0, 0.0, -1.0);
    return glm::dot(dir, toPoint) / d > std::cos(double(l.outerConeAngle));
}

// `image`: the light-count debug view in linear output (r: lights listed, b: view depth in m).
// `other`, when given: a second grid over the same lights, whose list length at each pixel's
// surface point is averaged too.
PerPixel countPerPixel(const RenderedImage& image, const Eye& view, const std::vector<Light>& lights,
                       const ClusterGrid* other = nullptr) {
    const glm::dmat4 clipFromView(view.clipFromView);
    const glm::dmat4 viewFromClip = glm::inverse(clipFromView);
    const glm::dmat4 worldFromView = glm::inverse(glm::dmat4(view.viewFromWorld));
    struct Sample {
        glm::dvec3 positionWs;
        uint32_t listed;
    };
    std::vector<Sample> samples;
    glm::dvec3 lo(std::numeric_limits<double>::max());
    glm::dvec3 hi(-std::numeric_limits<double>::max());
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x) {
            const float* px = &image.rgba32f[(size_t(y) * image.width + x) * 4];
            const double depth = px[2];
            if (!(depth > 0.5 * double(view.nearM))) continue;  // background (clear colour)
            const glm::dvec4 clip = clipFromView * glm::dvec4(0.0, 0.0, -depth, 1.0);
            const glm::dvec4 ndc((x + 0.5) / image.width * 2.0 - 1.0, (y + 0.5) / image.height * 2.0 - 1.0,
                                 clip.z / clip.w, 1.0);
            glm::dvec4 p = viewFromClip * ndc;
            p /= p.w;
            const glm::dvec3 world(worldFromView * p);
            samples.push_back({world, static_cast<uint32_t>(std::lround(px[0]))});
            lo = glm::min(lo, world);
            hi = glm::max(hi, world);
        }
    PerPixel out;
    if (samples.empty()) return out;

    // Candidate lights per cell of a grid over the surface points.
    const int n = 32;
    const glm::dvec3 cell = glm::max((hi - lo) / double(n), glm::dvec3(1e-6));
    std::vector<std::vector<uint32_t>> cells(size_t(n) * n * n);
    std::vector<uint32_t> everywhere;
    auto cellOf = [&](const glm::dvec3& p) {
        return glm::clamp(glm::ivec3(glm::floor((p - lo) / cell)), glm::ivec3(0), glm::ivec3(n - 1));
    };
    for (uint32_t i = 0; i < lights.size(); ++i) {
        const Light& l = lights[i];
        if (l.type == LightType::Directional) continue;
        if (!(l.range > 0.0f)) {
            everywhere.push_back(i);
            continue;
        }
        const glm::dvec3 c(l.positionWs);
        const double r = l.range;
        if (glm::any(glm::lessThan(c + r, lo)) || glm::any(glm::greaterThan(c - r, hi))) continue;
        const glm::ivec3 a = cellOf(c - r);
        const glm::ivec3 b = cellOf(c + r);
        for (int z = a.z; z <= b.z; ++z)
            for (int y = a.y; y <= b.y; ++y)
                for (int x = a.x; x <= b.x; ++x) cells[(size_t(z) * n + size_t(y)) * n + size_t(x)].push_back(i);
    }
    double listedSum = 0.0;
    double exactSum = 0.0;
    double otherSum = 0.0;
    for (const Sample& s : samples) {
        if (other) otherSum += other->ranges[other->froxelAt(glm::vec3(s.positionWs))].y;
        const glm::ivec3 c = cellOf(s.positionWs);
        uint32_t exact = 0;
        for (uint32_t i : cells[(size_t(c.z) * n + size_t(c.y)) * n + size_t(c.x)])
            if (lightTouches(lights[i], s.positionWs)) ++exact;
        for (uint32_t i : everywhere)
            if (lightTouches(lights[i], s.positionWs)) ++exact;
        listedSum += s.listed;
        exactSum += exact;
        out.listedMax = std::max(out.listedMax, s.listed);
        out.exactMax = std::max(out.exactMax, exact);
        if (s.listed < exact) ++out.listedBelowExact;
    }
    out.pixels = samples.size();
    out.listedMean = listedSum / double(samples.size());
    out.exactMean = exactSum / double(samples.size());
    out.otherListedMean = otherSum / double(samples.size());
    return out;
}

// ---- the command ---------------------------------------------------------------------------------

std::vector<uint32_t> parseCounts(const std::string& text, const char* flag) {
    std::vector<uint32_t> out;
    for (float v : parseFloats(text, std::count(text.begin(), text.end(), ',') + 1, flag)) {
        if (v < 0.0f || v > float(1 << 20) || v != std::floor(v))
            throw Error(fmt::format("{} {}: light counts are whole numbers in 0..{}", flag, text, 1 << 20));
        out.push_back(static_cast<uint32_t>(v));
    }
    return out;
}

struct ProfileFigures {
    double bakeOneMs = 0.0;
    int cachedCount = 64;
    double bakeAllMs = 0.0;
    double loadCachedMs = 0.0;
    int copies = 8;
    Measurement single;
    Measurement eight;
};

// `copies` copies of the scene's meshes side by side along +X (each with its own materials),
// every skin material of copy k naming profile k, or the default (-1) when `oneProfile`.
Scene sideBySideCopies(const Scene& scene, int copies, bool oneProfile) {
    Scene out = scene;
    out.instances.clear();
    out.meshes.clear();
    out.materials.clear();
    out.animations.clear();
    const Bounds bounds = scene.worldBounds();
    const float stepM = 1.1f * (bounds.max.x - bounds.min.x);
    for (int k = 0; k < copies; ++k) {
        const int firstMaterial = static_cast<int>(out.materials.size());
        for (Material m : scene.materials) {
            if (m.skin) m.skin->profile = oneProfile ? -1 : k;
            out.materials.push_back(std::move(m));
        }
        const int firstMesh = static_cast<int>(out.meshes.size());
        for (Mesh mesh : scene.meshes) {
            for (Primitive& p : mesh.primitives)
                if (p.material >= 0) p.material += firstMaterial;
            out.meshes.push_back(std::move(mesh));
        }
        const float offset = (float(k) - 0.5f * float(copies - 1)) * stepM;
        for (MeshInstance instance : scene.instances) {
            instance.mesh += firstMesh;
            instance.worldFromObject = glm::translate(glm::mat4(1.0f), glm::vec3(offset, 0.0f, 0.0f)) * instance.worldFromObject;
            instance.skin = -1;
            out.instances.push_back(std::move(instance));
        }
    }
    return out;
}

ProfileFigures measureProfiles(const BenchOptions& o, Bench& bench, Context& context, const Scene& scene,
                               const Environment& environment, const LutSet& luts, const RenderSettings& base) {
    ProfileFigures f;
    fmt::print(stderr, "preskin bench: baking one profile...");
    std::fflush(stderr);
    auto start = Clock::now();
    const LutBakeSettings settings = LutBakeSettings::withSize(o.profileLutSize);
    (void)LutSet::bake(DiffusionProfile::burley({0.85, 0.55, 0.45}, {1.5, 0.6, 0.35}), settings);
    f.bakeOneMs = secondsSince(start) * 1000.0;
    fmt::print(stderr, " {:.0f} ms\n", f.bakeOneMs);

    Scene many;
    for (int i = 0; i < f.cachedCount; ++i)
        many.profiles.push_back({fmt::format("p{}", i),
                                 DiffusionProfile::burley({0.5 + 0.5 * i / (f.cachedCount - 1.0), 0.55, 0.45},
                                                          {1.0 + 0.05 * i, 0.6, 0.35}),
                                 {}});
    char pattern[] = "/tmp/preskin-bench-cache-XXXXXX";
    if (!mkdtemp(pattern)) throw Error("preskin bench: cannot create a temporary cache folder");
    const std::filesystem::path cacheFolder = pattern;
    const auto shared = std::make_shared<const LutSet>(luts);
    try {
        fmt::print(stderr, "preskin bench: baking {} profiles into a fresh cache...", f.cachedCount);
        std::fflush(stderr);
        start = Clock::now();
        (void)ProfileLibrary::forScene(many, shared, settings, {true, cacheFolder});
        f.bakeAllMs = secondsSince(start) * 1000.0;
        fmt::print(stderr, " {:.0f} ms; loading them from the cache...", f.bakeAllMs);
        std::fflush(stderr);
        std::vector<double> loads;
        for (int rep = 0; rep < 3; ++rep) {
            const ProfileLibrary loaded = ProfileLibrary::forScene(many, shared, settings, {true, cacheFolder});
            if (loaded.stats().cacheHits != f.cachedCount) throw Error("preskin bench: the profile cache missed");
            loads.push_back(loaded.stats().wallMs);
        }
        f.loadCachedMs = median(loads);
        fmt::print(stderr, " {:.0f} ms\n", f.loadCachedMs);
    } catch (...) {
        std::error_code ec;
        std::filesystem::remove_all(cacheFolder, ec);
        throw;
    }
    std::error_code ec;
    std::filesystem::remove_all(cacheFolder, ec);

    Scene one = sideBySideCopies(scene, f.copies, true);
    Scene eight = sideBySideCopies(scene, f.copies, false);
    eight.profiles.assign(many.profiles.begin(), many.profiles.begin() + f.copies);
    const ProfileLibrary library = ProfileLibrary::forScene(eight, shared, settings, {false, {}});
    Renderer oneRenderer(context, one, environment, library, base);
    Renderer eightRenderer(context, eight, environment, library, base);
    const View view = frameBoundsView(one.worldBounds(), float(o.width) / float(o.height));
    std::vector<Measurement> measured =
        bench.measure({{&oneRenderer, base, fmt::format("{} copies, one profile", f.copies), 0.0, &view, o.width, o.height},
                       {&eightRenderer, base, fmt::format("{} copies, {} profiles", f.copies, f.copies), 0.0, &view,
                        o.width, o.height}},
                      sceneLights(one, CommonOptions{}));
    f.single = std::move(measured[0]);
    f.eight = std::move(measured[1]);
    return f;
}

void run(const BenchOptions& o) {
    const auto started = Clock::now();
    const std::vector<uint32_t> counts = parseCounts(o.counts, "--counts");
    const std::vector<uint32_t> skinCounts = o.noSkin ? std::vector<uint32_t>{} : parseCounts(o.skinCounts, "--skin-counts");
    if (!o.out.empty()) checkOutputFile(o.out);

    CommonOptions common;
    common.device = o.device;
    common.validation = o.validation;
    common.profileLutSize = uint32_t(o.profileLutSize);
    const std::filesystem::path scenePath = o.scene.empty() ? defaultScenePath() : std::filesystem::path(o.scene);
    const Scene scene = loadScene(scenePath, common);
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
    base.clusters.build = o.build == "cpu" ? ClusterBuild::Cpu : o.build == "gpu" ? ClusterBuild::Gpu : ClusterBuild::Auto;
    Renderer renderer(*context, scene, environment, profiles, base);
    Bench bench(o, *context, view);

    JsonWriter j;
    j.beginObject();
    j.field("tool", "preskin bench");
    j.field("device", context->deviceName());
    j.field("software_device", context->isSoftwareDevice());
    j.field("scene", reportedPath(scenePath));
    j.field("width", o.width);
    j.field("height", o.height);
    j.field("seed", o.seed);
    j.field("scene_lights", scene.lights.size());
    j.key("cluster_settings");
    j.beginObject();
    j.field("tile_size_px", base.clusters.tileSizePx);
    j.field("depth_slices", base.clusters.depthSlices);
    j.field("near_slice_m", base.clusters.nearSliceM);
    j.field("fit_depth_to_scene", base.clusters.fitDepthToScene);
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
    j.field("cluster_build_share", "(build CPU ms + compute pass GPU ms when built on the GPU) / clustered median wall ms");
    j.field("per_pixel",
            "listed: the fragment's cluster list length; exact: lights whose range sphere (and spot cone) contains "
            "the pixel's surface point");
    j.field("standard_material", "the same scene with the skin extension removed (glTF metal-rough shading)");
    j.endObject();

    // LUT bake of the default set.
    if (!o.noLutBake) {
        fmt::print(stderr, "preskin bench: LUT bake of the default set...");
        std::fflush(stderr);
        const auto bakeStart = Clock::now();
        const LutSet baked = LutSet::bake(DiffusionProfile::deonLuebke());
        const double bakeMs = secondsSince(bakeStart) * 1000.0;
        fmt::print(stderr, " {:.0f} ms\n", bakeMs);
        j.key("lut_bake");
        j.beginObject();
        j.field("profile", baked.profile().name());
        j.field("ms", bakeMs);
        j.endObject();
    }

    // Clustered vs brute force, per-pixel counts, and the other build.
    struct Row {
        uint32_t lights;
        Measurement clustered;
        std::optional<Measurement> brute;
        std::optional<Measurement> otherBuild;
        std::optional<PerPixel> perPixel;
    };
    std::vector<Row> rows;
    std::vector<std::pair<double, double>> bruteHistory;
    std::vector<std::pair<double, double>> clusteredHistory;
    std::vector<std::pair<double, double>> otherHistory;
    const ClusterBuild otherBuild = [&] {
        // Which build the main measurement uses shows in its frame stats; the first frame tells.
        RenderSettings probe = base;
        renderer.setSettings(probe);
        renderer.render(view, 16, 16, OutputEncoding::DisplaySrgb8);
        return renderer.frameStats().clusterBuildGpu ? ClusterBuild::Cpu : ClusterBuild::Gpu;
    }();
    for (uint32_t n : counts) {
        CommonOptions withLights = common;
        withLights.lights = n;
        withLights.seed = o.seed;
        const std::vector<Light> lights = sceneLights(scene, withLights);
        Row row{n, {}, {}, {}, {}};
        std::vector<Config> configs;
        RenderSettings clustered = base;
        clustered.lightLoop = LightLoop::Clustered;
        configs.push_back({&renderer, clustered, fmt::format("{} lights, clustered", n), predictFrameMs(clusteredHistory, n)});
        if (!o.noBuildCompare) {
            RenderSettings other = clustered;
            other.clusters.build = otherBuild;
            configs.push_back({&renderer, other,
                               fmt::format("{} lights, clustered, {} build", n, otherBuild == ClusterBuild::Gpu ? "gpu" : "cpu"),
                               predictFrameMs(otherHistory, n)});
        }
        if (!o.noBrute) {
            RenderSettings brute = base;
            brute.lightLoop = LightLoop::All;
            configs.push_back({&renderer, brute, fmt::format("{} lights, brute force", n), predictFrameMs(bruteHistory, n)});
        }
        std::vector<Measurement> measured = bench.measure(configs, lights);
        size_t next = 0;
        row.clustered = std::move(measured[next++]);
        clusteredHistory.emplace_back(n, row.clustered.wallMs());
        if (!o.noBuildCompare) {
            row.otherBuild = std::move(measured[next++]);
            otherHistory.emplace_back(n, row.otherBuild->wallMs());
        }
        if (!o.noBrute) {
            row.brute = std::move(measured[next++]);
            bruteHistory.emplace_back(n, row.brute->wallMs());
        }
        if (!o.noPerPixel) {
            RenderSettings debug = clustered;
            debug.debugView = DebugView::LightCount;
            renderer.setSettings(debug);
            renderer.setLights(lights);
            const RenderedImage counted = renderer.render(view, o.width, o.height, OutputEncoding::LinearFloat);
            row.perPixel = countPerPixel(counted, view.eye(), lights);
            reportValidation(*context);
        }
        rows.push_back(std::move(row));
    }

    j.key("light_loop");
    j.beginArray();
    for (const Row& row : rows) {
        j.beginObject();
        j.field("lights", row.lights);
        j.key("clustered");
        writeMeasurement(j, row.clustered);
        if (row.brute) {
            j.key("brute_force");
            writeMeasurement(j, *row.brute);
            j.field("speedup", row.brute->wallMs() / row.clustered.wallMs());
            j.field("speedup_gpu", row.brute->gpuMs() / row.clustered.gpuMs());
        }
        j.field("cluster_build_share", row.clustered.buildMs() / row.clustered.wallMs());
        if (row.perPixel) {
            const PerPixel& p = *row.perPixel;
            j.key("per_pixel");
            j.beginObject();
            j.field("pixels", p.pixels);
            j.field("listed_mean", p.listedMean);
            j.field("exact_mean", p.exactMean);
            j.field("listed_over_exact", p.exactMean > 0.0 ? p.listedMean / p.exactMean : std::nan(""));
            j.field("listed_max", p.listedMax);
            j.field("exact_max", p.exactMax);
            j.field("pixels_listed_below_exact", p.listedBelowExact);
            j.endObject();
        }
        j.endObject();
    }
    j.endArray();

    if (!o.noBuildCompare) {
        j.key("cluster_build");
        j.beginArray();
        for (const Row& row : rows) {
            if (!row.otherBuild) continue;
            const Measurement& cpu = row.clustered.buildGpu() ? *row.otherBuild : row.clustered;
            const Measurement& gpu = row.clustered.buildGpu() ? row.clustered : *row.otherBuild;
            j.beginObject();
            j.field("lights", row.lights);
            for (const auto& [name, m] : {std::pair<const char*, const Measurement*>{"cpu", &cpu}, {"gpu", &gpu}}) {
                j.key(name);
                j.beginObject();
                j.field("build_ms", m->buildMs());
                j.field("build_cpu_ms", m->buildCpuMs());
                j.field("clusters_pass_gpu_ms", m->passMs("clusters"));
                j.field("frame_wall_ms", m->wallMs());
                j.field("frames", m->frames.size());
                j.endObject();
            }
            j.endObject();
        }
        j.endArray();
    }

    // Skin vs standard material, same lights.
    struct SkinRow {
        uint32_t lights;
        Measurement skin, standard, featuresOff;
    };
    std::vector<SkinRow> skinRows;
    if (!skinCounts.empty() && hasSkin) {
        Renderer standardRenderer(*context, standardScene, environment, profiles, base);
        for (uint32_t n : skinCounts) {
            CommonOptions withLights = common;
            withLights.lights = n;
            withLights.seed = o.seed;
            const std::vector<Light> lights = sceneLights(scene, withLights);
            RenderSettings off = base;
            off.skin = SkinFeatures::none();
            std::vector<Measurement> measured =
                bench.measure({{&renderer, base, fmt::format("{} lights, skin", n), 0.0},
                               {&standardRenderer, base, fmt::format("{} lights, standard material", n), 0.0},
                               {&renderer, off, fmt::format("{} lights, skin techniques off", n), 0.0}},
                              lights);
            skinRows.push_back({n, std::move(measured[0]), std::move(measured[1]), std::move(measured[2])});
        }
        j.key("skin_vs_standard");
        j.beginArray();
        for (const SkinRow& row : skinRows) {
            j.beginObject();
            j.field("lights", row.lights);
            j.key("skin");
            writeMeasurement(j, row.skin);
            j.key("standard_material");
            writeMeasurement(j, row.standard);
            j.key("skin_features_off");
            writeMeasurement(j, row.featuresOff);
            j.field("skin_over_standard", row.skin.wallMs() / row.standard.wallMs());
            j.field("skin_over_standard_gpu", row.skin.gpuMs() / row.standard.gpuMs());
            j.field("skin_over_standard_cpu", row.skin.cpuMs() / row.standard.cpuMs());
            j.field("skin_over_features_off", row.skin.wallMs() / row.featuresOff.wallMs());
            j.endObject();
        }
        j.endArray();

        // What each technique costs: the skin frame with one technique off at a time, beside the
        // frame with all on, the standard material and all off, interleaved (first skin count).
        if (!o.noTechniques) {
            const uint32_t n = skinCounts.front();
            CommonOptions withLights = common;
            withLights.lights = n;
            withLights.seed = o.seed;
            const std::vector<Light> lights = sceneLights(scene, withLights);
            struct Technique {
                const char* name;
                bool SkinFeatures::*flag;
            };
            const Technique techniques[] = {{"lut_diffuse", &SkinFeatures::lutDiffuse},
                                            {"normal_prefilter", &SkinFeatures::normalPrefilter},
                                            {"penumbra", &SkinFeatures::penumbra},
                                            {"sh_ambient", &SkinFeatures::shAmbient},
                                            {"transmission", &SkinFeatures::transmission},
                                            {"dual_specular", &SkinFeatures::dualSpecular}};
            std::vector<Config> configs{{&renderer, base, fmt::format("{} lights, skin", n), 0.0},
                                        {&standardRenderer, base, fmt::format("{} lights, standard material", n), 0.0}};
            for (const Technique& t : techniques) {
                RenderSettings without = base;
                without.skin.*t.flag = false;
                configs.push_back({&renderer, without, fmt::format("{} lights, skin without {}", n, t.name), 0.0});
            }
            const std::vector<Measurement> measured = bench.measure(configs, lights);
            j.key("skin_techniques");
            j.beginObject();
            j.field("lights", n);
            j.field("method",
                    "each technique's cost: the all-on skin frame minus the frame with that technique off (its "
                    "standard fallback on), interleaved; wall, process CPU and forward-pass GPU ms");
            j.key("skin");
            writeMeasurement(j, measured[0]);
            j.key("standard_material");
            writeMeasurement(j, measured[1]);
            j.key("cost_ms");
            j.beginObject();
            for (size_t i = 0; i < std::size(techniques); ++i) {
                j.key(techniques[i].name);
                j.beginObject();
                j.field("wall", measured[0].wallMs() - measured[2 + i].wallMs());
                j.field("cpu", measured[0].cpuMs() - measured[2 + i].cpuMs());
                j.field("forward_gpu", measured[0].passMs("forward") - measured[2 + i].passMs("forward"));
                j.endObject();
            }
            j.endObject();
            j.field("skin_over_standard", measured[0].wallMs() / measured[1].wallMs());
            j.field("skin_over_standard_gpu", measured[0].gpuMs() / measured[1].gpuMs());
            j.field("skin_over_standard_cpu", measured[0].cpuMs() / measured[1].cpuMs());
            j.endObject();
        }
    } else if (!skinCounts.empty()) {
        fmt::print(stderr, "preskin bench: the scene has no skin material; skipping skin vs standard\n");
    }

    // The environment: the frame with specular IBL and the environment as background against the
    // frame with neither (SH specular, cleared background), interleaved with the scene's own
    // lights; and the environment's update (light extraction, upload, prefiltering on the device).
    if (!o.noEnvironment) {
        const std::vector<Light> lights = sceneLights(scene, common);
        RenderSettings full = base, noBackground = base, neither = base;
        full.background.mode = BackgroundMode::Environment;
        neither.specularIbl = false;
        const std::vector<Measurement> measured =
            bench.measure({{&renderer, full, "specular IBL and background", 0.0},
                           {&renderer, noBackground, "specular IBL, cleared background", 0.0},
                           {&renderer, neither, "SH specular, cleared background", 0.0}},
                          lights);
        std::vector<double> updateMs;
        for (int i = 0; i < 3; ++i) {
            const auto start = std::chrono::steady_clock::now();
            renderer.setEnvironment(environment);
            updateMs.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
        }
        std::sort(updateMs.begin(), updateMs.end());
        j.key("environment");
        j.beginObject();
        j.field("method",
                "frames with the prefiltered specular and the environment as background, with the prefiltered "
                "specular alone and with neither (SH specular, cleared background), interleaved; the update: "
                "Renderer::setEnvironment (dominant lights, upload, GGX prefiltering), median of 3");
        j.field("image_width", environment.image().width);
        j.key("ibl_and_background");
        writeMeasurement(j, measured[0]);
        j.key("ibl");
        writeMeasurement(j, measured[1]);
        j.key("neither");
        writeMeasurement(j, measured[2]);
        j.field("ibl_and_background_share_of_frame", (measured[0].wallMs() - measured[2].wallMs()) / measured[0].wallMs());
        j.field("ibl_and_background_share_of_forward_gpu",
                (measured[0].passMs("forward") - measured[2].passMs("forward")) / measured[0].passMs("forward"));
        j.field("update_ms", updateMs[1]);
        j.endObject();
    }

    // VR: a stereo frame against the two mono frames of its eyes, the light grid built for both
    // eyes (one grid through the cluster camera) against a grid per eye, and MSAA 4x against 1x.
    struct VrRun {
        Measurement stereo, left, right;
        std::optional<Measurement> msaa1, msaa4;
        Measurement recordStereo, recordMono;
        double combinedBuildMs = 0.0, perEyeBuildMs = 0.0;
        PerPixel perPixel[2];
    };
    std::optional<VrRun> vr;
    if (!o.noVr) {
        CommonOptions withLights = common;
        withLights.lights = o.vrLights;
        withLights.seed = o.seed;
        const std::vector<Light> lights = sceneLights(scene, withLights);
        const View stereo =
            stereoFromMono(frameBoundsView(scene.worldBounds(), float(o.vrWidth) / float(o.vrHeight)), o.ipdM);
        const View left(stereo.eyes[0]);
        const View right(stereo.eyes[1]);
        VrRun run;
        // One renderer per eye count and sample count, as an application keeps them: a renderer
        // resizes its attachments when either changes.
        Renderer stereoRenderer(*context, scene, environment, profiles, base);
        Renderer monoRenderer(*context, scene, environment, profiles, base);
        std::vector<Measurement> eyes = bench.measure(
            {{&stereoRenderer, base, fmt::format("{} lights, stereo {}x{} per eye", o.vrLights, o.vrWidth, o.vrHeight),
              0.0, &stereo, o.vrWidth, o.vrHeight},
             {&monoRenderer, base, "left eye mono", 0.0, &left, o.vrWidth, o.vrHeight},
             {&monoRenderer, base, "right eye mono", 0.0, &right, o.vrWidth, o.vrHeight}},
            lights);
        run.stereo = std::move(eyes[0]);
        run.left = std::move(eyes[1]);
        run.right = std::move(eyes[2]);
        // CPU recording alone (Renderer::record without the light-grid build): ~0.1 ms, so many
        // small interleaved frames; recording does not depend on the image size.
        {
            BenchOptions many = o;
            many.reps = std::max<uint32_t>(o.reps, 1) * 12;
            many.warmup = 3;
            Bench recordBench(many, *context, stereo);
            std::vector<Measurement> recorded =
                recordBench.measure({{&stereoRenderer, base, "recording: stereo, 32x36 per eye", 0.0, &stereo, 32, 36},
                                     {&monoRenderer, base, "recording: left eye mono, 32x36", 0.0, &left, 32, 36}},
                                    lights);
            run.recordStereo = std::move(recorded[0]);
            run.recordMono = std::move(recorded[1]);
        }
        const std::vector<uint32_t> offered = renderer.msaaSampleCounts();
        if (std::find(offered.begin(), offered.end(), 4u) != offered.end()) {
            RenderSettings four = base;
            four.msaaSamples = 4;
            Renderer msaaRenderer(*context, scene, environment, profiles, four);
            std::vector<Measurement> msaa = bench.measure(
                {{&renderer, base, fmt::format("{} lights, MSAA 1x", o.vrLights), 0.0},
                 {&msaaRenderer, four, fmt::format("{} lights, MSAA 4x", o.vrLights), 0.0}},
                lights);
            run.msaa1 = std::move(msaa[0]);
            run.msaa4 = std::move(msaa[1]);
        }
        // Grid layouts, CPU builds interleaved: one grid for both eyes vs one grid per eye.
        std::vector<double> combined, perEye;
        ClusterGrid eyeGrids[2];
        for (uint32_t r = 0; r < std::max<uint32_t>(o.reps, 1) + 1; ++r) {
            auto t0 = Clock::now();
            const ClusterGrid both =
                buildClusterGrid(base.clusters, stereo, o.vrWidth, o.vrHeight, scene.worldBounds(), lights);
            auto t1 = Clock::now();
            for (uint32_t e = 0; e < 2; ++e)
                eyeGrids[e] = buildClusterGrid(base.clusters, View(stereo.eyes[e]), o.vrWidth, o.vrHeight,
                                               scene.worldBounds(), lights);
            auto t2 = Clock::now();
            if (r == 0) continue;  // warm-up
            combined.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
            perEye.push_back(std::chrono::duration<double, std::milli>(t2 - t1).count());
        }
        run.combinedBuildMs = median(combined);
        run.perEyeBuildMs = median(perEye);
        if (!o.noPerPixel) {
            RenderSettings debug = base;
            debug.debugView = DebugView::LightCount;
            stereoRenderer.setSettings(debug);
            stereoRenderer.setLights(lights);
            const RenderedImage counted = stereoRenderer.render(stereo, o.vrWidth, o.vrHeight, OutputEncoding::LinearFloat);
            for (uint32_t e = 0; e < 2; ++e)
                run.perPixel[e] = countPerPixel(eyeImage(counted, e), stereo.eyes[e], lights, &eyeGrids[e]);
            reportValidation(*context);
        }
        vr = std::move(run);

        j.key("vr");
        j.beginObject();
        j.field("lights", o.vrLights);
        j.field("eye_width", o.vrWidth);
        j.field("eye_height", o.vrHeight);
        j.field("ipd_m", o.ipdM);
        j.key("stereo");
        writeMeasurement(j, vr->stereo);
        j.key("left_mono");
        writeMeasurement(j, vr->left);
        j.key("right_mono");
        writeMeasurement(j, vr->right);
        j.field("stereo_over_two_mono", vr->stereo.wallMs() / (vr->left.wallMs() + vr->right.wallMs()));
        j.field("stereo_over_two_mono_gpu", vr->stereo.gpuMs() / (vr->left.gpuMs() + vr->right.gpuMs()));
        j.field("grid_build_stereo_over_mono", vr->stereo.buildMs() / vr->left.buildMs());
        j.field("record_cpu_stereo_ms", vr->recordStereo.recordCpuMs());
        j.field("record_cpu_mono_ms", vr->recordMono.recordCpuMs());
        j.field("record_cpu_frames", vr->recordStereo.frames.size());
        j.field("record_cpu_stereo_over_mono", vr->recordStereo.recordCpuMs() / vr->recordMono.recordCpuMs());
        if (vr->msaa1) {
            j.key("msaa");
            j.beginObject();
            j.field("samples", 4);
            j.key("msaa_1x");
            writeMeasurement(j, *vr->msaa1);
            j.key("msaa_4x");
            writeMeasurement(j, *vr->msaa4);
            j.field("msaa4_over_msaa1", vr->msaa4->wallMs() / vr->msaa1->wallMs());
            j.field("msaa4_over_msaa1_gpu", vr->msaa4->gpuMs() / vr->msaa1->gpuMs());
            j.endObject();
        }
        j.key("grid_layout");
        j.beginObject();
        j.field("combined_build_cpu_ms", vr->combinedBuildMs);
        j.field("per_eye_build_cpu_ms", vr->perEyeBuildMs);
        if (!o.noPerPixel) {
            const PerPixel& a = vr->perPixel[0];
            const PerPixel& b = vr->perPixel[1];
            const double pixels = double(a.pixels + b.pixels);
            auto mean = [&](double PerPixel::*field) {
                return pixels > 0.0 ? (a.*field * double(a.pixels) + b.*field * double(b.pixels)) / pixels : std::nan("");
            };
            j.field("pixels", a.pixels + b.pixels);
            j.field("exact_mean", mean(&PerPixel::exactMean));
            j.field("combined_listed_mean", mean(&PerPixel::listedMean));
            j.field("per_eye_listed_mean", mean(&PerPixel::otherListedMean));
            j.field("combined_pixels_listed_below_exact", a.listedBelowExact + b.listedBelowExact);
        }
        j.endObject();
        j.endObject();
    }

    // Animation: the deformation and curvature passes against the whole frame, for an animated
    // scene at its animation's middle (posed once: both passes run every frame whatever the pose),
    // and the GPU curvature pass against recomputing curvature on the CPU (updateMeshCurvature of
    // the CPU-deformed meshes, what a renderer without the pass would do per frame).
    struct AnimationRun {
        Measurement frame;
        double cpuCurvatureMs = 0.0;
        uint64_t deformedVertices = 0;
    };
    std::optional<AnimationRun> animation;
    if (!o.noAnimation) {
        const std::filesystem::path animatedPath = !o.animatedScene.empty() ? std::filesystem::path(o.animatedScene)
                                                   : !scene.animations.empty() ? scenePath
                                                                               : defaultAnimatedScenePath();
        const Scene animated = animatedPath == scenePath ? scene : loadScene(animatedPath, common);
        if (animated.animations.empty()) {
            fmt::print(stderr, "preskin bench: {} has no animation; skipping animation\n", animatedPath.string());
        } else {
            const Animation& clip = animated.animations.front();
            const float timeS = 0.5f * (clip.startS() + clip.endS());
            const ScenePose pose = posedScene(animated, animationNodePose(animated, clip, timeS));
            const View animatedView = frameBoundsView(animated.worldBounds(), float(o.width) / float(o.height));
            CommonOptions withLights = common;
            withLights.lights = o.vrLights;
            withLights.seed = o.seed;
            Renderer animatedRenderer(*context, animated, environment, &luts, base);
            animatedRenderer.setPose(pose);
            Bench animatedBench(o, *context, animatedView);
            AnimationRun run;
            run.frame = std::move(animatedBench.measure(
                {{&animatedRenderer, base,
                  fmt::format("{} lights, animated ({} at {:.2f} s)", o.vrLights, clip.name, timeS), 0.0}},
                sceneLights(animated, withLights))[0]);
            // The CPU recompute over the same deformed meshes, interleaved repetitions.
            std::vector<Mesh> deformed;
            for (size_t i = 0; i < animated.instances.size(); ++i) {
                const MeshInstance& instance = animated.instances[i];
                Mesh mesh = animated.meshes[size_t(instance.mesh)];
                bool morphs = false;
                for (const Primitive& p : mesh.primitives) morphs = morphs || !p.targets.empty();
                if (instance.skin < 0 && !morphs) continue;
                for (Primitive& p : mesh.primitives) {
                    std::vector<Vertex> out;
                    deformPrimitive(p, pose.instances[i], out);
                    p.vertices = std::move(out);
                    run.deformedVertices += p.vertices.size();
                }
                deformed.push_back(std::move(mesh));
            }
            std::vector<double> cpuMs;
            for (uint32_t r = 0; r < std::max<uint32_t>(o.reps, 1) + 1; ++r) {
                const auto t0 = Clock::now();
                for (Mesh& mesh : deformed) updateMeshCurvature(mesh);
                if (r > 0) cpuMs.push_back(secondsSince(t0) * 1000.0);  // the first is a warm-up
            }
            run.cpuCurvatureMs = median(cpuMs);
            fmt::print(stderr, "preskin bench:   curvature on the CPU: {:.2f} ms median\n", run.cpuCurvatureMs);
            animation = std::move(run);

            j.key("animation");
            j.beginObject();
            j.field("scene", reportedPath(animatedPath));
            j.field("animation", clip.name);
            j.field("time_s", timeS);
            j.field("lights", o.vrLights);
            j.field("deformed_vertices", animation->deformedVertices);
            j.key("frame");
            writeMeasurement(j, animation->frame);
            const double deformMs = animation->frame.passMs("deform");
            const double curvatureMs = animation->frame.passMs("curvature");
            j.field("deform_gpu_ms", deformMs);
            j.field("curvature_gpu_ms", curvatureMs);
            j.field("deform_and_curvature_share_gpu", (deformMs + curvatureMs) / animation->frame.gpuMs());
            j.field("deform_and_curvature_share_wall", (deformMs + curvatureMs) / animation->frame.wallMs());
            j.field("curvature_cpu_ms", animation->cpuCurvatureMs);
            j.field("curvature_cpu_over_gpu", animation->cpuCurvatureMs / curvatureMs);
            j.endObject();
        }
    }

    // Diffusion profiles: one bake, loading 64 cached profiles, and a frame of 8 copies of the
    // scene side by side with one profile against 8 profiles (docs/profiles.md).
    std::optional<ProfileFigures> profileFigures;
    if (!o.noProfiles) {
        profileFigures = measureProfiles(o, bench, *context, scene, environment, luts, base);
        const ProfileFigures& f = *profileFigures;
        j.key("profiles");
        j.beginObject();
        j.field("bake_one_ms", f.bakeOneMs);
        j.field("bake_size", o.profileLutSize);
        j.field("cached_profiles", f.cachedCount);
        j.field("load_cached_ms", f.loadCachedMs);
        j.field("bake_all_ms", f.bakeAllMs);
        j.field("frame_copies", f.copies);
        j.key("frame_one_profile");
        writeMeasurement(j, f.single);
        j.key("frame_eight_profiles");
        writeMeasurement(j, f.eight);
        j.endObject();
    }

    // Goals (docs/clustering.md), on this run's figures.
    j.key("goals");
    j.beginArray();
    auto goal = [&](const std::string& name, double measured, double target, bool atMost) {
        j.beginObject();
        j.field("goal", name);
        j.field("target", target);
        j.field("measured", measured);
        j.field("holds", std::isfinite(measured) && (atMost ? measured <= target : measured >= target));
        j.endObject();
    };
    for (const Row& row : rows) {
        if (row.brute && (row.lights == 256 || row.lights == 1024))
            goal(fmt::format("clustered speedup over brute force at {} lights >= {}", row.lights,
                             row.lights == 256 ? 16 : 30),
                 row.brute->wallMs() / row.clustered.wallMs(), row.lights == 256 ? 16.0 : 30.0, false);
    }
    for (const Row& row : rows)
        if (row.perPixel && row.perPixel->exactMean > 0.0)
            goal(fmt::format("lights listed per pixel / exact at {} lights <= 1.5", row.lights),
                 row.perPixel->listedMean / row.perPixel->exactMean, 1.5, true);
    for (const Row& row : rows)
        if (row.lights == 1024)
            goal("cluster build share of the frame at 1024 lights <= 0.10", row.clustered.buildMs() / row.clustered.wallMs(),
                 0.10, true);
    // Skin against standard: <= 1.3 on a software device (wall time: lavapipe shades on the same
    // cores the host runs on), <= 1.10 on a GPU (its timestamps, the frame's GPU time).
    const bool software = context->isSoftwareDevice();
    for (const SkinRow& row : skinRows)
        goal(fmt::format("skin frame / standard frame at {} lights <= {} ({})", row.lights, software ? "1.3" : "1.10",
                         software ? "wall time" : "GPU timestamps"),
             software ? row.skin.wallMs() / row.standard.wallMs() : row.skin.gpuMs() / row.standard.gpuMs(),
             software ? 1.3 : 1.10, true);
    if (vr) {
        goal("stereo frame / (left mono + right mono frames) <= 0.85",
             vr->stereo.wallMs() / (vr->left.wallMs() + vr->right.wallMs()), 0.85, true);
        goal("light-grid build stereo / mono <= 1.3", vr->stereo.buildMs() / vr->left.buildMs(), 1.3, true);
        goal("CPU recording stereo / mono <= 1.1", vr->recordStereo.recordCpuMs() / vr->recordMono.recordCpuMs(), 1.1,
             true);
        if (vr->msaa1) goal("MSAA 4x frame / 1x frame <= 1.6", vr->msaa4->wallMs() / vr->msaa1->wallMs(), 1.6, true);
    }
    if (animation) {
        const double passesMs = animation->frame.passMs("deform") + animation->frame.passMs("curvature");
        goal("deformation + curvature recompute / animated frame <= 0.10", passesMs / animation->frame.gpuMs(), 0.10,
             true);
        goal("CPU curvature recompute / GPU curvature pass >= 10",
             animation->cpuCurvatureMs / animation->frame.passMs("curvature"), 10.0, false);
    }
    if (profileFigures) {
        const ProfileFigures& f = *profileFigures;
        goal("frame with 8 profiles in view / one profile <= 1.03", f.eight.wallMs() / f.single.wallMs(), 1.03, true);
        goal("loading 64 cached profiles <= 100 ms", f.loadCachedMs, 100.0, true);
        goal("baking one profile <= 100 ms", f.bakeOneMs, 100.0, true);
    }
    j.endArray();
    j.field("elapsed_s", secondsSince(started));
    j.endObject();

    const std::string json = j.text() + "\n";
    if (o.out.empty()) std::fwrite(json.data(), 1, json.size(), stdout);
    else writeTextFile(o.out, json);

    if (!o.out.empty()) fmt::print(stderr, "preskin bench: wrote {}\n", o.out);
}

}  // namespace

void addBenchCommand(CLI::App& app) {
    auto o = std::make_shared<BenchOptions>();
    CLI::App* cmd = app.add_subcommand(
        "bench", "Measure clustered vs brute-force lighting, the light grid, skin vs standard and the LUT bake (JSON)");
    cmd->add_option("scene", o->scene, "glTF scene; default: the bundled head scene");
    cmd->add_option("--out,-o", o->out, "Write the JSON here instead of stdout");
    cmd->add_option("--width", o->width, "Image width in pixels")->capture_default_str()->check(wholeNumberIn(1, 16384));
    cmd->add_option("--height", o->height, "Image height in pixels")->capture_default_str()->check(wholeNumberIn(1, 16384));
    cmd->add_option("--counts", o->counts, "Scattered light counts, comma-separated")->capture_default_str();
    cmd->add_option("--skin-counts", o->skinCounts, "Light counts for skin vs standard material")->capture_default_str();
    cmd->add_option("--seed", o->seed, "Seed of the scattered lights")->capture_default_str()->check(wholeNumberIn(0, UINT32_MAX));
    cmd->add_option("--warmup", o->warmup, "Warm-up frames per point")->capture_default_str()->check(wholeNumberIn(0, 100));
    cmd->add_option("--reps", o->reps, "Measured frames per point (median)")->capture_default_str()->check(wholeNumberIn(1, 1000));
    cmd->add_option("--budget-s", o->budgetS, "Seconds per point before warm-up and repetitions are cut (at least one frame)")
        ->capture_default_str()
        ->check(numberIn(0.0, 1e6));
    cmd->add_option("--tile", o->clusters.tileSizePx, "Cluster tile size in pixels")->capture_default_str()->check(wholeNumberIn(4, 256));
    cmd->add_option("--slices", o->clusters.depthSlices, "Cluster depth slices")->capture_default_str()->check(wholeNumberIn(2, 256));
    cmd->add_option("--near-slice", o->clusters.nearSliceM, "Depth where the first slice ends at the earliest (m)")
        ->capture_default_str()
        ->check(numberIn(0.0, 1e6));
    cmd->add_option("--max-per-cluster", o->clusters.maxLightsPerCluster, "Lights kept per cluster")
        ->capture_default_str()
        ->check(wholeNumberIn(1, 1 << 20));
    cmd->add_option("--build", o->build, "Light-list build: auto, cpu or gpu (compute pass)")
        ->check(oneOf({"auto", "cpu", "gpu"}))
        ->capture_default_str();
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
    cmd->add_flag("--no-profiles", o->noProfiles,
                  "Skip the diffusion-profile figures (one bake, 64 cached profiles, 8 profiles in view)");
    cmd->add_option("--profile-lut-size", o->profileLutSize, "Table size of the profiles baked for the profile figures")
        ->capture_default_str()
        ->check(wholeNumberIn(LutBakeSettings::kMinSize, LutBakeSettings::kMaxSize));
    cmd->add_option("--animated-scene", o->animatedScene,
                    "Animated glTF scene for the animation figures; default: the bench scene when it is animated, "
                    "else the bundled animated head");
    cmd->add_option("--vr-width", o->vrWidth, "Stereo: width per eye")->capture_default_str()->check(wholeNumberIn(1, 16384));
    cmd->add_option("--vr-height", o->vrHeight, "Stereo: height per eye")->capture_default_str()->check(wholeNumberIn(1, 16384));
    cmd->add_option("--vr-lights", o->vrLights, "Stereo and MSAA: scattered lights")
        ->capture_default_str()
        ->check(wholeNumberIn(0, 1 << 20));
    cmd->add_option("--ipd", o->ipdM, "Stereo: interpupillary distance, metres")->capture_default_str()->check(numberIn(0.0, 1.0));
    cmd->add_option("--device", o->device, "Vulkan device: index or part of its name (default: best GPU, else lavapipe)");
    cmd->add_flag("--validation", o->validation, "Enable Vulkan validation layers; any message makes the run fail");
    cmd->callback([o] { run(*o); });
}

}  // namespace preskin::cli
