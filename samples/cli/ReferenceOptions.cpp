#include "ReferenceOptions.h"
#include "CommandLine.h"  // samples/common
#include "ProgressBar.h"

#include <fmt/core.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <fstream>
#include <optional>

namespace preskin::cli {

void addReferenceOptions(CLI::App& cmd, ReferenceOptions& o) {
    ReferenceSettings& s = o.settings;
    cmd.add_option("--tail-fraction", s.tailFraction,
                   "Reference: profile energy left out beyond the integration radius")
        ->check(numberIn(1e-9, 0.1))
        ->capture_default_str();
    cmd.add_option("--leaf-ratio", s.leafRatio, "Reference: irradiance piece size over its distance from the point")
        ->check(numberIn(1e-3, 2.0))
        ->capture_default_str();
    cmd.add_option("--finest-leaf-ratio", s.finestLeafRatio,
                   "Reference: smallest irradiance piece over the profile's narrowest scale")
        ->check(numberIn(1e-3, 100.0))
        ->capture_default_str();
    cmd.add_option("--moment-tolerance", s.momentTolerance,
                   "Reference: adaptive profile quadrature tolerance per piece")
        ->check(numberIn(1e-12, 1e-2))
        ->capture_default_str();
    cmd.add_option("--trace-environment", s.environmentSamples,
                   "Reference: trace the environment image with this many rays per vertex (importance-sampled, "
                   "occluded by the scene) instead of taking the renderer's L2 SH irradiance")
        ->check(wholeNumberIn(0, 1 << 20))
        ->capture_default_str();
    cmd.add_option("--threads", o.threads, "Reference: CPU threads (0: all cores); the result does not depend on it")
        ->check(wholeNumberIn(0, 1024))
        ->capture_default_str();
}

std::unique_ptr<DiffusionReference> makeReference(const Scene& scene, const Environment& environment,
                                                  const LutSet& luts, const CommonOptions& common,
                                                  const ReferenceOptions& o) {
    ReferenceSettings settings = o.settings;
    settings.shadows = !common.noShadows;
    const std::vector<Light> lights = sceneLights(scene, common);
    // Traced: the environment image itself, occluded by the scene (the truth the renderer's
    // extracted lights and SH ambient stand for).
    if (settings.environmentSamples > 0)
        return std::make_unique<DiffusionReference>(scene, lights, environment, luts.profile(), settings);
    // SH ambient: the renderer's own model of the environment, its extracted lights (the first
    // shadowed when no other light is) and the SH they leave.
    const EnvironmentLights extracted =
        extractEnvironmentLights(environment, uint32_t(environmentLightCount(scene, common)));
    return std::make_unique<DiffusionReference>(scene, withEnvironmentLights(lights, extracted, common.envLightSize),
                                                extracted.residualSh, luts.profile(), settings);
}

namespace {

// FNV-1a (64 bits) of bytes: tells a changed scene file or profile from the one a reference was made of.
uint64_t fnv1a(uint64_t h, const char* bytes, size_t count) {
    for (size_t i = 0; i < count; ++i) h = (h ^ uint8_t(bytes[i])) * 1099511628211ull;
    return h;
}
constexpr uint64_t kFnvOffset = 14695981039346656037ull;

std::string fileHash(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    uint64_t h = kFnvOffset;
    char buffer[1 << 16];
    while (in) {
        in.read(buffer, sizeof buffer);
        h = fnv1a(h, buffer, size_t(in.gcount()));
    }
    return fmt::format("{:016x}", h);
}

}  // namespace

ReferenceKey referenceKey(const std::filesystem::path& scenePath, const Scene& loadedScene, const ViewOptions& view,
                          const CommonOptions& common, const ReferenceOptions& o, const LutSet& luts) {
    const int environmentLights = environmentLightCount(loadedScene, common);
    std::error_code ec;
    const std::filesystem::path scene = std::filesystem::weakly_canonical(scenePath, ec);
    const ReferenceSettings& s = o.settings;
    return {
        {"model", "2"},  // 2: the terminator band
        {"scene", (ec ? scenePath : scene).string()},
        {"sceneHash", fileHash(scenePath)},
        {"size", fmt::format("{}x{}", view.width, view.height)},
        {"view",
         !view.camera.empty()      ? "camera " + view.camera
             : !view.orbit.empty() ? "orbit " + view.orbit
                                   : "default"},
        {"env", common.env.empty() ? "scene" : common.env},
        {"envIntensity", common.envIntensity < 0.0f ? "scene" : fmt::format("{}", common.envIntensity)},
        {"envRotation", common.envRotationDeg ? fmt::format("{}", *common.envRotationDeg) : "scene"},
        {"skin", common.skin.empty() ? "scene" : common.skin},
        {"lights", fmt::format("{} seed {}", common.lights, common.seed)},
        {"exposure", fmt::format("{}", common.exposure)},
        {"shadows", common.noShadows ? "off" : "on"},
        {"profile", luts.profile().name()},
        {"profileHash",
         [&] {
             const std::string json = luts.profile().toJson();
             return fmt::format("{:016x}", fnv1a(kFnvOffset, json.data(), json.size()));
         }()},
        {"quadrature",
         fmt::format("tail {} leaf {} finest {} moments {} edge {} terminator {}", s.tailFraction, s.leafRatio,
                     s.finestLeafRatio, s.momentTolerance, s.shadowEdgeWidths, s.terminatorClearanceMm)},
        // The SH ambient with the environment's lights as the renderer extracts them (none: the
        // SH of the whole environment, as before they were modelled).
        {"ambient",
         s.environmentSamples > 0 ? fmt::format("traced {}", s.environmentSamples)
             : environmentLights > 0
             ? fmt::format("sh less {} environment lights{}", environmentLights, common.envLightSize ? " (sized)" : "")
             : std::string("sh")},
    };
}

ReferenceImage renderReference(const DiffusionReference& reference, const View& view, const ViewOptions& size,
                               float exposure, const ReferenceOptions& o) {
    std::optional<tbb::global_control> threads;
    if (o.threads > 0) threads.emplace(tbb::global_control::max_allowed_parallelism, size_t(o.threads));
    ProgressBar bar("reference");
    return reference.render(view.eye(), size.width, size.height, exposure, [&](double f) { bar(f); });
}

}  // namespace preskin::cli
