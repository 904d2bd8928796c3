// The picture `preskin compare` writes: the reference, the skin render and the Lambert render
// side by side (tone-mapped with the renderer's Khronos PBR Neutral curve, sRGB), and under them
// the regions (grey flat skin, green convex, blue concave, red near cast-shadow edges) and the
// per-pixel error of skin and of Lambert as heat maps (root mean square over RGB of render minus
// reference; black 0 through blue, magenta and orange to white at the scale printed in the
// title: the 99th percentile of Lambert's error on skin, shared by both maps).
#pragma once

#include "CompareMetrics.h"

#include <preskin/DiffusionReference.h>

#include <filesystem>
#include <string>
#include <vector>

namespace preskin::cli {

void writeComparePicture(const std::filesystem::path& path, const std::string& title, const ReferenceImage& reference,
                         const std::vector<float>& skin, const std::vector<float>& lambert,
                         const std::vector<Region>& regions);

}  // namespace preskin::cli
