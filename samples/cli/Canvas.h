// Canvas: an 8-bit RGBA picture for the tool's comparison sheets (`preskin compare`): filled
// rectangles, lines with a square brush, and text in a built-in 5 x 8
// pixel font (digits, lower-case letters and a little punctuation; other characters leave a gap).
#pragma once

#include <glm/glm.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string_view>
#include <vector>

namespace preskin::cli {

// The font: per character 8 rows of 5 columns, '#' set (row 7 holds descenders).
const std::map<char, std::array<const char*, 8>>& canvasGlyphs();

struct Canvas {
    uint32_t width;
    uint32_t height;
    std::vector<uint8_t> rgba;

    Canvas(uint32_t w, uint32_t h) : width(w), height(h), rgba(size_t(w) * h * 4, 255) {}

    void set(int x, int y, glm::u8vec3 c) {
        if (x < 0 || y < 0 || x >= int(width) || y >= int(height)) return;
        uint8_t* p = &rgba[(size_t(y) * width + size_t(x)) * 4];
        p[0] = c.r;
        p[1] = c.g;
        p[2] = c.b;
        p[3] = 255;
    }
    void fill(int x0, int y0, int x1, int y1, glm::u8vec3 c) {
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) set(x, y, c);
    }
    // A line `thickness` pixels wide (square brush).
    void line(double x0, double y0, double x1, double y1, int thickness, glm::u8vec3 c) {
        const double length = std::max(std::abs(x1 - x0), std::abs(y1 - y0));
        const int steps = std::max(1, int(std::ceil(length * 2.0)));
        const int h = thickness / 2;
        for (int i = 0; i <= steps; ++i) {
            const double t = double(i) / steps;
            const int x = int(std::lround(x0 + (x1 - x0) * t));
            const int y = int(std::lround(y0 + (y1 - y0) * t));
            fill(x - h, y - h, x - h + thickness - 1, y - h + thickness - 1, c);
        }
    }
    // Text at `scale` pixels per font pixel; returns the width drawn. Unknown characters: a gap.
    int text(int x, int y, std::string_view s, int scale, glm::u8vec3 c) {
        const auto& font = canvasGlyphs();
        int cursor = x;
        for (char ch : s) {
            auto it = font.find(ch);
            if (it != font.end())
                for (int row = 0; row < 8; ++row)
                    for (int col = 0; col < 5; ++col)
                        if (it->second[size_t(row)][col] == '#')
                            fill(cursor + col * scale, y + row * scale, cursor + (col + 1) * scale - 1,
                                 y + (row + 1) * scale - 1, c);
            cursor += 6 * scale;
        }
        return cursor - x;
    }
    static int textWidth(std::string_view s, int scale) { return int(s.size()) * 6 * scale; }
    // Writes the picture as an 8-bit sRGB PNG (preskin::writeImage: atomic, errors name the path).
    void writePng(const std::filesystem::path& path) const;
};

}  // namespace preskin::cli
