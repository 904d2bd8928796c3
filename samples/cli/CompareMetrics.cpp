#include "CompareMetrics.h"

#include <cmath>

namespace preskin::cli {

std::vector<Region> compareRegions(const ReferenceImage& reference, double curvatureClassPerMm) {
    const size_t count = size_t(reference.width) * reference.height;
    std::vector<Region> regions{{"all", {}, 0},        {"shadowEdge", {}, 0},    {"concave", {}, 0},
                                {"convex", {}, 0},     {"awayFromEdges", {}, 0}, {"concaveAway", {}, 0},
                                {"convexAway", {}, 0}, {"terminator", {}, 0}};
    for (Region& r : regions) r.mask.assign(count, 0);
    for (size_t i = 0; i < count; ++i) {
        if (!(reference.rgba32f[4 * i + 3] > 0.0f) || !reference.skin[i]) continue;
        const double curvature = reference.curvaturePerMm[i];
        const bool edge = reference.nearShadowEdge[i] != 0;
        const bool concave = curvature<-curvatureClassPerMm, convex = curvature> curvatureClassPerMm;
        const bool in[8] = {
            true, edge, concave, convex, !edge, concave && !edge, convex && !edge, reference.terminatorBand[i] != 0};
        for (size_t r = 0; r < regions.size(); ++r)
            if (in[r]) {
                regions[r].mask[i] = 1;
                ++regions[r].pixels;
            }
    }
    return regions;
}

ErrorStats measureError(const std::vector<float>& image, const ReferenceImage& reference, const Region& region) {
    ErrorStats s;
    glm::dvec3 squared(0.0);
    for (size_t i = 0; i < region.mask.size(); ++i) {
        if (!region.mask[i]) continue;
        for (int c = 0; c < 3; ++c) {
            const double d = double(image[4 * i + size_t(c)]) - double(reference.rgba32f[4 * i + size_t(c)]);
            squared[c] += d * d;
            s.meanError[c] += d;
        }
    }
    if (region.pixels == 0) return s;
    const double n = double(region.pixels);
    s.rmse = glm::sqrt(squared / n);
    s.rmsePooled = std::sqrt((squared.x + squared.y + squared.z) / (3.0 * n));
    s.meanError /= n;
    return s;
}

glm::dvec3 regionMean(const ReferenceImage& reference, const Region& region) {
    glm::dvec3 sum(0.0);
    for (size_t i = 0; i < region.mask.size(); ++i)
        if (region.mask[i])
            sum += glm::dvec3(reference.rgba32f[4 * i], reference.rgba32f[4 * i + 1], reference.rgba32f[4 * i + 2]);
    return region.pixels > 0 ? sum / double(region.pixels) : sum;
}

}  // namespace preskin::cli
