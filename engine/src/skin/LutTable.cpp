// LutTable and LutAxis: axis mappings, the CPU bilinear sampler (Vulkan's LINEAR +
// CLAMP_TO_EDGE rule, Vulkan spec "Texel Filtering"), half-float export and the FNV-1a content
// hash (Fowler, Noll & Vo; 64-bit offset basis 14695981039346656037, prime 1099511628211).
// Limits: see LutTable.h.
#include <preskin/Error.h>
#include <preskin/LutTable.h>

#include "skin/Half.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace preskin {

const char* axisMappingName(AxisMapping mapping) {
    switch (mapping) {
    case AxisMapping::Linear: return "linear";
    case AxisMapping::SplitLinear: return "splitLinear";
    case AxisMapping::Sqrt: return "sqrt";
    case AxisMapping::SplitSqrt: return "splitSqrt";
    case AxisMapping::Rational: return "rational";
    case AxisMapping::Log1p: return "log1p";
    case AxisMapping::Index: return "index";
    }
    return "unknown";
}

double LutAxis::valueAt(int node) const {
    const int last = size - 1;
    const double t = last > 0 ? static_cast<double>(node) / last : 0.0;
    switch (mapping) {
    case AxisMapping::Linear: return min + (max - min) * t;
    case AxisMapping::SplitLinear: {
        const int zero = size / 2;
        if (node < zero) return min * (1.0 - static_cast<double>(node) / zero);
        return max * static_cast<double>(node - zero) / (last - zero);
    }
    case AxisMapping::Sqrt: return min + (max - min) * t * t;
    case AxisMapping::SplitSqrt: {
        const int zero = size / 2;
        if (node < zero) {
            const double f = 1.0 - static_cast<double>(node) / zero;
            return min * f * f;
        }
        const double f = static_cast<double>(node - zero) / (last - zero);
        return max * f * f;
    }
    case AxisMapping::Rational: return node >= last ? std::numeric_limits<double>::infinity() : t / (1.0 - t);
    case AxisMapping::Log1p: return scale * std::expm1(t * std::log1p(max / scale));
    case AxisMapping::Index: return node;
    }
    return 0.0;
}

double LutAxis::nodeCoordinate(double value) const {
    const double last = size - 1;
    double t = 0.0;
    switch (mapping) {
    case AxisMapping::Linear: t = last * (value - min) / (max - min); break;
    case AxisMapping::SplitLinear: {
        const int zero = size / 2;
        t = value < 0.0 ? zero * (value - min) / -min : zero + (last - zero) * value / max;
        break;
    }
    case AxisMapping::Sqrt: t = last * std::sqrt(std::clamp((value - min) / (max - min), 0.0, 1.0)); break;
    case AxisMapping::SplitSqrt: {
        const int zero = size / 2;
        t = value < 0.0 ? zero * (1.0 - std::sqrt(std::clamp(value / min, 0.0, 1.0)))
                        : zero + (last - zero) * std::sqrt(std::clamp(value / max, 0.0, 1.0));
        break;
    }
    case AxisMapping::Rational: {
        const double v = std::max(value, 0.0);
        t = std::isinf(v) ? last : last * v / (v + 1.0);
        break;
    }
    case AxisMapping::Log1p: t = last * std::log1p(std::max(value, 0.0) / scale) / std::log1p(max / scale); break;
    case AxisMapping::Index: t = value; break;
    }
    return std::clamp(t, 0.0, last);
}

std::string LutAxis::formula() const {
    switch (mapping) {
    case AxisMapping::Linear: return "t = (size-1) * (v - min) / (max - min)";
    case AxisMapping::SplitLinear:
        return "k = floor(size/2) (texel k is exactly v = 0); t = k * (v - min) / (0 - min) for v < 0, "
               "t = k + (size-1-k) * v / max for v >= 0";
    case AxisMapping::Sqrt: return "t = (size-1) * sqrt((v - min) / (max - min))";
    case AxisMapping::SplitSqrt:
        return "k = floor(size/2) (texel k is exactly v = 0), min = -max; t = k * (1 - sqrt(v / min)) for v < 0, "
               "t = k + (size-1-k) * sqrt(v / max) for v >= 0";
    case AxisMapping::Rational: return "t = (size-1) * v / (v + 1); the last texel is v = infinity";
    case AxisMapping::Log1p: return "t = (size-1) * ln(1 + v / scale) / ln(1 + max / scale)";
    case AxisMapping::Index: return "t = v (one texel row per index)";
    }
    return "";
}

glm::vec3 LutTable::texel(int ix, int iy) const {
    const size_t i = (static_cast<size_t>(iy) * static_cast<size_t>(width()) + static_cast<size_t>(ix)) * 3;
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
}

glm::vec3 LutTable::sample(glm::vec2 uv) const {
    // Unnormalised coordinates minus the half-texel offset; i0 = floor, weight = fraction;
    // CLAMP_TO_EDGE clamps each integer texel index.
    const float px = uv.x * static_cast<float>(width()) - 0.5f;
    const float py = uv.y * static_cast<float>(height()) - 0.5f;
    const float x0f = std::floor(px);
    const float y0f = std::floor(py);
    const float fx = px - x0f;
    const float fy = py - y0f;
    const int x0 = static_cast<int>(x0f);
    const int y0 = static_cast<int>(y0f);
    auto cx = [&](int i) { return std::clamp(i, 0, width() - 1); };
    auto cy = [&](int i) { return std::clamp(i, 0, height() - 1); };
    const glm::vec3 t00 = texel(cx(x0), cy(y0));
    const glm::vec3 t10 = texel(cx(x0 + 1), cy(y0));
    const glm::vec3 t01 = texel(cx(x0), cy(y0 + 1));
    const glm::vec3 t11 = texel(cx(x0 + 1), cy(y0 + 1));
    return (1.0f - fy) * ((1.0f - fx) * t00 + fx * t10) + fy * ((1.0f - fx) * t01 + fx * t11);
}

std::vector<uint16_t> LutTable::rgba16f() const {
    const size_t texels = rgb.size() / 3;
    std::vector<uint16_t> out(texels * 4);
    const uint16_t one = skin::floatToHalfBits(1.0f);
    for (size_t i = 0; i < texels; ++i) {
        for (size_t c = 0; c < 3; ++c) out[4 * i + c] = skin::floatToHalfBits(rgb[3 * i + c]);
        out[4 * i + 3] = one;
    }
    return out;
}

std::vector<float> LutTable::planes() const { return lutPlanes(rgba16f(), width(), height()); }

std::vector<float> lutPlanes(const std::vector<uint16_t>& rgba16f, int width, int height) {
    const auto w = static_cast<size_t>(std::max(width, 0));
    const auto h = static_cast<size_t>(std::max(height, 0));
    if (rgba16f.size() != w * h * 4)
        throw Error("lutPlanes: the image holds " + std::to_string(rgba16f.size()) + " values, not " +
                    std::to_string(w * h * 4));
    std::vector<float> out(3 * w * h);
    for (size_t y = 0; y < h; ++y)
        for (size_t x = 0; x < w; ++x)
            for (size_t c = 0; c < 3; ++c)
                out[y * 3 * w + c * w + x] = skin::halfBitsToFloat(rgba16f[(y * w + x) * 4 + c]);
    return out;
}

std::string LutTable::contentHash() const {
    std::vector<uint16_t> half(rgb.size());
    for (size_t i = 0; i < rgb.size(); ++i) half[i] = skin::floatToHalfBits(rgb[i]);
    return skin::halfContentHash(half);
}

std::string skin::halfContentHash(std::span<const uint16_t> half) {
    uint64_t hash = 14695981039346656037ull;
    for (const uint16_t value : half) {
        for (int byte = 0; byte < 2; ++byte) {
            hash ^= static_cast<uint64_t>((value >> (8 * byte)) & 0xffu);
            hash *= 1099511628211ull;
        }
    }
    return fmt::format("fnv1a64:{:016x}", hash);
}

}  // namespace preskin
