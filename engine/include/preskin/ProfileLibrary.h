// ProfileLibrary: the LUT sets of every diffusion profile a scene uses, in the order the
// renderer's LUT arrays hold them: layer 0 is the default set (the bundled skin, or whatever the
// host passes), layer i + 1 is Scene::profiles[i]. A skin material's SkinMaterial::profile p
// reads layer p + 1.
//
// Preparing a scene's profiles: LUT folders are loaded (LutSet::load); analytic profiles are
// looked up in the on-disk cache and baked where missing, all of them at once on every core
// (TBB), then written to the cache. A cache entry is a folder named after a hash of the
// profile's JSON, the bake settings and the LUT file format version; it holds an ordinary LUT
// set (LutSet::save), so a damaged entry fails LutSet::load's content hashes and is baked again
// with a warning. A cache folder that cannot be written gives one warning and the profiles are
// baked without caching.
//
// Limits: every layer of the GPU arrays has the largest size of any layer (smaller LUT sets are
// padded with their edge texels, exact under CLAMP_TO_EDGE); at most limits::kMaxSkinProfiles.
#pragma once

#include <preskin/Export.h>
#include <preskin/LutSet.h>
#include <preskin/Scene.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace preskin {

struct PRESKIN_API ProfileCacheOptions {
    bool enabled = true;
    // Empty: $XDG_CACHE_HOME/preskin/luts, or ~/.cache/preskin/luts (no caching without either).
    std::filesystem::path folder;

    std::filesystem::path resolvedFolder() const;
};

// What preparing the profiles did, for tools and tests.
struct ProfileLoadStats {
    int cacheHits = 0;
    int baked = 0;        // analytic profiles baked (misses and damaged entries)
    int damaged = 0;      // cache entries that failed to load and were baked again
    int lutFolders = 0;   // profiles loaded from LUT folders
    double wallMs = 0.0;  // the whole preparation
};

class PRESKIN_API ProfileLibrary {
public:
    // A library of the default set alone.
    explicit ProfileLibrary(std::shared_ptr<const LutSet> defaultLuts);
    // The default set, then every profile of `scene`. Throws preskin::Error naming the profile
    // (or its LUT folder's file and field) on bad data.
    static ProfileLibrary forScene(const Scene& scene, std::shared_ptr<const LutSet> defaultLuts,
                                   const LutBakeSettings& settings = {}, const ProfileCacheOptions& cache = {});

    size_t layerCount() const { return layers_.size(); }
    const LutSet& layer(size_t index) const { return *layers_.at(index); }
    const std::shared_ptr<const LutSet>& layerPointer(size_t index) const { return layers_.at(index); }
    // Replaces one layer (a re-baked profile); the renderer uploads it with Renderer::setProfileLayer.
    void setLayer(size_t index, std::shared_ptr<const LutSet> luts);

    // Cache problems ("<folder>: ...; baked again"), at most one about an unwritable folder.
    const std::vector<std::string>& warnings() const { return warnings_; }
    const ProfileLoadStats& stats() const { return stats_; }

private:
    std::vector<std::shared_ptr<const LutSet>> layers_;
    std::vector<std::string> warnings_;
    ProfileLoadStats stats_;
};

// The cache folder entry for a profile baked with `settings` (inside `cacheFolder`).
PRESKIN_API std::filesystem::path profileCacheEntry(const std::filesystem::path& cacheFolder,
                                                    const DiffusionProfile& profile, const LutBakeSettings& settings);

}  // namespace preskin
