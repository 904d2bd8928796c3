// The diffuse response on a sphere (convex) or a concave patch, and the SH transfer (method and
// sources: SphereScatter.h).
#include "skin/SphereScatter.h"

#include "skin/LutLayout.h"
#include "skin/Quadrature.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace preskin::skin {
namespace {

constexpr double kPi = std::numbers::pi;

// Gauss-Legendre nodes in psi with the kernel weight W(psi) folded into each node's weight.
struct KernelNodes {
    std::vector<double> cosPsi;
    std::vector<double> sinPsi;
    std::vector<glm::dvec3> weight;  // quadrature weight * a^2 Rn(chord) sin(psi)
    glm::dvec3 total{0.0};           // 2 pi sum(weight): the profile's integral over the surface
};

KernelNodes kernelNodes(const DiffusionProfile& profile, double radiusMm, double psiEnd) {
    const glm::dvec3 invAlbedo = 1.0 / profile.albedo();
    const double uniform = psiEnd / 64.0;
    std::vector<double> breaks{0.0};
    for (double psi = 1e-3 * profile.narrowestScaleMm() / radiusMm; psi < uniform; psi *= 1.5) breaks.push_back(psi);
    for (int j = 1; j <= 64; ++j) breaks.push_back(uniform * j);
    const GaussLegendreRule& rule = gaussLegendre(8);
    KernelNodes nodes;
    for (size_t k = 0; k + 1 < breaks.size(); ++k) {
        const double half = 0.5 * (breaks[k + 1] - breaks[k]), mid = 0.5 * (breaks[k + 1] + breaks[k]);
        for (size_t i = 0; i < rule.nodes.size(); ++i) {
            const double psi = mid + half * rule.nodes[i];
            const double chord = 2.0 * radiusMm * std::sin(0.5 * psi);
            nodes.cosPsi.push_back(std::cos(psi));
            nodes.sinPsi.push_back(std::sin(psi));
            const glm::dvec3 w = (half * rule.weights[i]) * radiusMm * radiusMm * std::sin(psi) *
                profile.R(std::max(chord, 1e-12)) * invAlbedo;
            nodes.weight.push_back(w);
            nodes.total += 2.0 * kPi * w;
        }
    }
    return nodes;
}

// int_0^2pi (A + B cos(phi)) [A + B cos(phi) > tau] dphi for B >= 0, tau >= 0.
double azimuthal(double A, double B, double tau) {
    if (A - B >= tau) return 2.0 * kPi * A;
    if (A + B <= tau) return 0.0;
    const double x = std::clamp((tau - A) / B, -1.0, 1.0);         // cos(phi) at the limit
    return 2.0 * (A * std::acos(x) + B * std::sqrt(1.0 - x * x));  // sin(acos(x)) = sqrt(1 - x^2)
}

// The psi range that matters: the chord out to the profile's reach, and for a concave patch its
// arc radius.
double psiEnd(const DiffusionProfile& profile, double radiusMm) {
    const double reach = profile.reachMm(kTransmittanceFloor);
    return reach >= 2.0 * radiusMm ? kPi : 2.0 * std::asin(reach / (2.0 * radiusMm));
}

}  // namespace

void sphereScatter(const DiffusionProfile& profile, double curvaturePerMm, double patchMm, std::span<const double> NoL,
                   std::span<glm::dvec3> out) {
    if (curvaturePerMm == 0.0 || !std::isfinite(curvaturePerMm)) {
        for (size_t i = 0; i < NoL.size(); ++i) out[i] = glm::dvec3(std::clamp(NoL[i], 0.0, 1.0));
        return;
    }
    const bool concave = curvaturePerMm < 0.0;
    const double radiusMm = 1.0 / std::abs(curvaturePerMm);
    const double cosPatch = std::cos(std::min(patchMm / radiusMm, kPi));
    const KernelNodes nodes = kernelNodes(profile, radiusMm, psiEnd(profile, radiusMm));
    for (size_t n = 0; n < NoL.size(); ++n) {
        const double c = std::clamp(NoL[n], -1.0, 1.0);
        const double s = std::sqrt(std::max(0.0, 1.0 - c * c));
        glm::dvec3 sum(0.0);
        for (size_t i = 0; i < nodes.weight.size(); ++i) {
            const double A = c * nodes.cosPsi[i], B = s * nodes.sinPsi[i];
            double phi = 0.0;
            if (!concave) {
                phi = azimuthal(A, B, 0.0);
            } else {
                // Visible where 2 u cos(theta) > cos(psi) - cos(patch), u = n_y . L > 0.
                const double gap = nodes.cosPsi[i] - cosPatch;
                if (c > 0.0)
                    phi = azimuthal(A, B, std::max(0.0, gap / (2.0 * c)));
                else if (c < 0.0 && gap < 0.0)
                    phi = azimuthal(A, B, 0.0) - azimuthal(A, B, gap / (2.0 * c));
                else if (c == 0.0 && gap < 0.0)
                    phi = azimuthal(A, B, 0.0);
            }
            if (phi != 0.0) sum += nodes.weight[i] * phi;
        }
        out[n] = glm::max(sum / nodes.total, glm::dvec3(0.0));
    }
}

glm::dvec3 sphereScatter(const DiffusionProfile& profile, double curvaturePerMm, double patchMm, double NoL) {
    glm::dvec3 result;
    sphereScatter(profile, curvaturePerMm, patchMm, std::span<const double>(&NoL, 1),
                  std::span<glm::dvec3>(&result, 1));
    return result;
}

std::array<glm::dvec3, 3> shTransfer(const DiffusionProfile& profile, double curvaturePerMm) {
    const double k = std::abs(curvaturePerMm);
    std::array<glm::dvec3, 3> a{};
    if (!(k > 0.0) || !std::isfinite(k)) {
        for (size_t l = 0; l < 3; ++l) a[l] = glm::dvec3(kLambertZonal[l]);
        return a;
    }
    const double radiusMm = 1.0 / k;
    const KernelNodes nodes = kernelNodes(profile, radiusMm, psiEnd(profile, radiusMm));
    std::array<glm::dvec3, 3> g{glm::dvec3(0.0), glm::dvec3(0.0), glm::dvec3(0.0)};
    for (size_t i = 0; i < nodes.weight.size(); ++i) {
        const double m = nodes.cosPsi[i];
        const double legendre[3] = {1.0, m, 0.5 * (3.0 * m * m - 1.0)};
        for (size_t l = 0; l < 3; ++l) g[l] += nodes.weight[i] * legendre[l];
    }
    for (size_t l = 0; l < 3; ++l) a[l] = kLambertZonal[l] * g[l] / g[0];
    return a;
}

}  // namespace preskin::skin
