// Writing rendered images: PNG (8-bit sRGB, libpng in the core) or EXR (half float, linear,
// through a registered codec: preskin::imageio),
// under the output rule of <preskin/OutputFile.h> (a temporary file renamed into place, missing
// folders made), so a failed run never leaves a partly written image behind.
#include <preskin/Error.h>
#include <preskin/ImageCodec.h>
#include <preskin/OutputFile.h>
#include <preskin/Renderer.h>

#include "image/ImageCodecs.h"

#include <fmt/core.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <system_error>

namespace preskin {

namespace {

constexpr float kHalfMax = 65504.0f;

std::string lowerExtension(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

}  // namespace

void checkOutputPath(const std::filesystem::path& path, OutputEncoding encoding) {
    const std::string ext = lowerExtension(path);
    const std::string wanted = encoding == OutputEncoding::DisplaySrgb8 ? ".png" : ".exr";
    if (ext != wanted)
        throw Error(
            fmt::format("{}: output: type '{}' does not match the encoding (expected {})", path.string(), ext, wanted));
    image::encoderFor(path);
    checkOutputFile(path);
}

RenderedImage eyeImage(const RenderedImage& image, uint32_t eye) {
    if (eye >= image.eyes) throw Error(fmt::format("image: eye {} of an image of {} eye(s)", eye, image.eyes));
    RenderedImage out;
    out.width = image.width;
    out.height = image.height;
    out.encoding = image.encoding;
    const size_t count = size_t(image.width) * image.height * 4;
    auto slice = [&](const auto& all, auto& part) {
        if (all.size() < count * image.eyes) return;
        part.assign(all.data() + count * eye, all.data() + count * (eye + 1));
    };
    slice(image.rgba8, out.rgba8);
    slice(image.rgba32f, out.rgba32f);
    return out;
}

RenderedImage sideBySide(const RenderedImage& image) {
    if (image.eyes <= 1) return image;
    RenderedImage out;
    out.width = image.width * image.eyes;
    out.height = image.height;
    out.encoding = image.encoding;
    const size_t row = size_t(image.width) * 4;
    auto place = [&](const auto& all, auto& joined) {
        if (all.size() != row * image.height * image.eyes) return;
        joined = all;  // sized like the source; every byte is overwritten below
        for (uint32_t e = 0; e < image.eyes; ++e)
            for (uint32_t y = 0; y < image.height; ++y)
                std::memcpy(joined.data() + size_t(y) * row * image.eyes + e * row,
                            all.data() + (size_t(e) * image.height + y) * row, row * sizeof(all[0]));
    };
    place(image.rgba8, out.rgba8);
    place(image.rgba32f, out.rgba32f);
    return out;
}

void writeImage(const std::filesystem::path& path, const RenderedImage& eyes) {
    checkOutputPath(path, eyes.encoding);
    const RenderedImage image = sideBySide(eyes);
    const bool display = image.encoding == OutputEncoding::DisplaySrgb8;
    const size_t expected = size_t(image.width) * image.height * 4;
    if (image.width == 0 || image.height == 0 || (display ? image.rgba8.size() : image.rgba32f.size()) != expected)
        throw Error(
            fmt::format("{}: image data does not match its size {}x{}", path.string(), image.width, image.height));
    // Half floats end at 65504: brighter radiance saturates there instead of becoming infinite.
    std::vector<float> linear;
    if (!display) {
        linear = image.rgba32f;
        size_t nonFinite = 0;
        for (float& v : linear) {
            if (!std::isfinite(v)) ++nonFinite;
            v = std::clamp(v, -kHalfMax, kHalfMax);
        }
        if (nonFinite > 0)
            throw Error(fmt::format("{}: pixels: {} values of the rendered image are not finite; nothing written",
                                    path.string(), nonFinite));
    }
    PixelImage pixels;
    pixels.width = image.width;
    pixels.height = image.height;
    pixels.channels = 4;
    if (display)
        pixels.texels = image.rgba8;
    else
        pixels.texels = std::move(linear);
    encodeImage(path, pixels);  // PNG in the core, EXR through a registered codec (preskin::imageio)
}

}  // namespace preskin
