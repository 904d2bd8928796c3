// IEEE 754 binary16 ("half") conversion, round to nearest even, as OpenEXR and GPUs store it.
// LUT values are rounded to half at bake time so the in-memory tables, the EXR files and an
// R16G16B16A16_SFLOAT texture hold the same numbers. Limits: NaN payloads are not preserved.
#pragma once

#include <bit>
#include <cstdint>
#include <span>
#include <string>

namespace preskin::skin {

inline uint16_t floatToHalfBits(float value) {
    const uint32_t bits = std::bit_cast<uint32_t>(value);
    const auto sign = static_cast<uint16_t>((bits >> 16) & 0x8000u);
    const uint32_t magnitude = bits & 0x7fffffffu;
    if (magnitude >= 0x7f800000u)
        return static_cast<uint16_t>(sign | 0x7c00u | (magnitude > 0x7f800000u ? 0x200u : 0u));
    if (magnitude >= 0x477ff000u) return static_cast<uint16_t>(sign | 0x7c00u);  // rounds to infinity
    const uint32_t exponent = magnitude >> 23;
    if (magnitude < 0x38800000u) {  // half subnormal (or zero)
        if (magnitude < 0x33000000u) return sign;
        const uint32_t mantissa = (magnitude & 0x7fffffu) | 0x800000u;
        const uint32_t shift = 126u - exponent;
        uint32_t half = mantissa >> shift;
        const uint32_t rest = mantissa & ((1u << shift) - 1u);
        const uint32_t tie = 1u << (shift - 1u);
        if (rest > tie || (rest == tie && (half & 1u))) ++half;
        return static_cast<uint16_t>(sign | half);
    }
    uint32_t half = ((exponent - 112u) << 10) | ((magnitude & 0x7fffffu) >> 13);
    const uint32_t rest = magnitude & 0x1fffu;
    if (rest > 0x1000u || (rest == 0x1000u && (half & 1u))) ++half;
    return static_cast<uint16_t>(sign | half);
}

inline float halfBitsToFloat(uint16_t half) {
    const uint32_t sign = static_cast<uint32_t>(half & 0x8000u) << 16;
    const uint32_t exponent = (half >> 10) & 0x1fu;
    uint32_t mantissa = half & 0x3ffu;
    if (exponent == 0) {
        if (mantissa == 0) return std::bit_cast<float>(sign);
        // Subnormal: normalise.
        uint32_t e = 113;
        while ((mantissa & 0x400u) == 0) {
            mantissa <<= 1;
            --e;
        }
        return std::bit_cast<float>(sign | (e << 23) | ((mantissa & 0x3ffu) << 13));
    }
    if (exponent == 31) return std::bit_cast<float>(sign | 0x7f800000u | (mantissa << 13));
    return std::bit_cast<float>(sign | ((exponent + 112u) << 23) | (mantissa << 13));
}

inline float roundToHalf(float value) { return halfBitsToFloat(floatToHalfBits(value)); }

// LutTable::contentHash of a table whose values are these half floats: "fnv1a64:<16 hex digits>"
// over their bytes, low byte first (LutTable.cpp).
std::string halfContentHash(std::span<const uint16_t> half);

}  // namespace preskin::skin
