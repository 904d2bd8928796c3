#include "ComparePicture.h"
#include "Canvas.h"

#include <preskin/Renderer.h>
#include <preskin/Tonemap.h>

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace preskin::cli {
namespace {

uint8_t encodeSrgb(double linear) {
    const double c = std::clamp(linear, 0.0, 1.0);
    const double e = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
    return uint8_t(std::lround(e * 255.0));
}

glm::u8vec3 heat(double t) {
    static const std::array<glm::dvec3, 5> stops{glm::dvec3(0.0, 0.0, 0.0), glm::dvec3(0.15, 0.2, 0.8),
                                                 glm::dvec3(0.8, 0.2, 0.7), glm::dvec3(1.0, 0.6, 0.1),
                                                 glm::dvec3(1.0, 1.0, 1.0)};
    const double x = std::clamp(t, 0.0, 1.0) * double(stops.size() - 1);
    const size_t i = std::min(size_t(x), stops.size() - 2);
    const glm::dvec3 c = glm::mix(stops[i], stops[i + 1], x - double(i));
    return glm::u8vec3(glm::round(c * 255.0));
}

double pixelError(const std::vector<float>& image, const ReferenceImage& reference, size_t i) {
    double sum = 0.0;
    for (size_t c = 0; c < 3; ++c) {
        const double d = double(image[4 * i + c]) - double(reference.rgba32f[4 * i + c]);
        sum += d * d;
    }
    return std::sqrt(sum / 3.0);
}

}  // namespace

void writeComparePicture(const std::filesystem::path& path, const std::string& title, const ReferenceImage& reference,
                         const std::vector<float>& skin, const std::vector<float>& lambert,
                         const std::vector<Region>& regions) {
    const int w = int(reference.width), h = int(reference.height);
    const int font = w >= 240 ? 2 : 1;  // font pixels per glyph pixel
    const int margin = 8, label = 12 * font, titleBand = 14 * font;
    Canvas c(uint32_t(3 * w + 4 * margin), uint32_t(titleBand + 2 * (h + label) + 3 * margin));
    c.fill(0, 0, int(c.width) - 1, int(c.height) - 1, glm::u8vec3(255));
    const glm::u8vec3 ink(30, 30, 30);
    const Region& all = regions[0];

    std::vector<double> lambertErrors;
    for (size_t i = 0; i < all.mask.size(); ++i)
        if (all.mask[i]) lambertErrors.push_back(pixelError(lambert, reference, i));
    double scale = 1e-6;
    if (!lambertErrors.empty()) {
        const size_t k = std::min(lambertErrors.size() - 1, size_t(0.99 * double(lambertErrors.size())));
        std::nth_element(lambertErrors.begin(), lambertErrors.begin() + std::ptrdiff_t(k), lambertErrors.end());
        scale = std::max(lambertErrors[k], scale);
    }

    auto panel = [&](int column, int row, const std::string& name, auto&& colorAt) {
        const int x0 = margin + column * (w + margin);
        const int y0 = titleBand + margin + row * (h + label + margin);
        c.text(x0, y0 + 2, name, font, ink);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) c.set(x0 + x, y0 + label + y, colorAt(size_t(y) * size_t(w) + size_t(x)));
    };
    auto toned = [&](const std::vector<float>& image) {
        return [&image](size_t i) {
            const glm::dvec3 t =
                tonemapNeutral(glm::max(glm::dvec3(image[4 * i], image[4 * i + 1], image[4 * i + 2]), glm::dvec3(0.0)));
            return glm::u8vec3(encodeSrgb(t.r), encodeSrgb(t.g), encodeSrgb(t.b));
        };
    };
    panel(0, 0, "reference", toned(reference.rgba32f));
    panel(1, 0, "skin", toned(skin));
    panel(2, 0, "lambert", toned(lambert));
    panel(0, 1, "regions", [&](size_t i) {
        if (!(reference.rgba32f[4 * i + 3] > 0.0f)) return glm::u8vec3(40);
        if (!all.mask[i]) return glm::u8vec3(90);
        glm::dvec3 col(150.0);
        if (regions[3].mask[i]) col = glm::dvec3(90, 170, 90);
        if (regions[2].mask[i]) col = glm::dvec3(80, 120, 210);
        if (regions[1].mask[i]) col = glm::mix(col, glm::dvec3(230, 50, 40), 0.7);
        if (regions[7].mask[i]) col = glm::mix(col, glm::dvec3(240, 210, 60), 0.7);
        return glm::u8vec3(col);
    });
    c.text(margin, 4, fmt::format("{}; error white at {:.3g}", title, scale), font, ink);
    panel(1, 1, "skin error",
          [&](size_t i) { return all.mask[i] ? heat(pixelError(skin, reference, i) / scale) : glm::u8vec3(40); });
    panel(2, 1, "lambert error",
          [&](size_t i) { return all.mask[i] ? heat(pixelError(lambert, reference, i) / scale) : glm::u8vec3(40); });

    c.writePng(path);
}

}  // namespace preskin::cli
