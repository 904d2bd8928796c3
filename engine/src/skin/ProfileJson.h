// Reading and writing DiffusionProfile as JSON (format: DiffusionProfile::toJson). Reading
// validates every field and reports the first problem as "<source>: <prefix><field>: <problem>",
// so a profile embedded in a LUT manifest is reported as "manifest.json: profile.gaussians[0]...".
// Limits: at most 64 Gaussian terms; variances in [1e-6, 1e4] mm^2 (a Gaussian 1 um to 100 mm
// wide); mean free paths in [1e-3, 1e3] mm. The lower bounds are physical (no tissue scatters
// light over less than a micrometre) and keep every bake finite.
#pragma once

#include <preskin/DiffusionProfile.h>

#include <nlohmann/json.hpp>

#include <string_view>

namespace preskin::skin {

inline constexpr int kMaxGaussianTerms = 64;
inline constexpr double kMinVarianceMm2 = 1e-6;
inline constexpr double kMaxVarianceMm2 = 1e4;
inline constexpr double kMinMeanFreePathMm = 1e-3;
inline constexpr double kMaxMeanFreePathMm = 1e3;

DiffusionProfile parseProfileJson(const nlohmann::json& json, std::string_view source, std::string_view fieldPrefix);
nlohmann::ordered_json profileToJson(const DiffusionProfile& profile);

}  // namespace preskin::skin
