#include "skin/SeparableKernel.h"

#include <preskin/Error.h>

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

namespace preskin {

double separableReachMm(const DiffusionProfile& profile, double tailFraction) {
    // edgeResponse(-x) falls monotonically from 1/2 at 0; bisect the widest channel's.
    auto tail = [&](double x) {
        const glm::dvec3 e = profile.edgeResponse(-x);
        return std::max({e.r, e.g, e.b});
    };
    double hi = std::max(profile.maxWidthMm(), 1e-3);
    while (tail(hi) > 0.5 * tailFraction && hi < 1e6) hi *= 2.0;
    double lo = 0.0;
    for (int i = 0; i < 60; ++i) {
        const double mid = 0.5 * (lo + hi);
        (tail(mid) > 0.5 * tailFraction ? lo : hi) = mid;
    }
    return hi;
}

std::vector<SeparableTap> separableKernel(const DiffusionProfile& profile, uint32_t taps) {
    if (taps < kMinSeparableTaps || taps > kMaxSeparableTaps || taps % 2 == 0)
        throw Error(
            fmt::format("separable kernel: {} taps (odd, {} to {})", taps, kMinSeparableTaps, kMaxSeparableTaps));
    const double reach = separableReachMm(profile);
    const int half = int(taps / 2);
    std::vector<SeparableTap> kernel(taps);
    for (int i = -half; i <= half; ++i) {
        const double t = double(i) / half;
        kernel[size_t(i + half)].offsetMm = reach * t * std::abs(t);
    }
    // Tap i covers [b_i, b_(i+1)): midpoints between offsets, the outer ones open to infinity.
    glm::dvec3 below(0.0);  // edgeResponse at the lower boundary
    for (size_t i = 0; i < taps; ++i) {
        const glm::dvec3 above =
            i + 1 < taps ? profile.edgeResponse(0.5 * (kernel[i].offsetMm + kernel[i + 1].offsetMm)) : glm::dvec3(1.0);
        kernel[i].weight = above - below;
        below = above;
    }
    return kernel;
}

}  // namespace preskin
