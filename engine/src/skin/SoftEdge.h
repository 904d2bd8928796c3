// The skin's response to a soft shadow edge: a straight edge whose irradiance falls off as a
// Gaussian edge of standard deviation sigma (the shadow filter's penumbra on the receiver), seen
// through the diffusion profile. E_sigma(x) = int E(x - t) phi_sigma(t) dt, E the profile's hard-
// edge response (DiffusionProfile::edgeResponse). Skin never sharpens a penumbra: every channel
// is at least as soft as the incoming edge, red the softest (Penner & Borshukov, GPU Pro 2, 2011:
// the penumbra convolved with the profile).
// Sums of Gaussians: closed form, sum_i w_i Phi(x / sqrt(v_i + sigma^2)) / albedo. Other profiles:
// E tabulated once on a fine grid, then the convolution by composite Gauss-Legendre split at the
// edge (where E's slope peaks). Limits: linear interpolation of the tabulated E (about 1e-4).
#pragma once

#include <preskin/DiffusionProfile.h>

#include <glm/glm.hpp>

#include <vector>

namespace preskin::skin {

class SoftEdge {
public:
    explicit SoftEdge(const DiffusionProfile& profile);
    // Per channel, in [0, 1]; sigmaMm = 0 gives the hard-edge response.
    glm::dvec3 operator()(double xMm, double sigmaMm) const;

private:
    glm::dvec3 tabulated(double xMm) const;

    const DiffusionProfile& profile_;
    double halfRangeMm_ = 0.0;
    double stepMm_ = 0.0;
    std::vector<glm::dvec3> table_;  // E at -halfRange + i * step (not SumOfGaussians)
};

}  // namespace preskin::skin
