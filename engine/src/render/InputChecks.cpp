// Checks of host-supplied renderer settings and lights (see InputChecks.h).
#include "render/InputChecks.h"
#include "io/NumberRule.h"

#include <preskin/Environment.h>
#include <preskin/Error.h>

#include <fmt/core.h>

#include <numbers>

#include <string>

namespace preskin {

namespace {

void check(double value, const std::string& where) {
    if (auto problem = io::numberProblem(value)) throw Error(where + ": " + *problem);
}

template <int N>
void check(const glm::vec<N, float>& v, const std::string& where) {
    for (int i = 0; i < N; ++i) check(v[i], where + "[" + std::to_string(i) + "]");
}

}  // namespace

void checkRenderSettings(const RenderSettings& settings) {
    check(settings.exposure, "RenderSettings: exposure");
    check(settings.shadowSoftnessTexels, "RenderSettings: shadowSoftnessTexels");
    if (settings.exposure < 0.0f) throw Error("RenderSettings: exposure: must be >= 0");
    if (!(settings.shadowSoftnessTexels > 0.0f)) throw Error("RenderSettings: shadowSoftnessTexels: must be > 0");
    check(settings.skinShadowReachMm, "RenderSettings: skinShadowReachMm");
    if (settings.skinShadowReachMm < 0.0f) throw Error("RenderSettings: skinShadowReachMm: must be >= 0");
    if (settings.environmentLights < -1 || settings.environmentLights > int(kMaxEnvironmentLights))
        throw Error(fmt::format("RenderSettings: environmentLights: {} is outside -1..{}", settings.environmentLights,
                                kMaxEnvironmentLights));
    if (settings.screenDiffusionTaps < 3 || settings.screenDiffusionTaps > 63 || settings.screenDiffusionTaps % 2 == 0)
        throw Error(fmt::format("RenderSettings: screenDiffusionTaps: {} is not an odd count from 3 to 63",
                                settings.screenDiffusionTaps));
    if (settings.textureDiffusionSize < 16 || settings.textureDiffusionSize > 8192)
        throw Error(
            fmt::format("RenderSettings: textureDiffusionSize: {} is outside 16..8192", settings.textureDiffusionSize));
    check(settings.background.color, "RenderSettings: background.color");
    if (glm::any(glm::lessThan(settings.background.color, glm::vec3(0.0f))))
        throw Error("RenderSettings: background.color: must be >= 0");
}

void checkLights(const std::vector<Light>& lights) {
    for (size_t i = 0; i < lights.size(); ++i) {
        const Light& l = lights[i];
        const std::string at = "lights[" + std::to_string(i) + "].";
        check(l.color, at + "color");
        check(l.intensity, at + "intensity");
        check(l.range, at + "range");
        check(l.innerConeAngle, at + "innerConeAngle");
        check(l.outerConeAngle, at + "outerConeAngle");
        check(l.positionWs, at + "positionWs");
        check(l.directionWs, at + "directionWs");
        if (l.intensity < 0.0f || l.range < 0.0f || l.color.r < 0.0f || l.color.g < 0.0f || l.color.b < 0.0f)
            throw Error(at + "intensity, range, color: must be >= 0");
        check(l.axisWs, at + "axisWs");
        const auto size = [&](float v, const char* field) {
            check(v, at + field);
            if (!(v > 0.0f) || v > 1e6f) throw Error(fmt::format("{}{}: {} is outside (0, 1e6] metres", at, field, v));
        };
        if (l.type == LightType::Sphere || l.type == LightType::Tube || l.type == LightType::Disc)
            size(l.radius, "radius");
        if (l.type == LightType::Tube) size(l.length, "length");
        check(l.angularRadius, at + "angularRadius");
        if (l.angularRadius < 0.0f || l.angularRadius > 0.25f * std::numbers::pi_v<float>)
            throw Error(fmt::format("{}angularRadius: {} is outside [0, pi/4] radians", at, l.angularRadius));
        if (l.type == LightType::Rectangle) {
            size(l.width, "width");
            size(l.height, "height");
        }
    }
}

}  // namespace preskin
