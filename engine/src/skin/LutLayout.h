// The axes and file names of a LutSet, derived from its profile and bake settings. Baking and
// loading both use these, so a manifest is checked against exactly what a bake would produce.
// Definitions and reasons: engine/include/preskin/LutSet.h.
// Limits: the mappings are fixed per table (LutMapping in shaders/shared/lut_mapping.h encodes
// exactly these); only sizes and the curvature range are settings.
#pragma once

#include <preskin/DiffusionProfile.h>
#include <preskin/LutSet.h>

#include <string_view>

namespace preskin::skin {

inline constexpr double kPenumbraWindowSigmas = 3.0;  // the filter resolves |x| <= 3 sigma
inline constexpr double kTransmittanceFloor = 1e-4;   // the thickness range ends where max T <= this
// The skin's local patch: the surface within this many widths of the profile's widest channel
// (DiffusionProfile::maxWidthMm) of a shaded point. Its self-shadowing belongs to the diffuse
// LUT; the shadow map is looked up above it (skin.glsl, preskinSkinShadowPosition).
inline constexpr double kLocalPatchWidths = 1.0;

struct LutLayout {
    LutTable diffuse;  // name and axes only (rgb empty)
    LutTable penumbra;
    LutTable shTransfer;
    LutTable transmittance;
    double penumbraReferenceWidthMm = 1.0;
};

LutLayout makeLutLayout(const DiffusionProfile& profile, const LutBakeSettings& settings);

// How many of the table's values are NaN or infinite (none may be baked, written or drawn).
size_t nonFiniteValues(const LutTable& table);

// Throws preskin::Error "<source>: <prefix><field>: must be ..., got ...".
void validateBakeSettings(const LutBakeSettings& settings, std::string_view source, std::string_view prefix);

}  // namespace preskin::skin
