// Lights listed per pixel against the exact count, for `preskin bench`: the light-count debug
// view in linear output gives each pixel's list length and view depth; the surface point is
// rebuilt from the depth on the pixel centre's ray and tested against every light on the CPU (a
// world-space grid of the lights only narrows the candidates).
#pragma once

#include <preskin/ClusterGrid.h>
#include <preskin/Renderer.h>
#include <preskin/Scene.h>
#include <preskin/View.h>

#include <cstdint>
#include <vector>

namespace preskin::cli::bench {

struct PerPixel {
    uint64_t pixels = 0;
    double listedMean = 0.0;
    double exactMean = 0.0;
    uint32_t listedMax = 0;
    uint32_t exactMax = 0;
    uint64_t listedBelowExact = 0;  // pixels whose list is shorter than the exact count (a bug)
    double otherListedMean = 0.0;   // the list length another grid (countPerPixel's `other`) gives
};

// The light-count debug view of `view` in linear output with `lights` (the renderer keeps the
// debug settings and lights afterwards).
RenderedImage lightCountImage(Renderer& renderer, const RenderSettings& settings, const View& view, uint32_t width,
                              uint32_t height, const std::vector<Light>& lights);

// `image`: the light-count debug view in linear output (r: lights listed, b: view depth in m).
// `other`, when given: a second grid over the same lights, whose list length at each pixel's
// surface point is averaged too.
PerPixel countPerPixel(const RenderedImage& image, const Eye& view, const std::vector<Light>& lights,
                       const ClusterGrid* other = nullptr);

}  // namespace preskin::cli::bench
