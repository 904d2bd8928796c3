// The environment's dominant lights by median cut; see extractEnvironmentLights in
// <preskin/Environment.h>.
#include <preskin/Environment.h>
#include <preskin/Error.h>

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <queue>

namespace preskin {

namespace {

constexpr uint32_t kWorkWidth = 1024;         // the widest image the search runs on
constexpr int kCutDepth = 6;                  // 2^6 = 64 median-cut regions
constexpr double kMinContrast = 4.0;          // a seed region's mean radiance over the environment's
constexpr float kGrowFraction = 0.1f;         // a light's texels: at least this fraction of its peak
constexpr double kMaxLightSolidAngle = 0.25;  // sr

float luminance(const glm::vec3& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

// The image box-filtered to at most kWorkWidth texels wide (boxFiltered), with every row's texel
// solid angle.
struct WorkImage {
    uint32_t width = 0, height = 0;
    std::vector<glm::vec3> radiance;
    std::vector<double> rowSolidAngle;
    glm::vec3 at(uint32_t x, uint32_t y) const { return radiance[size_t(y) * width + x]; }
    glm::vec3 direction(uint32_t x, uint32_t y) const {
        return EquirectImage::directionAt((float(x) + 0.5f) / float(width), (float(y) + 0.5f) / float(height));
    }
};

WorkImage workImage(const EquirectImage& source) {
    const EquirectImage image = boxFiltered(source, kWorkWidth);
    WorkImage w;
    w.width = image.width;
    w.height = image.height;
    w.radiance.resize(size_t(w.width) * w.height);
    for (uint32_t y = 0; y < w.height; ++y)
        for (uint32_t x = 0; x < w.width; ++x) w.radiance[size_t(y) * w.width + x] = image.texel(x, y);
    w.rowSolidAngle.resize(w.height);
    for (uint32_t y = 0; y < w.height; ++y)
        w.rowSolidAngle[y] =
            2.0 * M_PI / w.width * (std::cos(M_PI * y / w.height) - std::cos(M_PI * (y + 1) / w.height));
    return w;
}

struct Region {
    uint32_t x0, x1, y0, y1;  // [x0, x1) x [y0, y1)
};

// Summed-area table of luminous energy (luminance times solid angle) per texel.
class EnergyTable {
public:
    explicit EnergyTable(const WorkImage& image)
        : width_(image.width + 1), sum_(size_t(image.width + 1) * (image.height + 1), 0.0) {
        for (uint32_t y = 0; y < image.height; ++y) {
            double row = 0.0;
            for (uint32_t x = 0; x < image.width; ++x) {
                row += double(luminance(image.at(x, y))) * image.rowSolidAngle[y];
                sum_[size_t(y + 1) * width_ + x + 1] = sum_[size_t(y) * width_ + x + 1] + row;
            }
        }
    }
    double energy(const Region& r) const { return at(r.x1, r.y1) - at(r.x0, r.y1) - at(r.x1, r.y0) + at(r.x0, r.y0); }

private:
    double at(uint32_t x, uint32_t y) const { return sum_[size_t(y) * width_ + x]; }
    size_t width_;
    std::vector<double> sum_;
};

// Debevec's median cut: each region is split across its longer side (longitude measured at the
// region's middle latitude) where half its energy lies on either side.
std::vector<Region> medianCut(const WorkImage& image, const EnergyTable& table) {
    std::vector<Region> regions{{0, image.width, 0, image.height}};
    for (int depth = 0; depth < kCutDepth; ++depth) {
        std::vector<Region> next;
        for (const Region& r : regions) {
            const double theta = M_PI * 0.5 * (r.y0 + r.y1) / image.height;
            const double across = 2.0 * M_PI * (r.x1 - r.x0) / image.width * std::sin(theta);
            const double down = M_PI * (r.y1 - r.y0) / image.height;
            const bool cutColumns = (across >= down && r.x1 - r.x0 > 1) || r.y1 - r.y0 <= 1;
            if ((cutColumns && r.x1 - r.x0 <= 1) || (!cutColumns && r.y1 - r.y0 <= 1)) {
                next.push_back(r);
                continue;
            }
            const double half = 0.5 * table.energy(r);
            uint32_t lo = cutColumns ? r.x0 + 1 : r.y0 + 1;
            uint32_t hi = cutColumns ? r.x1 - 1 : r.y1 - 1;
            while (lo < hi) {  // the first cut with at least half the energy before it
                const uint32_t mid = (lo + hi) / 2;
                const Region before = cutColumns ? Region{r.x0, mid, r.y0, r.y1} : Region{r.x0, r.x1, r.y0, mid};
                if (table.energy(before) >= half)
                    hi = mid;
                else
                    lo = mid + 1;
            }
            if (cutColumns) {
                next.push_back({r.x0, lo, r.y0, r.y1});
                next.push_back({lo, r.x1, r.y0, r.y1});
            } else {
                next.push_back({r.x0, r.x1, r.y0, lo});
                next.push_back({r.x0, r.x1, lo, r.y1});
            }
        }
        regions = std::move(next);
    }
    return regions;
}

double solidAngle(const WorkImage& image, const Region& r) {
    double sum = 0.0;
    for (uint32_t y = r.y0; y < r.y1; ++y) sum += image.rowSolidAngle[y];
    return sum * (r.x1 - r.x0);
}

}  // namespace

EnvironmentLights extractEnvironmentLights(const Environment& environment, uint32_t count) {
    if (count > kMaxEnvironmentLights)
        throw Error(fmt::format("environment lights: {} asked for, at most {}", count, kMaxEnvironmentLights));
    EnvironmentLights result;
    result.residualSh = environment.radianceSh();
    const EquirectImage& source = environment.image();
    if (source.width == 0 || source.height == 0) return result;

    WorkImage image = workImage(source);
    const float rotationY = environment.rotationY();
    for (uint32_t light = 0; light < count; ++light) {
        const EnergyTable table(image);
        const Region whole{0, image.width, 0, image.height};
        const double meanRadiance = table.energy(whole) / (4.0 * M_PI);
        if (!(meanRadiance > 0.0)) break;
        // The seed: the region of highest mean radiance.
        Region seed{};
        double seedDensity = 0.0;
        for (const Region& r : medianCut(image, table)) {
            const double density = table.energy(r) / std::max(solidAngle(image, r), 1e-12);
            if (density > seedDensity) {
                seedDensity = density;
                seed = r;
            }
        }
        if (seedDensity < kMinContrast * meanRadiance) break;
        uint32_t peakX = seed.x0, peakY = seed.y0;
        for (uint32_t y = seed.y0; y < seed.y1; ++y)
            for (uint32_t x = seed.x0; x < seed.x1; ++x)
                if (luminance(image.at(x, y)) > luminance(image.at(peakX, peakY))) {
                    peakX = x;
                    peakY = y;
                }
        const float threshold = kGrowFraction * luminance(image.at(peakX, peakY));

        // Grow brightest first over 8-connected texels (longitude wraps) above the threshold.
        using Entry = std::pair<float, uint32_t>;  // luminance, texel index
        std::priority_queue<Entry> frontier;
        std::vector<uint8_t> seen(image.radiance.size(), 0);
        const auto push = [&](uint32_t x, uint32_t y) {
            const size_t i = size_t(y) * image.width + x;
            if (seen[i]) return;
            seen[i] = 1;
            const float l = luminance(image.radiance[i]);
            if (l >= threshold) frontier.push({l, uint32_t(i)});
        };
        push(peakX, peakY);
        EnvironmentLight out;
        glm::dvec3 irradiance(0.0), weightedDirection(0.0);
        double omega = 0.0;
        std::vector<uint32_t> texels;
        while (!frontier.empty() && omega < kMaxLightSolidAngle) {
            const uint32_t i = frontier.top().second;
            frontier.pop();
            const uint32_t x = i % image.width, y = i / image.width;
            const double texelOmega = image.rowSolidAngle[y];
            const glm::dvec3 radiance(image.radiance[i]);
            irradiance += radiance * texelOmega;
            weightedDirection +=
                glm::dvec3(image.direction(x, y)) * (double(luminance(image.radiance[i])) * texelOmega);
            omega += texelOmega;
            texels.push_back(i);
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int ny = int(y) + dy;
                    if (ny < 0 || ny >= int(image.height)) continue;
                    push(uint32_t((int(x) + dx + int(image.width)) % int(image.width)), uint32_t(ny));
                }
        }
        if (glm::length(weightedDirection) <= 0.0) break;
        const glm::vec3 towards = rotateY(glm::vec3(glm::normalize(weightedDirection)), rotationY);
        out.directionWs = -towards;
        out.irradiance = glm::vec3(irradiance);
        out.solidAngleSr = float(omega);
        // The spread about the direction (before the rotation, which keeps angles).
        const glm::dvec3 centre = glm::normalize(weightedDirection);
        double spread = 0.0, weight = 0.0;
        for (uint32_t i : texels) {
            const uint32_t x = i % image.width, y = i / image.width;
            const glm::dvec3 d(image.direction(x, y));
            const double theta = std::atan2(glm::length(glm::cross(d, centre)), glm::dot(d, centre));
            const double w = double(luminance(image.radiance[i])) * image.rowSolidAngle[y];
            spread += w * theta * theta;
            weight += w;
        }
        out.angularRadius =
            weight > 0.0 ? float(std::min(std::sqrt(2.0 * spread / weight), 0.25 * std::numbers::pi)) : 0.0f;
        // Its texels leave the image and the SH.
        for (uint32_t i : texels) {
            const uint32_t x = i % image.width, y = i / image.width;
            const auto basis = shBasis(rotateY(image.direction(x, y), rotationY));
            const glm::vec3 removed = image.radiance[i] * float(image.rowSolidAngle[y]);
            for (size_t c = 0; c < 9; ++c) result.residualSh.c[c] -= removed * basis[c];
            image.radiance[i] = glm::vec3(0.0f);
        }
        result.lights.push_back(out);
    }
    result.residualImage.width = image.width;
    result.residualImage.height = image.height;
    result.residualImage.rgb.reserve(image.radiance.size() * 3);
    for (const glm::vec3& l : image.radiance)
        result.residualImage.rgb.insert(result.residualImage.rgb.end(), {l.r, l.g, l.b});
    std::stable_sort(result.lights.begin(), result.lights.end(),
                     [](const EnvironmentLight& a, const EnvironmentLight& b) {
                         return luminance(a.irradiance) > luminance(b.irradiance);
                     });
    return result;
}

}  // namespace preskin
