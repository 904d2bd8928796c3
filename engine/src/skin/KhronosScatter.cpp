// Diffusion profiles from Khronos scattering parameters; the mapping and its sources are in
// <preskin/KhronosScatter.h>.
#include <preskin/KhronosScatter.h>

#include <preskin/Error.h>

#include <fmt/core.h>

#include <cmath>

namespace preskin {

glm::dvec3 singleScatteringAlbedo(const glm::dvec3& multiscatterAlbedo, double anisotropy) {
    glm::dvec3 alpha;
    for (int c = 0; c < 3; ++c) {
        const double a = multiscatterAlbedo[c];
        const double s = 4.09712 + 4.20863 * a - std::sqrt(9.59217 + 41.6808 * a + 17.7126 * a * a);
        alpha[c] = (1.0 - s * s) / (1.0 - anisotropy * s * s);
    }
    return alpha;
}

glm::dvec3 khronosMeanFreePathMm(const KhronosScatter& scatter) {
    const glm::dvec3 alpha = singleScatteringAlbedo(scatter.multiscatterColor, scatter.scatterAnisotropy);
    glm::dvec3 mfp;
    for (int c = 0; c < 3; ++c) {
        const double extinctionPerM = -std::log(scatter.attenuationColor[c]) / scatter.attenuationDistanceM;
        mfp[c] = 1000.0 / (extinctionPerM * (1.0 - scatter.scatterAnisotropy * alpha[c]));
    }
    return mfp;
}

DiffusionProfile profileFromKhronosScatter(const KhronosScatter& scatter, std::string name) {
    const char* channel[3] = {"red", "green", "blue"};
    if (!(scatter.attenuationDistanceM > 0.0) || !std::isfinite(scatter.attenuationDistanceM))
        throw Error(fmt::format("attenuationDistance: {} m defines no extinction (a finite distance > 0 is needed)",
                                scatter.attenuationDistanceM));
    if (!(std::abs(scatter.scatterAnisotropy) < 1.0))
        throw Error(fmt::format("scatterAnisotropy: must be in (-1, 1), got {}", scatter.scatterAnisotropy));
    for (int c = 0; c < 3; ++c) {
        const double color = scatter.attenuationColor[c];
        if (!(color > 0.0 && color < 1.0))
            throw Error(
                fmt::format("attenuationColor: the {} channel is {}: a profile needs each channel in (0, 1) "
                            "(1: no extinction, no scattering)",
                            channel[c], color));
        const double albedo = scatter.multiscatterColor[c];
        if (!(albedo > 0.0 && albedo <= 1.0))
            throw Error(fmt::format("multiscatterColor: the {} channel is {}: a profile needs each channel in (0, 1]",
                                    channel[c], albedo));
    }
    return DiffusionProfile::burley(scatter.multiscatterColor, khronosMeanFreePathMm(scatter), std::move(name));
}

}  // namespace preskin
