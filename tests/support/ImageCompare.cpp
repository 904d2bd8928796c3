#include "support/ImageCompare.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
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
            png.rgba8[i] = static_cast<uint8_t>(std::lround(
                i % 4 == 3 ? std::clamp(double(image.rgba32f[i]), 0.0, 1.0) * 255.0 : srgb255(image.rgba32f[i])));
        png.rgba32f.clear();
    }
    std::filesystem::create_directories(dir);
    writeImage(std::filesystem::path(dir) / (name + ".png"), png);
}

// Reads an 8-bit RGBA PNG; empty image on failure (with `error` set).
RenderedImage readPng(const std::filesystem::path& path, std::string& error) {
    RenderedImage image;
    auto input = OIIO::ImageInput::open(path.string());
    if (!input) {
        error = OIIO::geterror();
        return image;
    }
    const OIIO::ImageSpec& spec = input->spec();
    image.width = static_cast<uint32_t>(spec.width);
    image.height = static_cast<uint32_t>(spec.height);
    image.encoding = OutputEncoding::DisplaySrgb8;
    image.rgba8.assign(size_t(image.width) * image.height * 4, 255);
    std::vector<uint8_t> pixels(size_t(image.width) * image.height * size_t(spec.nchannels));
    if (!input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, pixels.data())) {
        error = input->geterror();
        return {};
    }
    for (size_t p = 0; p < size_t(image.width) * image.height; ++p)
        for (int c = 0; c < std::min(spec.nchannels, 4); ++c)
            image.rgba8[p * 4 + size_t(c)] = pixels[p * size_t(spec.nchannels) + size_t(c)];
    return image;
}

size_t pixelsDifferingBy(const RenderedImage& a, const RenderedImage& b, int tolerance, int& maxDifference) {
    maxDifference = 0;
    size_t differing = 0;
    for (size_t p = 0; p + 3 < std::min(a.rgba8.size(), b.rgba8.size()); p += 4) {
        int worst = 0;
        for (size_t c = 0; c < 3; ++c) worst = std::max(worst, std::abs(int(a.rgba8[p + c]) - int(b.rgba8[p + c])));
        maxDifference = std::max(maxDifference, worst);
        differing += worst > tolerance ? 1 : 0;
    }
    return differing;
}

}  // namespace preskin::test
