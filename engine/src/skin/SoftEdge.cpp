#include "skin/SoftEdge.h"

#include "skin/Quadrature.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace preskin::skin {

namespace {
constexpr int kTableSize = 65537;
constexpr double kKernelSigmas = 7.0;  // phi beyond 7 sigma is below 1e-11
}  // namespace

SoftEdge::SoftEdge(const DiffusionProfile& profile) : profile_(profile) {
    if (profile.kind() == DiffusionProfile::Kind::SumOfGaussians) return;
    // The response reaches 0 and 1 to within 1e-12 about 60 widest scales from the edge.
    halfRangeMm_ = 80.0 * profile.maxWidthMm();
    stepMm_ = 2.0 * halfRangeMm_ / (kTableSize - 1);
    table_.resize(kTableSize);
    tbb::parallel_for(0, kTableSize, [&](int i) {
        table_[size_t(i)] = profile.edgeResponse(-halfRangeMm_ + i * stepMm_);
    });
}

glm::dvec3 SoftEdge::tabulated(double xMm) const {
    const double t = (xMm + halfRangeMm_) / stepMm_;
    if (t <= 0.0) return glm::dvec3(0.0);
    if (t >= kTableSize - 1) return glm::dvec3(1.0);
    const size_t i = static_cast<size_t>(t);
    const double f = t - double(i);
    return glm::mix(table_[i], table_[i + 1], f);
}

glm::dvec3 SoftEdge::operator()(double xMm, double sigmaMm) const {
    if (profile_.kind() == DiffusionProfile::Kind::SumOfGaussians) {
        glm::dvec3 sum(0.0);
        for (const auto& g : profile_.gaussians())
            sum += g.weight * (0.5 * std::erfc(-xMm / std::sqrt(2.0 * (g.varianceMm2 + sigmaMm * sigmaMm))));
        return sum / profile_.albedo();
    }
    if (sigmaMm <= stepMm_) return tabulated(xMm);
    // int E(x - t) phi(t) dt over |t| <= 7 sigma, split at t = x where E is steepest, each side
    // on panels graded geometrically towards the split.
    const GaussLegendreRule& rule = gaussLegendre(16);
    const double invNorm = 1.0 / (sigmaMm * std::sqrt(2.0 * 3.14159265358979323846));
    auto integrand = [&](double t) { return tabulated(xMm - t) * (std::exp(-0.5 * t * t / (sigmaMm * sigmaMm)) * invNorm); };
    const double lo = -kKernelSigmas * sigmaMm;
    const double hi = kKernelSigmas * sigmaMm;
    const double split = std::clamp(xMm, lo, hi);
    glm::dvec3 sum(0.0);
    auto graded = [&](double from, double to) {  // panels shrink by 4 towards `to`
        double a = from;
        for (int level = 0; level < 4; ++level) {
            const double b = level == 3 ? to : a + 0.75 * (to - a);
            if (b != a) sum += integrateGaussLegendre<glm::dvec3>(rule, std::min(a, b), std::max(a, b), integrand);
            a = b;
        }
    };
    graded(lo, split);
    graded(hi, split);
    // Beyond the kernel's reach E(x - t) is weighted by phi < 1e-11: ignored.
    return glm::clamp(sum, 0.0, 1.0);
}

}  // namespace preskin::skin
