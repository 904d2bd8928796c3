#include <preskin/Tonemap.h>

#include <algorithm>
#include <cmath>

namespace preskin {

glm::dvec3 tonemapNeutral(glm::dvec3 color) {
    const double startCompression = 0.8 - 0.04, desaturation = 0.15;
    const double x = std::min({color.r, color.g, color.b});
    const double offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
    color -= offset;
    const double peak = std::max({color.r, color.g, color.b});
    if (peak < startCompression) return color;
    const double d = 1.0 - startCompression;
    const double newPeak = 1.0 - d * d / (peak + d - startCompression);
    color *= newPeak / peak;
    const double g = 1.0 - 1.0 / (desaturation * (peak - newPeak) + 1.0);
    return glm::mix(color, glm::dvec3(newPeak), g);
}

glm::dvec3 tonemapNeutralInverse(glm::dvec3 display) {
    const glm::dvec3 y = glm::clamp(display, glm::dvec3(0.0), glm::dvec3(0.999));
    glm::dvec3 x = y;
    for (int i = 0; i < 100; ++i) {
        const glm::dvec3 r = tonemapNeutral(x) - y;
        if (std::max({std::abs(r.r), std::abs(r.g), std::abs(r.b)}) < 1e-12) break;
        for (int c = 0; c < 3; ++c) {  // the channel's own slope (the others' pull is small)
            glm::dvec3 step = x;
            const double h = 1e-7 * std::max(1.0, x[c]);
            step[c] += h;
            const double slope = std::max((tonemapNeutral(step)[c] - tonemapNeutral(x)[c]) / h, 1e-6);
            x[c] = std::max(x[c] - r[c] / slope, 0.0);
        }
    }
    return x;
}

}  // namespace preskin
