// Per-channel prefiltered geometric normals for skin.
//
// Light leaving skin at x entered it at every y within the profile's reach, so the diffuse light
// of each colour channel sees the surface's normals averaged by that channel's profile:
// n_c(x) = int Rn_c(|x - y|) n(y) dA(y), red averaged widest. Where the irradiance is linear in
// the normal (the neighbourhood faces the light) this average is exact, whatever the shape; the
// diffuse LUT then supplies what the osculating sphere adds at the terminator. It removes the
// triangle-scale normal variation of scanned meshes that the profile smooths away, and turns the
// walls of creases towards each other as the light crossing them does.
//
// Split in two so that profiles can change without touching the mesh:
//  - geometry: per vertex, the mesh's normals averaged with kNormalBasisCount normalised 2D
//    Gaussians of kNormalBasisSigmaMm (straight-line distances, as every LUT and the reference
//    assume; neighbours whose normals face more than 90 degrees away, the far side of a thin
//    part, are left to transmission), M_b(x) = n(x) + int G_b(|x - y|) (n(y) - n(x)) dA(y): where
//    the surface ends or turns away, the vertex normal stands for what is missing;
//  - profile: per channel, weights a_b >= 0 (sum <= 1) of the basis that best stand for the
//    profile's radial energy (its transmittance curve, matched on a log scale of radii from
//    0.05 to 20 mm); the rest, 1 - sum a_b, is the profile's part narrower than the basis, for
//    which the vertex normal itself stands.
// The shader combines them: n_c = normalize((1 - sum_b a_cb) n + sum_b a_cb M_b).
//
// The neighbours the basis leaves out, those facing more than 90 degrees away (the other side of
// a thin part, the lip across the lips' line, a fold's far wall), are kept apart: per vertex and
// Gaussian O_b(x) = int_opp c G_b(|x - y|) n(y) dA(y) (c fades them in from the 90-degree cut,
// full from 96 degrees on: min(-10 n(y) . n(x), 1)), and their centroid. Lit, they send light into x
// across the gap or through the tissue; skin shading takes it as sum_b a_cb max(O_b . L, 0) times
// the light's visibility at the centroid (preskin/skin.glsl, preskinSkinOpposingLight). For a
// sheet of thickness d facing x, |O_b| = exp(-d^2 / (2 sigma_b^2)): the basis's plane integral,
// so sum_b a_cb |O_b| is the profile's transmittance through the sheet.
//
// Limits: the basis is fixed in world millimetres (the material's scatter scale moves the profile
// onto it): profiles wider than about 8 mm or narrower than 0.5 mm are only partly resolved (the
// narrow part is the vertex normal, which is exact there for smooth meshes); the geometry is
// integrated at the rest pose and applied to the normals of the current pose (the weights follow
// the surface, not a changed distance between its points).
#pragma once

#include <preskin/DiffusionProfile.h>
#include <preskin/Export.h>
#include <preskin/Glm.h>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace preskin {

inline constexpr int kNormalBasisCount = 4;
inline constexpr std::array<double, kNormalBasisCount> kNormalBasisSigmaMm = {0.5, 1.0, 2.0, 4.0};

// One vertex's neighbourhood as skin sees it (read by the GPU as kNormalBasisFloats floats).
struct NormalBasis {
    std::array<glm::vec3, kNormalBasisCount> averaged{};  // M_0 .. M_3
    std::array<glm::vec3, kNormalBasisCount> opposing{};  // O_0 .. O_3 (zero where no neighbour faces away)
    glm::vec3 opposingCentroid{0.0f};  // the opposing neighbours' centroid, from the vertex (units of the positions)
};

// The basis normals and opposing neighbours of every vertex of a triangle mesh. `normals`: per-vertex unit normals;
// `mmPerUnit`: millimetres per unit of `positions` (1000 for metres). Vertices duplicated along
// seams are welded by position and normal hemisphere, as for curvature. Throws preskin::Error
// when the counts disagree, an index is out of range or mmPerUnit is not a positive finite number.
PRESKIN_API std::vector<NormalBasis> computeNormalBasis(std::span<const glm::vec3> positions,
                                                        std::span<const glm::vec3> normals,
                                                        std::span<const uint32_t> indices, double mmPerUnit);

// Per channel (red, green, blue) the basis weights a_0 .. a_3 standing for `profile` at
// `scatterScale` (profile millimetres per world millimetre, SkinMaterial::scatterScale).
PRESKIN_API std::array<glm::vec4, 3> normalBasisWeights(const DiffusionProfile& profile, double scatterScale);

}  // namespace preskin
