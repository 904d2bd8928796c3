// TracedEnvironment: the environment's irradiance at a surface point for the diffusion reference,
// E(y) = int L(w) V(y, w) max(n . w, 0) dw, with L the environment image (Environment::radiance)
// and V the scene's visibility (RayScene, every triangle occludes), by Monte Carlo: half the
// samples cosine-weighted over the hemisphere, half drawn from the image's luminance per solid
// angle (a table of cells of at most 512 x 256, each sampled uniformly in longitude and cos(theta)),
// combined by the balance heuristic (Veach & Guibas, "Optimally Combining Sampling Techniques for
// Monte Carlo Rendering", SIGGRAPH 1995). Points are a Hammersley set rotated per point
// (Cranley-Patterson) by a hash of a caller's key, so a result depends only on the point and the
// key, never on threads. A constant environment takes cosine samples alone.
// Limits: noise falls as 1 / sqrt(samples); texels are read nearest; the visibility is of the
// point on the flat triangle the caller gives.
#pragma once

#include "RayScene.h"

#include <preskin/Environment.h>

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace preskin::reference {

class TracedEnvironment {
public:
    TracedEnvironment(const Environment& environment, uint32_t samples);

    glm::dvec3 irradiance(const RayScene& rays, const glm::dvec3& origin, const glm::dvec3& normal, uint64_t key) const;

private:
    // Direction and its density (per steradian) under the image's distribution, from (u1, u2).
    glm::dvec3 sampleImage(double u1, double u2, double& pdf) const;
    double imagePdf(const glm::dvec3& direction) const;

    const Environment& environment_;
    uint32_t samples_ = 0;
    bool image_ = false;
    uint32_t cellsX_ = 0, cellsY_ = 0;
    std::vector<double> rowCdf_;                  // cellsY + 1
    std::vector<std::vector<double>> columnCdf_;  // per row, cellsX + 1
    std::vector<double> cellProbability_;         // per cell
};

}  // namespace preskin::reference
