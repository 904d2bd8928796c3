// The screen-space baseline's kernel (RenderSettings::diffusion, Diffusion::ScreenSpace): a
// diffusion profile as one 1D kernel per channel, applied along image rows and then columns
// (separable subsurface scattering, Jimenez et al., "Separable Subsurface Scattering", CGF 2015).
//
// A radial profile R(r) is separable only when it is one Gaussian; what a separable pass can
// reproduce exactly is the response to a straight edge. Blurring a step horizontally with a 1D
// kernel k and then vertically leaves the step's response int k, so k is the profile's line
// profile P(u) (DiffusionProfile::lineProfile, R integrated along a line): every straight
// boundary of light (a shadow edge, a terminator seen flat) then gets the profile's exact edge
// response, corners and points an approximation. The kernel is sampled at `taps` offsets
// spread as the square of the tap index (denser in the middle, as Jimenez et al. place them) over
// [-reach, reach]; each tap weighs P integrated between the midpoints to its neighbours
// (DiffusionProfile::edgeResponse), the outer taps taking the tails beyond, so the weights of a
// channel sum to exactly 1 (a uniformly lit surface stays unchanged).
#pragma once

#include <preskin/DiffusionProfile.h>
#include <preskin/Glm.h>

#include <cstdint>
#include <vector>

namespace preskin {

struct SeparableTap {
    double offsetMm = 0.0;  // profile millimetres from the centre
    glm::dvec3 weight{0.0};
};

// Odd tap counts from kMinSeparableTaps to kMaxSeparableTaps.
inline constexpr uint32_t kMinSeparableTaps = 3;
inline constexpr uint32_t kMaxSeparableTaps = 63;

// The reach: where the widest channel's edge response falls to `tailFraction` / 2 on either side
// (what lies beyond is carried by the outer taps).
double separableReachMm(const DiffusionProfile& profile, double tailFraction = 0.01);

// `taps` taps (odd, kMinSeparableTaps..kMaxSeparableTaps), ascending offsets, the middle one at 0.
// Throws preskin::Error for another count.
std::vector<SeparableTap> separableKernel(const DiffusionProfile& profile, uint32_t taps);

}  // namespace preskin
