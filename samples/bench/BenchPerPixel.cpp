// Lights listed per pixel against the exact count; see BenchPerPixel.h.
#include "BenchPerPixel.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace preskin::cli::bench {

namespace {

// Does the light's volume contain p? Range sphere (the attenuation window is zero at the range)
// and, for spots, the outer cone (the cone attenuation is zero at its edge).
bool lightTouches(const Light& l, const glm::dvec3& p) {
    const glm::dvec3 toPoint = p - glm::dvec3(l.positionWs);
    const double d2 = glm::dot(toPoint, toPoint);
    if (l.range > 0.0f && d2 >= double(l.range) * double(l.range)) return false;
    if (l.type != LightType::Spot) return true;
    const double d = std::sqrt(d2);
    if (d <= 0.0) return true;
    const glm::dvec3 dir =
        glm::length(l.directionWs) > 0.0f ? glm::normalize(glm::dvec3(l.directionWs)) : glm::dvec3(0.0, 0.0, -1.0);
    return glm::dot(dir, toPoint) / d > std::cos(double(l.outerConeAngle));
}

}  // namespace

RenderedImage lightCountImage(Renderer& renderer, const RenderSettings& settings, const View& view, uint32_t width,
                              uint32_t height, const std::vector<Light>& lights) {
    RenderSettings debug = settings;
    debug.debugView = DebugView::LightCount;
    renderer.setSettings(debug);
    renderer.setLights(lights);
    return renderer.render(view, width, height, OutputEncoding::LinearFloat);
}

PerPixel countPerPixel(const RenderedImage& image, const Eye& view, const std::vector<Light>& lights,
                       const ClusterGrid* other) {
    const glm::dmat4 clipFromView(view.clipFromView);
    const glm::dmat4 viewFromClip = glm::inverse(clipFromView);
    const glm::dmat4 worldFromView = glm::inverse(glm::dmat4(view.viewFromWorld));
    struct Sample {
        glm::dvec3 positionWs;
        uint32_t listed;
    };
    std::vector<Sample> samples;
    glm::dvec3 lo(std::numeric_limits<double>::max());
    glm::dvec3 hi(-std::numeric_limits<double>::max());
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x) {
            const float* px = &image.rgba32f[(size_t(y) * image.width + x) * 4];
            const double depth = px[2];
            if (!(depth > 0.5 * double(view.nearM))) continue;  // background (clear colour)
            const glm::dvec4 clip = clipFromView * glm::dvec4(0.0, 0.0, -depth, 1.0);
            const glm::dvec4 ndc((x + 0.5) / image.width * 2.0 - 1.0, (y + 0.5) / image.height * 2.0 - 1.0,
                                 clip.z / clip.w, 1.0);
            glm::dvec4 p = viewFromClip * ndc;
            p /= p.w;
            const glm::dvec3 world(worldFromView * p);
            samples.push_back({world, static_cast<uint32_t>(std::lround(px[0]))});
            lo = glm::min(lo, world);
            hi = glm::max(hi, world);
        }
    PerPixel out;
    if (samples.empty()) return out;

    // Candidate lights per cell of a grid over the surface points.
    const int n = 32;
    const glm::dvec3 cell = glm::max((hi - lo) / double(n), glm::dvec3(1e-6));
    std::vector<std::vector<uint32_t>> cells(size_t(n) * n * n);
    std::vector<uint32_t> everywhere;
    auto cellOf = [&](const glm::dvec3& p) {
        return glm::clamp(glm::ivec3(glm::floor((p - lo) / cell)), glm::ivec3(0), glm::ivec3(n - 1));
    };
    for (uint32_t i = 0; i < lights.size(); ++i) {
        const Light& l = lights[i];
        if (l.type == LightType::Directional) continue;
        if (!(l.range > 0.0f)) {
            everywhere.push_back(i);
            continue;
        }
        const glm::dvec3 c(l.positionWs);
        const double r = l.range;
        if (glm::any(glm::lessThan(c + r, lo)) || glm::any(glm::greaterThan(c - r, hi))) continue;
        const glm::ivec3 a = cellOf(c - r);
        const glm::ivec3 b = cellOf(c + r);
        for (int z = a.z; z <= b.z; ++z)
            for (int y = a.y; y <= b.y; ++y)
                for (int x = a.x; x <= b.x; ++x) cells[(size_t(z) * n + size_t(y)) * n + size_t(x)].push_back(i);
    }
    double listedSum = 0.0;
    double exactSum = 0.0;
    double otherSum = 0.0;
    for (const Sample& s : samples) {
        if (other) otherSum += other->ranges[other->froxelAt(glm::vec3(s.positionWs))].y;
        const glm::ivec3 c = cellOf(s.positionWs);
        uint32_t exact = 0;
        for (uint32_t i : cells[(size_t(c.z) * n + size_t(c.y)) * n + size_t(c.x)])
            if (lightTouches(lights[i], s.positionWs)) ++exact;
        for (uint32_t i : everywhere)
            if (lightTouches(lights[i], s.positionWs)) ++exact;
        listedSum += s.listed;
        exactSum += exact;
        out.listedMax = std::max(out.listedMax, s.listed);
        out.exactMax = std::max(out.exactMax, exact);
        if (s.listed < exact) ++out.listedBelowExact;
    }
    out.pixels = samples.size();
    out.listedMean = listedSum / double(samples.size());
    out.exactMean = exactSum / double(samples.size());
    out.otherListedMean = otherSum / double(samples.size());
    return out;
}

}  // namespace preskin::cli::bench
