// LutMapping from a LutSet, and the set's CPU lookups. Both go through the mapping functions of
// shaders/shared/lut_mapping.h, the same code lut.glsl runs, then LutTable::sample (the Vulkan
// LINEAR + CLAMP_TO_EDGE rule). Limits: see lut_mapping.h.
#include "shared/constants.h"
#include "shared/lut_mapping.h"

#include <preskin/LutSet.h>

#include "skin/LutLayout.h"

#include <cmath>

namespace preskin {
namespace {

float f(double value) { return static_cast<float>(value); }

// v = (t + 0.5) / E with t = (N-1) * g(value), N the table's size and E >= N the texture's
// (a table padded with its edge texels up to E): returns ((N-1)/E, 0.5/E).
glm::vec2 texelScaleOffset(int size, int extent) {
    return {f(static_cast<double>(size - 1) / extent), f(0.5 / extent)};
}

int extentOr(int extent, int size) { return extent > 0 ? extent : size; }

}  // namespace

gpu::LutMapping lutMapping(const LutSet& luts) { return lutMapping(luts, LutExtents{}); }

gpu::LutMapping lutMapping(const LutSet& luts, const LutExtents& extents) {
    gpu::LutMapping m{};

    const LutAxis& nol = luts.diffuse().x;  // SplitLinear on [min < 0, max > 0]
    const int n = nol.size;
    const int zero = n / 2;
    const double nolExtent = extentOr(extents.diffuse.x, n);
    m.diffuseNoL = glm::vec4(f((zero + 0.5) / nolExtent), f(zero / (-nol.min * nolExtent)),
                             f((n - 1 - zero) / (nol.max * nolExtent)), f(luts.localPatchMm()));

    const LutAxis& curvature = luts.diffuse().y;  // SplitSqrt on [-max, max]
    const int cn = curvature.size;
    const int czero = cn / 2;
    const double curvatureExtent = extentOr(extents.diffuse.y, cn);
    m.diffuseCurvature = glm::vec4(f(1.0 / curvature.max), f((czero + 0.5) / curvatureExtent),
                                   f(double(czero) / curvatureExtent), f(double(cn - 1 - czero) / curvatureExtent));

    const LutAxis& shadow = luts.penumbra().x;  // Linear on [0, 1]
    const glm::vec2 shadowTexel = texelScaleOffset(shadow.size, extentOr(extents.penumbra.x, shadow.size));
    m.penumbraShadow = glm::vec4(shadowTexel.x, shadowTexel.y, 0.0f, 0.0f);
    const LutAxis& width = luts.penumbra().y;  // Rational
    const glm::vec2 widthTexel = texelScaleOffset(width.size, extentOr(extents.penumbra.y, width.size));
    m.penumbraWidth = glm::vec4(f(1.0 / luts.penumbraReferenceWidthMm()), widthTexel.x, widthTexel.y, 0.0f);

    const LutAxis& shCurvature = luts.shTransfer().x;
    const glm::vec2 shTexel = texelScaleOffset(shCurvature.size, extentOr(extents.shTransfer.x, shCurvature.size));
    m.shCurvature = glm::vec4(f(1.0 / shCurvature.max), shTexel.x, shTexel.y, 0.0f);
    const auto bands = static_cast<float>(extentOr(extents.shTransfer.y, luts.shTransfer().y.size));
    m.shBandV = glm::vec4(0.5f / bands, 1.5f / bands, 2.5f / bands, 0.0f);
    m.shLambert = glm::vec4(gpu::kShLambert0, gpu::kShLambert1, gpu::kShLambert2, 0.0f);

    const LutAxis& thickness = luts.transmittance().x;  // Log1p on [0, max]
    const glm::vec2 thicknessTexel =
        texelScaleOffset(thickness.size, extentOr(extents.transmittance.x, thickness.size));
    m.transmittance = glm::vec4(f(1.0 / thickness.scale), f(1.0 / std::log1p(thickness.max / thickness.scale)),
                                thicknessTexel.x, thicknessTexel.y);
    return m;
}

double LutSet::localPatchMm() const { return skin::kLocalPatchWidths * profile_.maxWidthMm(); }

glm::vec2 LutSet::diffuseUv(float NoL, float curvaturePerMm) const {
    return gpu::preskinDiffuseLutUv(lutMapping(*this), NoL, curvaturePerMm);
}

glm::vec3 LutSet::lookupDiffuse(float NoL, float curvaturePerMm) const {
    return diffuse_.sample(diffuseUv(NoL, curvaturePerMm));
}

glm::vec2 LutSet::penumbraUv(float shadow, float filterSigmaMm) const {
    return gpu::preskinPenumbraLutUv(lutMapping(*this), shadow, filterSigmaMm);
}

glm::vec3 LutSet::lookupPenumbra(float shadow, float filterSigmaMm) const {
    return penumbra_.sample(penumbraUv(shadow, filterSigmaMm));
}

glm::vec2 LutSet::shTransferUv(float curvaturePerMm, int band) const {
    return gpu::preskinShTransferLutUv(lutMapping(*this), curvaturePerMm, band);
}

std::array<glm::vec3, 3> LutSet::lookupShTransfer(float curvaturePerMm) const {
    const gpu::LutMapping m = lutMapping(*this);
    std::array<glm::vec3, 3> a;
    for (int l = 0; l < 3; ++l)
        a[static_cast<size_t>(l)] =
            m.shLambert[l] * shTransfer_.sample(gpu::preskinShTransferLutUv(m, curvaturePerMm, l));
    return a;
}

glm::vec2 LutSet::transmittanceUv(float thicknessMm) const {
    return gpu::preskinTransmittanceLutUv(lutMapping(*this), thicknessMm);
}

glm::vec3 LutSet::lookupTransmittance(float thicknessMm) const {
    return transmittance_.sample(transmittanceUv(thicknessMm));
}

}  // namespace preskin
