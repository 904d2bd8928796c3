// The pre-integrated diffuse response on a sphere, and the SH transfer built from it: the
// three-dimensional form of Penner & Borshukov's ring integral ("Pre-Integrated Skin Shading",
// GPU Pro 2, 2011), integrating the profile over the osculating sphere of the mean curvature
// instead of over a ring (a cylinder's cross-section). On a sphere the surface curves away in
// both directions, so the lit side's peak is spread twice as much as on the ring of the same
// radius, which is what the diffusion integral over a real sphere gives (docs/reference.md).
//
// Convex skin (curvature k > 0), a sphere of radius a = 1/k seen from outside: a point whose
// normal makes the angle theta with L receives
//   D(theta) = int_S Rn(|x - y|) max(n_y . L, 0) dA(y) / int_S Rn dA
//            = int W(psi) Phi(cos(theta) cos(psi), sin(theta) sin(psi)) dpsi / (2 pi int W dpsi),
//   W(psi) = a^2 Rn(2 a sin(psi / 2)) sin(psi),
// psi the angle between x and y and Phi(A, B) = int_0^2pi max(A + B cos(phi), 0) dphi in closed
// form (2 pi A if A >= B, 0 if A <= -B, else 2 (A phi0 + B sin(phi0)), phi0 = acos(-A / B)).
// On a convex surface max(n_y . L, 0) is the exact visibility: nothing else of the sphere can
// shadow a point that faces the light.
//
// Concave skin (k < 0), the inside of a sphere of radius a = 1/|k|, which shadows itself: the
// local patch, the cap of arc radius rho (LutSet::localPatchMm) around x, is the occluder. Light
// towards a neighbour y that faces it crosses the cavity and leaves the sphere at
// y' = y - 2 (y . L) L (centre at the origin); it is blocked when y' lies on the patch. With
// u = n_y . L that is 2 u cos(theta) <= cos(psi) - cos(Psi), Psi = rho / a, a bound on u, so the
// azimuthal integral keeps its closed form between thresholds:
//   Phi_tau(A, B, tau) = int_0^2pi (A + B cos(phi)) [A + B cos(phi) > tau] dphi,
//   visible u in (max(0, (cos(psi) - cos(Psi)) / (2 cos(theta))), inf) for cos(theta) > 0,
//   and in (0, (cos(Psi) - cos(psi)) / (2 |cos(theta)|)) for cos(theta) < 0 (only neighbours
//   beyond the patch). So a concave patch darkens under grazing light (its rim shadows it) and
// gets far less light past its terminator than a convex one, whose neighbours all see the light.
// Without the patch (rho -> 0) the two are the same integral. Shadows from beyond the patch are
// the shadow map's (skin looks it up above the patch).
//
// Both integrate over the sphere out to the profile's reach and are normalised by the profile's
// integral over the same surface, so k -> 0 gives exactly
// saturate(NoL). The SH transfer is exact on the convex sphere by the Funk-Hecke theorem:
// A_l = Lambert_l g_l / g_0 with g_l = 2 pi int W(psi) P_l(cos(psi)) dpsi, the Legendre
// coefficients of the profile on the sphere; it is used for both signs of curvature (the ambient
// light is unshadowed, as in the renderer).
//
// Method: the psi integral runs to the profile's reach (the chord where all but 1e-4 of the
// energy is inside), on 8-point Gauss-Legendre panels graded geometrically
// (ratio 1.5) from 1e-3 of the profile's narrowest scale, then uniform (64 panels); the kernel
// weights are computed once per curvature and shared by every NoL. Against a direct surface
// integration (tests/reference/test_lut_reference.h) the values agree within 1e-4.
// Limits: the mean curvature's sphere stands in for both principal curvatures (exact for a
// sphere; a cylinder of radius r becomes a sphere of radius 2r); the concave patch's extent is a
// model choice (rho), not measured from the mesh.
#pragma once

#include <preskin/DiffusionProfile.h>

#include <glm/glm.hpp>

#include <array>
#include <span>

namespace preskin::skin {

// D for each NoL (clamped to [-1, 1]) at one signed curvature (1/mm); patchMm: the concave
// patch's arc radius (profile mm).
void sphereScatter(const DiffusionProfile& profile, double curvaturePerMm, double patchMm, std::span<const double> NoL,
                   std::span<glm::dvec3> out);
glm::dvec3 sphereScatter(const DiffusionProfile& profile, double curvaturePerMm, double patchMm, double NoL);

// A_0, A_1, A_2 per channel at curvature |curvaturePerMm| (absolute: flat skin gives
// pi, 2 pi / 3, pi / 4).
std::array<glm::dvec3, 3> shTransfer(const DiffusionProfile& profile, double curvaturePerMm);

// Lambert's zonal coefficients (pi, 2 pi / 3, pi / 4).
inline constexpr std::array<double, 3> kLambertZonal{3.14159265358979323846, 2.0 * 3.14159265358979323846 / 3.0,
                                                     3.14159265358979323846 / 4.0};

}  // namespace preskin::skin
