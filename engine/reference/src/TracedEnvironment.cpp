// The environment's traced irradiance for the diffusion reference (see TracedEnvironment.h).
#include "TracedEnvironment.h"
#include "PointHash.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace preskin::reference {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr uint32_t kMaxCellsX = 512, kMaxCellsY = 256;

double luminance(const glm::vec3& c) { return 0.2126 * double(c.r) + 0.7152 * double(c.g) + 0.0722 * double(c.b); }

double radicalInverse(uint32_t i) {
    i = (i << 16u) | (i >> 16u);
    i = ((i & 0x55555555u) << 1u) | ((i & 0xAAAAAAAAu) >> 1u);
    i = ((i & 0x33333333u) << 2u) | ((i & 0xCCCCCCCCu) >> 2u);
    i = ((i & 0x0F0F0F0Fu) << 4u) | ((i & 0xF0F0F0F0u) >> 4u);
    i = ((i & 0x00FF00FFu) << 8u) | ((i & 0xFF00FF00u) >> 8u);
    return double(i) * (1.0 / 4294967296.0);
}

// Index i of the interval of a cumulative table (cdf[0] = 0, cdf.back() = 1) holding u, and u's
// place within it in [0, 1).
size_t pick(const std::vector<double>& cdf, double u, double& within) {
    const auto it = std::upper_bound(cdf.begin(), cdf.end() - 1, u);
    size_t i = size_t(std::max<std::ptrdiff_t>(it - cdf.begin() - 1, 0));
    while (i + 1 < cdf.size() - 1 && !(cdf[i + 1] > cdf[i])) ++i;  // skip empty intervals
    const double width = cdf[i + 1] - cdf[i];
    within = width > 0.0 ? std::clamp((u - cdf[i]) / width, 0.0, std::nextafter(1.0, 0.0)) : 0.5;
    return i;
}

}  // namespace

TracedEnvironment::TracedEnvironment(const Environment& environment, uint32_t samples)
    : environment_(environment), samples_(std::max(samples, 2u)) {
    const EquirectImage& image = environment.image();
    image_ = image.width > 0 && image.height > 0;
    if (!image_) return;
    cellsX_ = std::min(image.width, kMaxCellsX);
    cellsY_ = std::min(image.height, kMaxCellsY);
    std::vector<double> weight(size_t(cellsX_) * cellsY_, 0.0);
    for (uint32_t y = 0; y < image.height; ++y) {
        const uint32_t cy = uint32_t(uint64_t(y) * cellsY_ / image.height);
        for (uint32_t x = 0; x < image.width; ++x) {
            const uint32_t cx = uint32_t(uint64_t(x) * cellsX_ / image.width);
            weight[size_t(cy) * cellsX_ + cx] += luminance(image.texel(x, y));  // the cell's radiance sum
        }
    }
    // A cell's probability: its mean radiance times its solid angle.
    double total = 0.0;
    for (uint32_t cy = 0; cy < cellsY_; ++cy) {
        const double theta0 = kPi * cy / cellsY_, theta1 = kPi * (cy + 1) / cellsY_;
        const double solidAngle = 2.0 * kPi / cellsX_ * (std::cos(theta0) - std::cos(theta1));
        const double texels = double(image.width) * image.height / (double(cellsX_) * cellsY_);
        for (uint32_t cx = 0; cx < cellsX_; ++cx) {
            double& w = weight[size_t(cy) * cellsX_ + cx];
            w = std::max(w / texels, 0.0) * solidAngle;
            total += w;
        }
    }
    if (!(total > 0.0)) {  // a black image: cosine samples alone
        image_ = false;
        return;
    }
    cellProbability_.resize(weight.size());
    rowCdf_.assign(cellsY_ + 1, 0.0);
    columnCdf_.assign(cellsY_, std::vector<double>(cellsX_ + 1, 0.0));
    for (uint32_t cy = 0; cy < cellsY_; ++cy) {
        double row = 0.0;
        for (uint32_t cx = 0; cx < cellsX_; ++cx) {
            const double p = weight[size_t(cy) * cellsX_ + cx] / total;
            cellProbability_[size_t(cy) * cellsX_ + cx] = p;
            row += p;
            columnCdf_[cy][cx + 1] = row;
        }
        for (double& c : columnCdf_[cy]) c = row > 0.0 ? c / row : 0.0;
        columnCdf_[cy].back() = 1.0;
        rowCdf_[cy + 1] = rowCdf_[cy] + row;
    }
    rowCdf_.back() = 1.0;
}

glm::dvec3 TracedEnvironment::sampleImage(double u1, double u2, double& pdf) const {
    double t1 = 0.0, t2 = 0.0;
    const size_t cy = pick(rowCdf_, u1, t1);
    const size_t cx = pick(columnCdf_[cy], u2, t2);
    const double c0 = std::cos(kPi * double(cy) / cellsY_), c1 = std::cos(kPi * double(cy + 1) / cellsY_);
    const double cosTheta = c0 + t1 * (c1 - c0);
    const double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
    const double u = (double(cx) + t2) / cellsX_;
    const double phi = 2.0 * kPi * (u - 0.5);
    const glm::vec3 imageDirection(float(sinTheta * std::cos(phi)), float(cosTheta), float(sinTheta * std::sin(phi)));
    const double solidAngle = 2.0 * kPi / cellsX_ * (c0 - c1);
    pdf = cellProbability_[cy * cellsX_ + cx] / solidAngle;
    return glm::dvec3(rotateY(imageDirection, environment_.rotationY()));
}

double TracedEnvironment::imagePdf(const glm::dvec3& direction) const {
    const glm::vec3 d = rotateY(glm::vec3(direction), -environment_.rotationY());
    const double theta = std::acos(std::clamp(double(d.y), -1.0, 1.0));
    double u = std::atan2(double(d.z), double(d.x)) / (2.0 * kPi) + 0.5;
    u -= std::floor(u);
    const auto cx = std::min(uint32_t(u * cellsX_), cellsX_ - 1);
    const auto cy = std::min(uint32_t(theta / kPi * cellsY_), cellsY_ - 1);
    const double solidAngle =
        2.0 * kPi / cellsX_ * (std::cos(kPi * double(cy) / cellsY_) - std::cos(kPi * double(cy + 1) / cellsY_));
    return cellProbability_[size_t(cy) * cellsX_ + cx] / solidAngle;
}

glm::dvec3 TracedEnvironment::irradiance(const RayScene& rays, const glm::dvec3& origin, const glm::dvec3& normal,
                                         uint64_t key) const {
    const uint64_t h = splitMix64(key);
    const double shiftX = unitInterval(h);
    const double shiftY = unitInterval(splitMix64(h));
    const glm::dvec3 a = std::abs(normal.x) < 0.9 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 1.0, 0.0);
    const glm::dvec3 tangent = glm::normalize(glm::cross(a, normal)), bitangent = glm::cross(normal, tangent);
    const uint32_t cosineCount = image_ ? samples_ / 2 : samples_;
    const uint32_t imageCount = samples_ - cosineCount;
    glm::dvec3 sum(0.0);
    auto add = [&](const glm::dvec3& w) {
        const double cosine = glm::dot(w, normal);
        if (!(cosine > 0.0)) return;
        const double density = cosineCount * cosine / kPi + (image_ ? imageCount * imagePdf(w) : 0.0);
        if (!(density > 0.0)) return;
        if (rays.occluded(origin, w, 0.0, std::numeric_limits<double>::infinity())) return;
        sum += glm::dvec3(environment_.radiance(glm::vec3(w))) * (cosine / density);
    };
    // Each strategy its own Hammersley set (its own count), rotated by the key.
    auto point = [&](uint32_t j, uint32_t count, double& x, double& y) {
        x = (double(j) + 0.5) / count + shiftX;
        y = radicalInverse(j) + shiftY;
        x -= std::floor(x);
        y -= std::floor(y);
    };
    for (uint32_t j = 0; j < cosineCount; ++j) {
        double x = 0.0, y = 0.0;
        point(j, cosineCount, x, y);
        const double r = std::sqrt(y), phi = 2.0 * kPi * x;
        add(tangent * (r * std::cos(phi)) + bitangent * (r * std::sin(phi)) +
            normal * std::sqrt(std::max(0.0, 1.0 - y)));
    }
    for (uint32_t j = 0; j < imageCount; ++j) {
        double x = 0.0, y = 0.0, pdf = 0.0;
        point(j, imageCount, x, y);
        add(sampleImage(x, y, pdf));
    }
    return sum;
}

}  // namespace preskin::reference
