// Linearly transformed cosines for the GGX lobe (Heitz, Dupuy, Hill & Neubelt, "Real-Time
// Polygonal-Light Shading with Linearly Transformed Cosines", SIGGRAPH 2016): at each (NoV,
// perceptual roughness) of the split-sum table's grid (env/Dfg.h), the matrix M whose transformed
// clamped cosine best matches the cosine-weighted GGX lobe (height-correlated Smith, Fresnel 1)
// normalised to unit integral; the lobe's integral over a polygon is then its directional albedo
// (F0 A + B of the DFG table, with Fresnel) times the clamped cosine's integral over the polygon
// transformed by M^-1. Fitted here, in the lobe's frame (view in the xz plane, normal +z): M =
// R(angle) [[sx, 0, k], [0, sy, 0], [0, 0, 1]], R a turn about +y, the four parameters by
// Nelder-Mead on the L3 distance between the two distributions, sampled on a polar grid around
// the lobe's mean direction, each entry started from its fitted neighbour.
#pragma once

#include <preskin/Glm.h>

#include <cstdint>
#include <vector>

namespace preskin::env {

// M^-1 of one entry divided by its (2, 2) element: (m00, m02, m20, m11) of
// [[m00, 0, m02], [0, m11, 0], [m20, 0, 1]] (row, column), the lobe's frame.
using LtcEntry = glm::vec4;

// The fit at one (NoV, roughness); `start`: the parameters (sx, sy, k, angle) to start from, or
// null for the isotropic guess. `parameters` gets the fitted ones.
LtcEntry fitLtc(float NoV, float roughness, const glm::dvec4* start, glm::dvec4* parameters);

// size x size entries on env/Dfg.h's grid (NoV = i / (size - 1), roughness = j / (size - 1), NoV
// at least 0.02 and roughness at least 0.1 in the fit), row j after row j - 1.
std::vector<LtcEntry> ltcTable(uint32_t size);

// The committed table (engine/src/env/LtcTable.inc, ltcTable(kDfgTableSize) as written by
// `PRESKIN_WRITE_LTC_TABLE=FILE preskin_tests --gtest_filter=Ltc.WriteTable`).
const std::vector<LtcEntry>& defaultLtcTable();

// The normalised clamped cosine's integral (of max(z, 0) / pi) over a polygon (corners relative to
// the shaded point, in the lobe's frame) seen through M^-1 (an LtcEntry): exact, the transformed
// polygon clipped by z = 0. Times the directional albedo: the lobe's integral over the polygon.
double ltcPolygonIntegral(const LtcEntry& minv, const std::vector<glm::dvec3>& corners);

}  // namespace preskin::env
