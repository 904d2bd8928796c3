#include "support/ImageCompare.h"

#include <cstdlib>
#include <filesystem>

namespace preskin::test {

void dumpImage(const std::string& name, const RenderedImage& image) {
    const char* dir = std::getenv("PRESKIN_TEST_OUTPUT");
    if (!dir || !*dir) return;
    RenderedImage png = image;
    if (image.encoding == OutputEncoding::LinearFloat) {
        png.encoding = OutputEncoding::DisplaySrgb8;
        png.rgba8.resize(image.rgba32f.size());
        for (size_t i = 0; i < image.rgba32f.size(); ++i)
            png.rgba8[i] = static_cast<uint8_t>(
                std::lround(i % 4 == 3 ? std::clamp(double(image.rgba32f[i]), 0.0, 1.0) * 255.0 : srgb255(image.rgba32f[i])));
        png.rgba32f.clear();
    }
    std::filesystem::create_directories(dir);
    writeImage(std::filesystem::path(dir) / (name + ".png"), png);
}

}  // namespace preskin::test
