// The figures of `preskin compare`: per region of the image (masks built from what the reference
// knows about each pixel), the root-mean-square error of a render against the reference per
// colour channel and pooled over RGB, the mean signed error, and the reference's mean. Field
// definitions: docs/reference.md ("preskin compare").
#pragma once

#include <preskin/DiffusionReference.h>

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace preskin::cli {

struct Region {
    std::string name;
    std::vector<uint8_t> mask;  // per pixel
    size_t pixels = 0;
};

// all: visible skin; shadowEdge: skin near a cast-shadow edge; concave / convex: skin whose
// signed mean curvature is below -curvatureClassPerMm / above +curvatureClassPerMm;
// awayFromEdges, concaveAway, convexAway: the same away from cast-shadow edges; terminator: the
// reference's terminator band (the shadow light's N.L within [-0.1, 0.2], no cast shadow within
// its clearance), in this order.
std::vector<Region> compareRegions(const ReferenceImage& reference, double curvatureClassPerMm);

struct ErrorStats {
    glm::dvec3 rmse{0.0};
    double rmsePooled = 0.0;    // sqrt of the mean over R, G, B of the mean squared error
    glm::dvec3 meanError{0.0};  // mean of render - reference
};

// `image`: RGBA linear floats of the reference's size.
ErrorStats measureError(const std::vector<float>& image, const ReferenceImage& reference, const Region& region);
glm::dvec3 regionMean(const ReferenceImage& reference, const Region& region);

}  // namespace preskin::cli
