// SkinProfile: one diffusion profile a scene names (the root PRESKIN_materials_skin extension's
// "profiles", docs/gltf-extensions.md, or a host's Scene::profiles). Either an analytic
// DiffusionProfile, baked into a LutSet when the scene's profiles are prepared
// (ProfileLibrary), or a LUT set baked earlier (a folder written by LutSet::save / `preskin
// bake`), loaded as it is. Skin materials name a profile by its index (SkinMaterial::profile);
// materials that name none use the renderer's default set (the bundled d'Eon & Luebke skin).
#pragma once

#include <preskin/DiffusionProfile.h>

#include <filesystem>
#include <optional>
#include <string>

namespace preskin {

struct SkinProfile {
    std::string name;
    std::optional<DiffusionProfile> profile;  // analytic: baked with the library's settings
    std::filesystem::path lutFolder;          // otherwise: a baked LUT set (absolute path)
};

}  // namespace preskin
