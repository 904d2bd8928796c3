// Penner & Borshukov's pre-integrated diffuse ring integral ("Pre-Integrated Skin Shading",
// GPU Pro 2, 2011) and the SH transfer coefficients built from it.
//
// On a ring (the cross-section of a cylinder of radius r = 1/curvature lit across its axis),
//   D(theta, r) = int cos(theta + x)+ K(x) dx / int K(x) dx,  x in [-pi, pi],
//   K(x) = P(2 r sin(|x| / 2)),
// with P the profile integrated along the cylinder axis (DiffusionProfile::lineProfile) and the
// chord 2 r sin(x/2) as distance. Integrating the radial profile R over the cylinder's surface
// gives exactly this P; for Gaussians it is the 1D-normalised Gaussian of Penner's published
// code, and it keeps Burley's 1/r profile integrable (R itself, used directly on the ring,
// diverges logarithmically and would reduce D to saturate(NoL)).
//
// Method: D = (cos(theta) I_c - sin(theta) I_s) / Z over the lit arc, where I_c, I_s, Z are
// integrals of K cos x, K sin x, K. They are accumulated once per curvature on [0, pi] with
// 8-point Gauss-Legendre on intervals whose breakpoints include every lit-arc endpoint
// (asin(NoL) and pi - asin(NoL), so the kinks of cos+ are never inside an interval) and a mesh
// graded geometrically (ratio 1.25) from 1e-7 of the kernel's narrowest scale, so narrow peaks
// and Burley's log singularity are resolved. Zero curvature returns the exact flat limit
// saturate(NoL).
//
// SH transfer: A_l(r) = 2 pi int D(theta, r) P_l(cos theta) sin theta dtheta, l = 0, 1, 2, by
// 16-point Gauss-Legendre on [-1, 1] in cos(theta), graded towards 0 (breaks at 0, +-1/256,
// +-1/64, +-1/16, +-1/4), exact for the flat limit (pi, 2 pi / 3, pi / 4).
//
// Limits: the ring/cylinder model of Penner (no sphere, no self-shadowing, lighting across the
// axis only); D carries the profile's shape only (it is normalised by Z; albedo comes from the
// material).
#pragma once

#include <preskin/DiffusionProfile.h>

#include <glm/glm.hpp>

#include <array>
#include <span>

namespace preskin::skin {

// D for each NoL (clamped to [-1, 1]) at one curvature (1/mm, >= 0).
void ringScatter(const DiffusionProfile& profile, double curvaturePerMm, std::span<const double> NoL,
                 std::span<glm::dvec3> out);
glm::dvec3 ringScatter(const DiffusionProfile& profile, double curvaturePerMm, double NoL);

// A_0, A_1, A_2 per channel at one curvature (absolute: flat skin gives pi, 2 pi / 3, pi / 4).
std::array<glm::dvec3, 3> shTransfer(const DiffusionProfile& profile, double curvaturePerMm);

// Lambert's zonal coefficients (pi, 2 pi / 3, pi / 4).
inline constexpr std::array<double, 3> kLambertZonal{3.14159265358979323846, 2.0 * 3.14159265358979323846 / 3.0,
                                                     3.14159265358979323846 / 4.0};

}  // namespace preskin::skin
