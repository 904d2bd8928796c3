// Irradiance from lights with a size (PRESKIN_lights_area) at a surface point, for the diffusion
// reference: E = L_e int max(n . omega, 0) dOmega over the directions the light covers, its
// radiance L_e the light's candela over its projected area (docs/area-lights.md), times the range
// window at the distance to its centre, as the renderer takes it. Computed independently of the
// renderer's cap model:
//  - sphere: exact (the horizon-clipped solid angle of a sphere, by 2D Gauss-Legendre quadrature
//    over the cap's polar angle and azimuth, the horizon cut analytically per ring);
//  - rectangle: exact (the polygon clipped by the point's tangent plane, Lambert's edge formula);
//  - disc: the area-matched 256-gon, clipped and integrated like the rectangle;
//  - tube (a capsule: a cylinder with a half sphere at each end): midpoint quadrature over the
//    capsule's surface of L_e cos cos' / r^2 on the part facing the point (a convex emitter sees
//    no other part of itself), 128 x 64 on the cylinder and 64 x 32 on each end.
// Unshadowed, as the renderer shades them.
#pragma once

#include <preskin/Scene.h>

#include <glm/glm.hpp>

namespace preskin::reference {

// Irradiance (colour times intensity units) at point y with unit normal n; light must be an area
// light or a directional light with an angular radius (a sphere at infinity: its lux spread over
// the cap, radiance E / (pi sin^2 sigma), integrated exactly like a sphere's cap).
glm::dvec3 areaLightIrradiance(const Light& light, const glm::dvec3& y, const glm::dvec3& n);

// The integral of max(n . omega, 0) over a cap of angular radius sigma whose axis makes cos theta =
// cosTheta with n (ring by ring, each ring's azimuthal integral in closed form, composite Simpson
// over the rings).
double capCosineIntegral(double cosTheta, double sigma);

// The integral of max(n . omega, 0) over the solid angle of the polygon `corners` (world, in
// order) seen from y: the polygon clipped by y's tangent plane, then Lambert's formula. Exact.
double polygonCosineIntegral(const glm::dvec3* corners, int count, const glm::dvec3& y, const glm::dvec3& n);

}  // namespace preskin::reference
