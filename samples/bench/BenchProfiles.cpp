// `preskin bench`, LUTs and profiles: the default set's bake, one profile's bake at the profile
// size, 64 profiles baked into a fresh cache and loaded from it again, and a frame of 8 copies of
// the scene side by side whose skin materials use one profile against one profile per copy.
#include "BenchSections.h"

#include <preskin/DiffusionProfile.h>
#include <preskin/Environment.h>
#include <preskin/Error.h>
#include <preskin/LutSet.h>
#include <preskin/ProfileLibrary.h>
#include <preskin/Scene.h>
#include <glm/gtc/matrix_transform.hpp>

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace preskin::cli::bench {

namespace {

constexpr int kBakeReps = 5;

struct ProfileFigures {
    double bakeOneMs = 0.0;    // median of kBakeReps bakes
    double bakeFirstMs = 0.0;  // the first of them (cold caches, threads starting)
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
            instance.worldFromObject =
                glm::translate(glm::mat4(1.0f), glm::vec3(offset, 0.0f, 0.0f)) * instance.worldFromObject;
            instance.skin = -1;
            out.instances.push_back(std::move(instance));
        }
    }
    return out;
}

ProfileFigures measureProfiles(const BenchOptions& o, Bench& bench, Context& context, const Scene& scene,
                               const Environment& environment, const LutSet& luts, const RenderSettings& base) {
    ProfileFigures f;
    fmt::print(stderr, "preskin bench: baking one profile {} times...", kBakeReps);
    std::fflush(stderr);
    const LutBakeSettings settings = LutBakeSettings::withSize(o.profileLutSize);
    std::vector<double> bakes;
    for (int rep = 0; rep < kBakeReps; ++rep) {
        const auto bakeStart = Clock::now();
        (void)LutSet::bake(DiffusionProfile::burley({0.85, 0.55, 0.45}, {1.5, 0.6, 0.35}), settings);
        bakes.push_back(secondsSince(bakeStart) * 1000.0);
    }
    f.bakeFirstMs = bakes.front();
    f.bakeOneMs = median(bakes);
    fmt::print(stderr, " median {:.0f} ms (first {:.0f} ms)\n", f.bakeOneMs, f.bakeFirstMs);

    Scene many;
    for (int i = 0; i < f.cachedCount; ++i)
        many.profiles.push_back(
            {fmt::format("p{}", i),
             DiffusionProfile::burley({0.5 + 0.5 * i / (f.cachedCount - 1.0), 0.55, 0.45}, {1.0 + 0.05 * i, 0.6, 0.35}),
             {}});
    char pattern[] = "/tmp/preskin-bench-cache-XXXXXX";
    if (!mkdtemp(pattern)) throw Error("preskin bench: cannot create a temporary cache folder");
    const std::filesystem::path cacheFolder = pattern;
    const auto shared = std::make_shared<const LutSet>(luts);
    try {
        fmt::print(stderr, "preskin bench: baking {} profiles into a fresh cache...", f.cachedCount);
        std::fflush(stderr);
        const auto start = Clock::now();
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
    std::vector<Measurement> measured = bench.measure(
        {{&oneRenderer, base, fmt::format("{} copies, one profile", f.copies), 0.0, &view, o.width, o.height},
         {&eightRenderer, base, fmt::format("{} copies, {} profiles", f.copies, f.copies), 0.0, &view, o.width,
          o.height}},
        sceneLights(one, CommonOptions{}));
    f.single = std::move(measured[0]);
    f.eight = std::move(measured[1]);
    return f;
}

}  // namespace

void BenchRun::lutBakeSection() {
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

// Diffusion profiles: one bake, loading 64 cached profiles, and a frame of 8 copies of the scene
// side by side with one profile against 8 profiles (docs/profiles.md).
void BenchRun::profilesSection() {
    const ProfileFigures f = measureProfiles(o, bench, context, scene, environment, luts, base);
    j.key("profiles");
    j.beginObject();
    j.field("bake_one_ms", f.bakeOneMs);
    j.field("bake_one_first_ms", f.bakeFirstMs);
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
    goal("frame with 8 profiles in view / one profile <= 1.03", f.eight.wallMs() / f.single.wallMs(), 1.03, true);
    goal("loading 64 cached profiles <= 100 ms", f.loadCachedMs, 100.0, true);
    goal("baking one profile <= 100 ms", f.bakeOneMs, 100.0, true);
    goal("baking 64 new profiles <= 8 s", f.bakeAllMs / 1000.0, 8.0, true);
}

}  // namespace preskin::cli::bench
