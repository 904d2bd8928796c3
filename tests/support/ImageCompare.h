// Helpers for comparing rendered images with CPU references.
#pragma once

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace preskin::test {

// Linear [0,1] -> sRGB-encoded value scaled to 0..255 (IEC 61966-2-1), unrounded.
inline double srgb255(double linear) {
    const double c = std::clamp(linear, 0.0, 1.0);
    const double s = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
    return s * 255.0;
}

}  // namespace preskin::test

#include <preskin/Renderer.h>

#include <filesystem>
#include <string>

namespace preskin::test {

// Writes the image as PNG into $PRESKIN_TEST_OUTPUT (when set) for a person to look at.
void dumpImage(const std::string& name, const RenderedImage& image);

// Reads an 8-bit PNG as RGBA; empty image on failure (with `error` set).
RenderedImage readPng(const std::filesystem::path& path, std::string& error);

// Pixels of two equally sized 8-bit images that differ by more than `tolerance` in any channel
// (RGB); `maxDifference` gets the largest channel difference.
size_t pixelsDifferingBy(const RenderedImage& a, const RenderedImage& b, int tolerance, int& maxDifference);

}  // namespace preskin::test
