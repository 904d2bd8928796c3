// Baking a LutSet from a DiffusionProfile: diffuse response on the sphere of the signed curvature
// (SphereScatter.h, after Penner & Borshukov 2011),
// penumbra scattering, SH transfer and transmittance, in parallel over table columns with TBB.
// Models and axis definitions: engine/include/preskin/LutSet.h; quadrature: SphereScatter.h.
// Limits: sizes in [16, 4096] per axis; curvature range (0, 100] 1/mm.
#include <preskin/LutSet.h>

#include "skin/Half.h"
#include "skin/LutLayout.h"
#include "skin/SpecialFunctions.h"
#include "skin/SphereScatter.h"

#include <preskin/Error.h>

#include <fmt/core.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <vector>

namespace preskin {
namespace skin {
namespace {

void checkSize(int value, std::string_view source, std::string_view field) {
    if (value < LutBakeSettings::kMinSize || value > LutBakeSettings::kMaxSize)
        throw Error(fmt::format("{}: {}: must be an integer in [{}, {}], got {}", source, field,
                                LutBakeSettings::kMinSize, LutBakeSettings::kMaxSize, value));
}

// The thickness where the largest channel's transmittance falls to kTransmittanceFloor, rounded
// up to 0.01 mm (a round number keeps manifests comparable across machines).
double transmittanceRangeMm(const DiffusionProfile& profile) {
    return std::ceil(profile.reachMm(kTransmittanceFloor) * 100.0) / 100.0;
}

LutAxis axis(std::string quantity, std::string unit, AxisMapping mapping, double min, double max, double scale,
             int size) {
    LutAxis a;
    a.quantity = std::move(quantity);
    a.unit = std::move(unit);
    a.mapping = mapping;
    a.min = min;
    a.max = max;
    a.scale = scale;
    a.size = size;
    return a;
}

void storeHalf(LutTable& table, int ix, int iy, glm::dvec3 value) {
    const size_t i = (static_cast<size_t>(iy) * static_cast<size_t>(table.width()) + static_cast<size_t>(ix)) * 3;
    for (int c = 0; c < 3; ++c) table.rgb[i + static_cast<size_t>(c)] = roundToHalf(static_cast<float>(value[c]));
}

// The profile's edge response E(x) (DiffusionProfile::edgeResponse) for the penumbra table, which
// reads it at every (shadow, width) node: found once per bake on a grid geometric in |x| (a
// step of 1 % from 1e-6 of the narrowest width out to where less than 1e-9 of the light is
// beyond the edge) and interpolated by four-point Lagrange polynomials in log |x|; the grid
// resolves the x log x shape of Burley's response at the edge. E(-x) = 1 - E(x).
class EdgeTable {
public:
    explicit EdgeTable(const DiffusionProfile& profile)
        : profile_(profile),
          logMin_(std::log(1e-6 * profile.narrowestScaleMm())),
          aMax_(std::max(profile.reachMm(1e-9), 2.0 * std::exp(logMin_))) {
        const int count = int(std::ceil((std::log(aMax_) - logMin_) / kStep)) + 4;
        beyond_.resize(size_t(count));
        tbb::parallel_for(0, count, [&](int k) {
            beyond_[size_t(k)] = glm::dvec3(1.0) - profile.edgeResponse(std::exp(logMin_ + kStep * (k - 1)));
        });
    }

    glm::dvec3 operator()(double x) const {
        const double a = std::abs(x);
        glm::dvec3 beyond(0.0);
        if (a >= aMax_) {
            beyond = glm::dvec3(0.0);
        } else {
            const double t = (std::log(a) - logMin_) / kStep + 1.0;  // node k sits at t = k
            if (!(t >= 1.0)) return profile_.edgeResponse(x);        // closer to the edge than the grid
            const auto k = std::min(size_t(t), beyond_.size() - 3);
            const double u = t - double(k);  // in [0, 1) between nodes k and k + 1
            const double w0 = -u * (u - 1.0) * (u - 2.0) / 6.0, w1 = (u + 1.0) * (u - 1.0) * (u - 2.0) / 2.0;
            const double w2 = -(u + 1.0) * u * (u - 2.0) / 2.0, w3 = (u + 1.0) * u * (u - 1.0) / 6.0;
            beyond = w0 * beyond_[k - 1] + w1 * beyond_[k] + w2 * beyond_[k + 1] + w3 * beyond_[k + 2];
        }
        return x >= 0.0 ? glm::dvec3(1.0) - beyond : beyond;
    }

private:
    static constexpr double kStep = 0.01;
    const DiffusionProfile& profile_;
    double logMin_;
    double aMax_;
    std::vector<glm::dvec3> beyond_;  // node k at |x| = exp(logMin + kStep (k - 1))
};

}  // namespace

size_t nonFiniteValues(const LutTable& table) {
    return size_t(std::count_if(table.rgb.begin(), table.rgb.end(), [](float v) { return !std::isfinite(v); }));
}

void validateBakeSettings(const LutBakeSettings& s, std::string_view source, std::string_view prefix) {
    const std::string p(prefix);
    checkSize(s.diffuseNoLSize, source, p + "diffuseNoLSize");
    checkSize(s.diffuseCurvatureSize, source, p + "diffuseCurvatureSize");
    checkSize(s.penumbraShadowSize, source, p + "penumbraShadowSize");
    checkSize(s.penumbraWidthSize, source, p + "penumbraWidthSize");
    checkSize(s.shCurvatureSize, source, p + "shCurvatureSize");
    checkSize(s.transmittanceSize, source, p + "transmittanceSize");
    if (!std::isfinite(s.curvatureMaxPerMm) || !(s.curvatureMaxPerMm > 0.0) || s.curvatureMaxPerMm > 100.0)
        throw Error(
            fmt::format("{}: {}curvatureMaxPerMm: must be in (0, 100] 1/mm, got {}", source, p, s.curvatureMaxPerMm));
}

LutLayout makeLutLayout(const DiffusionProfile& profile, const LutBakeSettings& s) {
    const double inf = std::numeric_limits<double>::infinity();
    LutLayout layout;
    layout.diffuse.name = "diffuse";
    layout.diffuse.x = axis("NoL", "1", AxisMapping::SplitLinear, -1.0, 1.0, 1.0, s.diffuseNoLSize);
    layout.diffuse.y = axis("curvature", "1/mm", AxisMapping::SplitSqrt, -s.curvatureMaxPerMm, s.curvatureMaxPerMm, 1.0,
                            s.diffuseCurvatureSize);
    layout.penumbra.name = "penumbra";
    layout.penumbra.x = axis("shadow", "1", AxisMapping::Linear, 0.0, 1.0, 1.0, s.penumbraShadowSize);
    layout.penumbra.y = axis("filterSigmaRelative", "1", AxisMapping::Rational, 0.0, inf, 1.0, s.penumbraWidthSize);
    layout.shTransfer.name = "shTransfer";
    layout.shTransfer.x =
        axis("curvature", "1/mm", AxisMapping::Sqrt, 0.0, s.curvatureMaxPerMm, 1.0, s.shCurvatureSize);
    layout.shTransfer.y = axis("band", "1", AxisMapping::Index, 0.0, 2.0, 1.0, 3);
    layout.transmittance.name = "transmittance";
    layout.transmittance.x = axis("thickness", "mm", AxisMapping::Log1p, 0.0, transmittanceRangeMm(profile),
                                  profile.narrowestScaleMm(), s.transmittanceSize);
    layout.transmittance.y = axis("row", "1", AxisMapping::Index, 0.0, 0.0, 1.0, 1);
    layout.penumbraReferenceWidthMm = profile.maxWidthMm();
    return layout;
}

}  // namespace skin

LutBakeSettings LutBakeSettings::withSize(int size) {
    LutBakeSettings s;
    s.diffuseNoLSize = s.diffuseCurvatureSize = s.penumbraShadowSize = s.penumbraWidthSize = s.shCurvatureSize =
        s.transmittanceSize = size;
    return s;
}

void LutBakeSettings::validate() const { skin::validateBakeSettings(*this, "LutBakeSettings", ""); }

LutSet LutSet::bake(const DiffusionProfile& profile, const LutBakeSettings& settings, const LutBakeProgress& progress) {
    settings.validate();
    skin::LutLayout layout = skin::makeLutLayout(profile, settings);
    LutSet set(profile);
    set.settings_ = settings;
    set.penumbraReferenceWidthMm_ = layout.penumbraReferenceWidthMm;
    set.diffuse_ = std::move(layout.diffuse);
    set.penumbra_ = std::move(layout.penumbra);
    set.shTransfer_ = std::move(layout.shTransfer);
    set.transmittance_ = std::move(layout.transmittance);
    for (LutTable* table : {&set.diffuse_, &set.penumbra_, &set.shTransfer_, &set.transmittance_})
        table->rgb.assign(static_cast<size_t>(table->width()) * static_cast<size_t>(table->height()) * 3, 0.0f);

    // Node values shared by all columns.
    std::vector<double> nol(static_cast<size_t>(set.diffuse_.width()));
    for (int i = 0; i < set.diffuse_.width(); ++i) nol[static_cast<size_t>(i)] = set.diffuse_.x.valueAt(i);
    std::vector<double> shadowQuantile(static_cast<size_t>(set.penumbra_.width()));
    for (int i = 0; i < set.penumbra_.width(); ++i)
        shadowQuantile[static_cast<size_t>(i)] = skin::normalQuantile(set.penumbra_.x.valueAt(i));

    // Work units: diffuse columns (one curvature each), SH columns, penumbra rows (one filter
    // width each), the transmittance row.
    const int diffuseUnits = set.diffuse_.height();
    const int shUnits = set.shTransfer_.width();
    const int penumbraUnits = set.penumbra_.height();
    const int total = diffuseUnits + shUnits + penumbraUnits + 1;
    std::atomic<int> done{0};
    std::mutex progressMutex;
    int reported = 0;
    auto finishUnit = [&] {
        done.fetch_add(1);
        if (!progress) return;
        std::lock_guard lock(progressMutex);
        const int now = done.load();
        if (now > reported) {
            reported = now;
            progress(static_cast<double>(now) / total);
        }
    };

    const double windowSigmas = skin::kPenumbraWindowSigmas;
    const skin::EdgeTable edgeResponse(profile);
    const double patchMm = set.localPatchMm();
    tbb::parallel_for(0, total, [&](int unit) {
        if (unit < diffuseUnits) {
            const int iy = unit;
            const double curvaturePerMm = set.diffuse_.y.valueAt(iy);
            std::vector<glm::dvec3> column(nol.size());
            skin::sphereScatter(profile, curvaturePerMm, patchMm, nol, column);
            for (int ix = 0; ix < set.diffuse_.width(); ++ix)
                skin::storeHalf(set.diffuse_, ix, iy, column[static_cast<size_t>(ix)]);
        } else if (unit < diffuseUnits + shUnits) {
            const int ix = unit - diffuseUnits;
            const std::array<glm::dvec3, 3> a = skin::shTransfer(profile, set.shTransfer_.x.valueAt(ix));
            for (int l = 0; l < 3; ++l)
                skin::storeHalf(set.shTransfer_, ix, l,
                                a[static_cast<size_t>(l)] / skin::kLambertZonal[static_cast<size_t>(l)]);
        } else if (unit < diffuseUnits + shUnits + penumbraUnits) {
            const int iy = unit - diffuseUnits - shUnits;
            const int lastRow = set.penumbra_.height() - 1;
            const double sigmaMm = set.penumbra_.y.valueAt(iy) * set.penumbraReferenceWidthMm_;
            const bool limitRow = iy == 0 || iy == lastRow;
            // The filter only finds where the edge is, x = sigma Phi^-1(shadow); the light is a
            // point, so the skin sees the hard edge there through its profile, E(x), renormalised
            // to the filter's window |x| <= 3 sigma (beyond it the filter reads 0 or 1).
            const glm::dvec3 low = limitRow ? glm::dvec3(0.0) : edgeResponse(-windowSigmas * sigmaMm);
            const glm::dvec3 high = limitRow ? glm::dvec3(1.0) : edgeResponse(windowSigmas * sigmaMm);
            for (int ix = 0; ix < set.penumbra_.width(); ++ix) {
                const double q = shadowQuantile[static_cast<size_t>(ix)];
                glm::dvec3 value;
                if (q <= -windowSigmas) {
                    value = glm::dvec3(0.0);
                } else if (q >= windowSigmas) {
                    value = glm::dvec3(1.0);
                } else if (iy == lastRow) {
                    value = glm::dvec3(q < 0.0 ? 0.0 : (q > 0.0 ? 1.0 : 0.5));  // a filter infinitely wider: the edge
                } else if (iy == 0) {
                    value = glm::dvec3(0.5 * (q / windowSigmas + 1.0));  // vanishing filter: the linear limit
                } else {
                    value = (edgeResponse(sigmaMm * q) - low) / (high - low);
                }
                skin::storeHalf(set.penumbra_, ix, iy, glm::clamp(value, 0.0, 1.0));
            }
        } else {
            for (int ix = 0; ix < set.transmittance_.width(); ++ix)
                skin::storeHalf(set.transmittance_, ix, 0, profile.transmittance(set.transmittance_.x.valueAt(ix)));
        }
        finishUnit();
    });
    // No table with a non-finite value leaves the bake (the profile's bounds keep it finite;
    // this is the last guard, not the rule).
    for (const LutTable* table : {&set.diffuse_, &set.penumbra_, &set.shTransfer_, &set.transmittance_}) {
        const size_t bad = skin::nonFiniteValues(*table);
        if (bad > 0)
            throw Error(fmt::format("{}: LUT bake: table {}: {} values are not finite; nothing baked", profile.name(),
                                    table->name, bad));
    }
    return set;
}

}  // namespace preskin
