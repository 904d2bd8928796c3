// ProfileLibrary: a scene's diffusion profiles as LUT sets (see <preskin/ProfileLibrary.h>):
// LUT folders loaded, analytic profiles read from the on-disk cache or baked in parallel.
#include <preskin/Error.h>
#include <preskin/Limits.h>
#include <preskin/ProfileLibrary.h>

#include "skin/ProfileJson.h"

#include <fmt/core.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <cstdlib>
#include <mutex>
#include <optional>

namespace preskin {

namespace fs = std::filesystem;

namespace {

// Bumped whenever baking changes its results for the same profile and settings.
constexpr const char* kCacheKeyVersion = "preskin-lut-cache-1";

uint64_t fnv1a64(const std::string& text) {
    uint64_t hash = 14695981039346656037ull;
    for (unsigned char c : text) {
        hash ^= c;
        hash *= 1099511628211ull;
    }
    return hash;
}

// The cache's entry answers for `profile` baked with `settings` only when both match exactly
// (a hash collision or a hand-edited entry must not pass for it).
bool entryMatches(const LutSet& set, const DiffusionProfile& profile, const LutBakeSettings& settings) {
    return set.settings() == settings && skin::profileToJson(set.profile()) == skin::profileToJson(profile);
}

}  // namespace

fs::path ProfileCacheOptions::resolvedFolder() const {
    if (!enabled) return {};
    if (!folder.empty()) return folder;
    // XDG Base Directory: only an absolute XDG_CACHE_HOME counts.
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg && fs::path(xdg).is_absolute())
        return fs::path(xdg) / "preskin" / "luts";
    if (const char* home = std::getenv("HOME"); home && *home) return fs::path(home) / ".cache" / "preskin" / "luts";
    return {};
}

fs::path profileCacheEntry(const fs::path& cacheFolder, const DiffusionProfile& profile,
                           const LutBakeSettings& settings) {
    const std::string key = fmt::format(
        "{}\n{}\n{} {} {} {} {} {} {:.17g}", kCacheKeyVersion, skin::profileToJson(profile).dump(),
        settings.diffuseNoLSize, settings.diffuseCurvatureSize, settings.penumbraShadowSize, settings.penumbraWidthSize,
        settings.shCurvatureSize, settings.transmittanceSize, settings.curvatureMaxPerMm);
    return cacheFolder / fmt::format("{:016x}", fnv1a64(key));
}

ProfileLibrary::ProfileLibrary(std::shared_ptr<const LutSet> defaultLuts) {
    if (!defaultLuts) throw Error("ProfileLibrary: the default LUT set is missing");
    layers_.push_back(std::move(defaultLuts));
}

void ProfileLibrary::setLayer(size_t index, std::shared_ptr<const LutSet> luts) {
    if (index >= layers_.size() || !luts)
        throw Error(
            fmt::format("ProfileLibrary: layer {} is out of range (the library has {})", index, layers_.size()));
    layers_[index] = std::move(luts);
}

ProfileLibrary ProfileLibrary::forScene(const Scene& scene, std::shared_ptr<const LutSet> defaultLuts,
                                        const LutBakeSettings& settings, const ProfileCacheOptions& cache) {
    const auto start = std::chrono::steady_clock::now();
    settings.validate();
    ProfileLibrary library(std::move(defaultLuts));
    const size_t count = scene.profiles.size();
    const std::string source = scene.sourcePath.empty() ? std::string("scene") : scene.sourcePath.string();
    if (count > limits::kMaxSkinProfiles) {
        throw Error(
            fmt::format("{}: profiles: {} profiles exceed the limit of {}", source, count, limits::kMaxSkinProfiles));
    }
    for (size_t i = 0; i < count; ++i) {
        const SkinProfile& p = scene.profiles[i];
        if (p.profile.has_value() == !p.lutFolder.empty())
            throw Error(fmt::format("{}: profiles[{}]: needs either an analytic profile or a LUT folder", source, i));
    }
    const fs::path cacheFolder = cache.resolvedFolder();

    std::vector<std::shared_ptr<const LutSet>> sets(count);
    std::vector<std::optional<Error>> errors(count);
    std::vector<std::string> warnings(count);
    std::vector<char> hit(count, 0), damaged(count, 0), toSave(count, 0);
    tbb::parallel_for(size_t(0), count, [&](size_t i) {
        const SkinProfile& p = scene.profiles[i];
        try {
            if (!p.lutFolder.empty()) {
                sets[i] = std::make_shared<const LutSet>(LutSet::load(p.lutFolder));
                return;
            }
            if (!cacheFolder.empty()) {
                const fs::path entry = profileCacheEntry(cacheFolder, *p.profile, settings);
                std::error_code ec;
                if (fs::exists(entry / "manifest.json", ec)) {
                    try {
                        LutSet set = LutSet::load(entry);
                        if (!entryMatches(set, *p.profile, settings))
                            throw Error(
                                fmt::format("{}: holds another profile or other bake settings", entry.string()));
                        sets[i] = std::make_shared<const LutSet>(std::move(set));
                        hit[i] = 1;
                        return;
                    } catch (const Error& e) {
                        damaged[i] = 1;
                        warnings[i] =
                            fmt::format("profile '{}': damaged cache entry ({}); baked again", p.name, e.what());
                    }
                }
                toSave[i] = 1;
            }
            sets[i] = std::make_shared<const LutSet>(LutSet::bake(*p.profile, settings));
        } catch (const Error& e) {
            errors[i] = e;
        }
    });
    for (size_t i = 0; i < count; ++i) {
        if (errors[i]) throw *errors[i];
    }
    // Writing the cache is serial: a folder that refuses one entry refuses them all, and is
    // reported once.
    bool cacheWritable = true;
    for (size_t i = 0; i < count; ++i) {
        if (!warnings[i].empty()) library.warnings_.push_back(warnings[i]);
        if (!toSave[i] || !cacheWritable) continue;
        try {
            sets[i]->save(profileCacheEntry(cacheFolder, *scene.profiles[i].profile, settings), {.rawTables = true});
        } catch (const Error& e) {
            cacheWritable = false;
            library.warnings_.push_back(
                fmt::format("{}: the profile cache cannot be written ({}); profiles are baked without caching",
                            cacheFolder.string(), e.what()));
        }
    }
    for (size_t i = 0; i < count; ++i) {
        library.layers_.push_back(std::move(sets[i]));
        const SkinProfile& p = scene.profiles[i];
        if (!p.lutFolder.empty())
            ++library.stats_.lutFolders;
        else if (hit[i])
            ++library.stats_.cacheHits;
        else
            ++library.stats_.baked;
        library.stats_.damaged += damaged[i];
    }
    library.stats_.wallMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return library;
}

}  // namespace preskin
