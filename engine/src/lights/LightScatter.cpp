// Deterministic scattered lights (see <preskin/LightScatter.h>).
#include <preskin/LightScatter.h>

#include <preskin/Error.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

namespace preskin {

namespace {

// [0, 1) from the top 24 bits of one mt19937 draw: identical on every standard library.
float unit(std::mt19937& rng) { return float(rng() >> 8) * (1.0f / 16777216.0f); }

glm::vec3 hueToRgb(float h) {
    const glm::vec3 k(0.0f, 2.0f / 3.0f, 1.0f / 3.0f);
    glm::vec3 c = glm::abs(glm::fract(glm::vec3(h) + k) * 6.0f - 3.0f) - 1.0f;
    return glm::clamp(c, 0.0f, 1.0f);
}

// The scattered lights' draws: a range factor a = 0.15 + 0.25 u, spots' outer cone angle
// 0.35 + 0.45 u (radians).
constexpr double kRangeLow = 0.15, kRangeSpan = 0.25;
constexpr double kConeLow = 0.35, kConeSpan = 0.45;
constexpr double kSpotRange = 1.5;

glm::vec3 scatterExtent(const Bounds& bounds) {
    return bounds.empty() ? glm::vec3(1.0f) : glm::max(bounds.extent(), glm::vec3(1e-3f));
}

}  // namespace

float scatterRangeScale(const Bounds& bounds, uint32_t count, float lightsPerPoint) {
    if (!(lightsPerPoint > 0.0f) || !std::isfinite(lightsPerPoint))
        throw Error("scatterLights: lights per point must be a positive finite number");
    if (count == 0) return 0.0f;
    const glm::dvec3 extent(scatterExtent(bounds));
    const double volume = 8.0 * extent.x * extent.y * extent.z;  // the bounds grown by half their size
    // E[a^3] for a = low + span u, u uniform: ((low + span)^4 - low^4) / (4 span).
    const double meanCube = (std::pow(kRangeLow + kRangeSpan, 4.0) - std::pow(kRangeLow, 4.0)) / (4.0 * kRangeSpan);
    // A cone of half-angle t holds (1 - cos t) / 2 of its sphere; E over t = low + span u.
    const double meanConeFraction = 0.5 - 0.5 * (std::sin(kConeLow + kConeSpan) - std::sin(kConeLow)) / kConeSpan;
    // Every third light is a spot (range 1.5 times longer, inside its cone).
    const double meanVolumePerScale3 = 4.0 / 3.0 * std::numbers::pi * meanCube *
        (2.0 / 3.0 + 1.0 / 3.0 * kSpotRange * kSpotRange * kSpotRange * meanConeFraction);
    return float(std::cbrt(double(lightsPerPoint) * volume / (double(count) * meanVolumePerScale3)));
}

std::vector<Light> scatterLights(const Bounds& bounds, uint32_t count, uint32_t seed, float lightsPerPoint) {
    std::mt19937 rng(seed);
    const glm::vec3 center = bounds.empty() ? glm::vec3(0.0f) : bounds.center();
    const glm::vec3 extent = scatterExtent(bounds);
    const float radius =
        lightsPerPoint != 0.0f ? scatterRangeScale(bounds, count, lightsPerPoint) : 0.5f * glm::length(extent);
    std::vector<Light> lights;
    lights.reserve(count);
    for (uint32_t i = 0; i < count; ++i) {
        Light l;
        l.name = "scattered" + std::to_string(i);
        l.type = (i % 3 == 2) ? LightType::Spot : LightType::Point;
        l.positionWs = center + (glm::vec3(unit(rng), unit(rng), unit(rng)) - 0.5f) * extent * 2.0f;
        l.color = glm::mix(glm::vec3(1.0f), hueToRgb(unit(rng)), 0.7f);
        l.range = radius * (float(kRangeLow) + float(kRangeSpan) * unit(rng));
        // About 0.5 lux at half the range, whatever the scene's scale.
        l.intensity = 0.5f * 0.25f * l.range * l.range;
        if (l.type == LightType::Spot) {
            const glm::vec3 toCenter = center - l.positionWs;
            l.directionWs = glm::length(toCenter) > 1e-6f ? glm::normalize(toCenter) : glm::vec3(0.0f, -1.0f, 0.0f);
            l.outerConeAngle = float(kConeLow) + float(kConeSpan) * unit(rng);
            l.innerConeAngle = l.outerConeAngle * 0.6f;
            l.range *= float(kSpotRange);
            l.intensity *= 2.25f;
        }
        lights.push_back(l);
    }
    return lights;
}

}  // namespace preskin
