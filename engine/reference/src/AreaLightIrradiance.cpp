// Irradiance from area lights for the diffusion reference (see AreaLightIrradiance.h).
#include "AreaLightIrradiance.h"

#include <preskin/LightRecord.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

namespace preskin::reference {

namespace {

constexpr double kPi = std::numbers::pi;

double rangeWindow(double d2, double range) {
    if (!(range > 0.0)) return 1.0;
    const double r = d2 / (range * range);
    const double w = std::clamp(1.0 - r * r, 0.0, 1.0);
    return w * w;
}

// The capsule's facing surface: sum of cos cos' / r^2 dA (midpoint rule).
double capsuleCosineIntegral(const glm::dvec3& c, const glm::dvec3& u, double halfLength, double radius,
                             const glm::dvec3& y, const glm::dvec3& n) {
    const glm::dvec3 e1 =
        glm::normalize(glm::cross(u, std::abs(u.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
    const glm::dvec3 e2 = glm::cross(u, e1);
    double sum = 0.0;
    const auto add = [&](const glm::dvec3& q, const glm::dvec3& m, double area) {
        const glm::dvec3 w = q - y;
        const double d2 = glm::dot(w, w);
        const double cy = glm::dot(n, w), cl = -glm::dot(m, w);
        if (cy > 0.0 && cl > 0.0) sum += cy * cl / (d2 * d2) * area;
    };
    const int around = 128, along = 64, polar = 32, azimuth = 64;
    for (int j = 0; j < around; ++j) {
        const double phi = 2.0 * kPi * (j + 0.5) / around;
        const glm::dvec3 m = std::cos(phi) * e1 + std::sin(phi) * e2;
        for (int i = 0; i < along; ++i) {
            const double t = -halfLength + 2.0 * halfLength * (i + 0.5) / along;
            add(c + u * t + radius * m, m, radius * (2.0 * kPi / around) * (2.0 * halfLength / along));
        }
    }
    for (int end = -1; end <= 1; end += 2) {
        const glm::dvec3 pole = double(end) * u;
        for (int i = 0; i < polar; ++i) {
            const double th = 0.5 * kPi * (i + 0.5) / polar;
            for (int j = 0; j < azimuth; ++j) {
                const double phi = 2.0 * kPi * (j + 0.5) / azimuth;
                const glm::dvec3 m = std::cos(th) * pole + std::sin(th) * (std::cos(phi) * e1 + std::sin(phi) * e2);
                add(c + pole * halfLength + radius * m, m,
                    radius * radius * std::sin(th) * (0.5 * kPi / polar) * (2.0 * kPi / azimuth));
            }
        }
    }
    return sum;
}

}  // namespace

double capCosineIntegral(double cosTheta, double sigma) {
    const double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
    const int intervals = 1024;
    const double h = sigma / intervals;
    double sum = 0.0;
    for (int i = 0; i <= intervals; ++i) {
        const double r = i * h;
        const double a = std::cos(r) * cosTheta, b = std::sin(r) * sinTheta;
        double ring;  // int_0^2pi max(a + b cos(phi), 0) dphi
        if (a >= b)
            ring = 2.0 * kPi * a;
        else if (a <= -b)
            ring = 0.0;
        else {
            const double phi0 = std::acos(std::clamp(-a / b, -1.0, 1.0));
            ring = 2.0 * (a * phi0 + b * std::sin(phi0));
        }
        const double weight = (i == 0 || i == intervals) ? 1.0 : (i % 2 ? 4.0 : 2.0);
        sum += weight * ring * std::sin(r);
    }
    return sum * h / 3.0;
}

double polygonCosineIntegral(const glm::dvec3* corners, int count, const glm::dvec3& y, const glm::dvec3& n) {
    // Clip by the tangent plane (Sutherland-Hodgman), corners relative to y.
    std::vector<glm::dvec3> in(corners, corners + count), out;
    for (glm::dvec3& p : in) p -= y;
    for (size_t i = 0; i < in.size(); ++i) {
        const glm::dvec3& a = in[i];
        const glm::dvec3& b = in[(i + 1) % in.size()];
        const double da = glm::dot(a, n), db = glm::dot(b, n);
        if (da >= 0.0) out.push_back(a);
        if ((da >= 0.0) != (db >= 0.0)) out.push_back(a + (b - a) * (da / (da - db)));
    }
    if (out.size() < 3) return 0.0;
    double sum = 0.0;
    for (size_t i = 0; i < out.size(); ++i) {
        const glm::dvec3 a = glm::normalize(out[i]);
        const glm::dvec3 b = glm::normalize(out[(i + 1) % out.size()]);
        const glm::dvec3 c = glm::cross(a, b);
        const double s = glm::length(c);
        if (!(s > 0.0)) continue;
        sum += std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0)) * glm::dot(c / s, n);
    }
    return 0.5 * std::abs(sum);
}

glm::dvec3 areaLightIrradiance(const Light& light, const glm::dvec3& y, const glm::dvec3& n) {
    if (light.type == LightType::Directional) {
        const double sigma = double(light.angularRadius), s = std::sin(sigma);
        const glm::dvec3 L = -glm::normalize(glm::dvec3(light.directionWs));
        return glm::dvec3(light.color) * double(light.intensity) *
            (capCosineIntegral(glm::dot(n, L), sigma) / (kPi * s * s));
    }
    const glm::dvec3 c(light.positionWs);
    const glm::dvec3 toCenter = c - y;
    const double window = rangeWindow(glm::dot(toCenter, toCenter), double(light.range));
    const glm::dvec3 intensity = glm::dvec3(light.color) * double(light.intensity) * window;
    const AreaLightAxes axes = areaLightAxes(light);
    const glm::dvec3 m(axes.normal), u(axes.width), v(axes.height);
    const double r = double(light.radius);
    double integral = 0.0, area = 1.0;  // int max(n . omega, 0) dOmega (or cos cos' / r^2 dA); projected area
    switch (light.type) {
    case LightType::Sphere: {
        area = kPi * r * r;
        const double d = glm::length(toCenter);
        if (d <= r) {
            integral = kPi;
            break;
        }
        integral = capCosineIntegral(glm::dot(n, toCenter) / d, std::asin(std::min(r / d, 1.0)));
        break;
    }
    case LightType::Rectangle: {
        area = double(light.width) * double(light.height);
        if (glm::dot(y - c, m) <= 0.0) break;
        const glm::dvec3 hu = u * (0.5 * double(light.width)), hv = v * (0.5 * double(light.height));
        const std::array<glm::dvec3, 4> corners = {c - hu - hv, c + hu - hv, c + hu + hv, c - hu + hv};
        integral = polygonCosineIntegral(corners.data(), 4, y, n);
        break;
    }
    case LightType::Disc: {
        area = kPi * r * r;
        if (glm::dot(y - c, m) <= 0.0) break;
        constexpr int kSides = 256;
        const double rho = r * std::sqrt(2.0 * kPi / (kSides * std::sin(2.0 * kPi / kSides)));
        std::array<glm::dvec3, kSides> corners;
        for (int k = 0; k < kSides; ++k) {
            const double phi = 2.0 * kPi * k / kSides;
            corners[size_t(k)] = c + rho * (std::cos(phi) * u + std::sin(phi) * v);
        }
        integral = polygonCosineIntegral(corners.data(), kSides, y, n);
        break;
    }
    case LightType::Tube:
        area = 2.0 * r * double(light.length) + kPi * r * r;
        integral = capsuleCosineIntegral(c, u, 0.5 * double(light.length), r, y, n);
        break;
    default: break;
    }
    return intensity * (integral / area);
}

}  // namespace preskin::reference
