// CPU texture sampling matching the renderer's samplers (see ReferenceTexture.h).
#include "ReferenceTexture.h"

#include <algorithm>
#include <cmath>

namespace preskin::reference {
namespace {

int64_t wrapIndex(int64_t i, int64_t size, Wrap wrap) {
    switch (wrap) {
    case Wrap::ClampToEdge: return std::clamp<int64_t>(i, 0, size - 1);
    case Wrap::MirroredRepeat: {
        const int64_t period = 2 * size;
        int64_t m = ((i % period) + period) % period;
        return m < size ? m : period - 1 - m;
    }
    default: return ((i % size) + size) % size;
    }
}

}  // namespace

double srgbToLinear(double encoded) {
    return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

ReferenceTexture::ReferenceTexture(const Image& image, const Sampler& sampler, bool srgb) : sampler_(sampler) {
    Level base;
    base.width = std::max(image.width, 1u);
    base.height = std::max(image.height, 1u);
    base.texels.resize(size_t(base.width) * base.height, glm::vec4(1.0f));
    if (image.rgba8.size() == size_t(image.width) * image.height * 4) {
        double table[256];
        for (int i = 0; i < 256; ++i) table[i] = srgb ? srgbToLinear(i / 255.0) : i / 255.0;
        for (size_t i = 0; i < base.texels.size() && image.width > 0; ++i) {
            const uint8_t* p = &image.rgba8[4 * i];
            base.texels[i] = glm::vec4(float(table[p[0]]), float(table[p[1]]), float(table[p[2]]), float(p[3] / 255.0));
        }
    }
    levels_.push_back(std::move(base));
    while (sampler.mipmaps && (levels_.back().width > 1 || levels_.back().height > 1)) {
        const Level& src = levels_.back();
        Level dst;
        dst.width = std::max(src.width / 2, 1u);
        dst.height = std::max(src.height / 2, 1u);
        dst.texels.resize(size_t(dst.width) * dst.height);
        for (uint32_t y = 0; y < dst.height; ++y)
            for (uint32_t x = 0; x < dst.width; ++x) {
                const uint32_t x0 = std::min(2 * x, src.width - 1), x1 = std::min(2 * x + 1, src.width - 1);
                const uint32_t y0 = std::min(2 * y, src.height - 1), y1 = std::min(2 * y + 1, src.height - 1);
                dst.texels[size_t(y) * dst.width + x] = 0.25f *
                    (src.texels[size_t(y0) * src.width + x0] + src.texels[size_t(y0) * src.width + x1] +
                     src.texels[size_t(y1) * src.width + x0] + src.texels[size_t(y1) * src.width + x1]);
            }
        levels_.push_back(std::move(dst));
    }
}

glm::dvec4 ReferenceTexture::texel(const Level& level, int64_t x, int64_t y) const {
    const int64_t xi = wrapIndex(x, level.width, sampler_.wrapU);
    const int64_t yi = wrapIndex(y, level.height, sampler_.wrapV);
    return glm::dvec4(level.texels[size_t(yi) * level.width + size_t(xi)]);
}

glm::dvec4 ReferenceTexture::nearest(const Level& level, const glm::dvec2& uv) const {
    return texel(level, int64_t(std::floor(uv.x * level.width)), int64_t(std::floor(uv.y * level.height)));
}

glm::dvec4 ReferenceTexture::bilinear(const Level& level, const glm::dvec2& uv) const {
    const double x = uv.x * level.width - 0.5;
    const double y = uv.y * level.height - 0.5;
    const double fx = std::floor(x), fy = std::floor(y);
    const double ax = x - fx, ay = y - fy;
    const auto x0 = int64_t(fx), y0 = int64_t(fy);
    return (1.0 - ay) * ((1.0 - ax) * texel(level, x0, y0) + ax * texel(level, x0 + 1, y0)) +
        ay * ((1.0 - ax) * texel(level, x0, y0 + 1) + ax * texel(level, x0 + 1, y0 + 1));
}

glm::dvec4 ReferenceTexture::sample(const glm::dvec2& uv, const glm::dvec2& duvDx, const glm::dvec2& duvDy) const {
    if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) return glm::dvec4(0.0);
    const Level& base = levels_.front();
    const glm::dvec2 size(base.width, base.height);
    const double rho = std::max(glm::length(duvDx * size), glm::length(duvDy * size));
    const double lambda = rho > 0.0 ? std::log2(rho) : -1.0;
    if (lambda <= 0.0 || levels_.size() == 1) {
        const Filter filter = lambda <= 0.0 ? sampler_.magFilter : sampler_.minFilter;
        return filter == Filter::Nearest ? nearest(base, uv) : bilinear(base, uv);
    }
    const double d = std::min(lambda, double(levels_.size() - 1));
    auto at = [&](size_t level) {
        return sampler_.minFilter == Filter::Nearest ? nearest(levels_[level], uv) : bilinear(levels_[level], uv);
    };
    if (sampler_.mipFilter == Filter::Nearest)
        return at(size_t(std::min(std::floor(d + 0.5), double(levels_.size() - 1))));
    const size_t lo = size_t(std::floor(d));
    const size_t hi = std::min(lo + 1, levels_.size() - 1);
    const double t = d - double(lo);
    return (1.0 - t) * at(lo) + t * at(hi);
}

}  // namespace preskin::reference
