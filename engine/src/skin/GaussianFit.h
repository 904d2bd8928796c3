// A diffusion profile as a sum of Gaussians, for methods that blur by Gaussians (the
// texture-space baseline, render/TextureDiffusion.h): a sum-of-Gaussians profile's own terms;
// any other profile (Christensen & Burley) fitted by 8 Gaussians whose standard deviations double
// from a quarter of its narrowest scale, with per-channel weights >= 0 by non-negative least
// squares on R(r) sampled over its reach, weighted by the ring's area 2 pi r.
#pragma once

#include <preskin/DiffusionProfile.h>

#include <vector>

namespace preskin {

// Terms ascending by variance; each channel's weights sum to 1 (the profile divided by its albedo).
std::vector<GaussianTerm> normalizedGaussians(const DiffusionProfile& profile);

}  // namespace preskin
