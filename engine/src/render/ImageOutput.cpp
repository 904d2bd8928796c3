// Writing rendered images: PNG (8-bit sRGB) or EXR (half float, linear) through OpenImageIO,
// into a temporary file in the same folder that is renamed into place, so a failed run never
// leaves a partly written image behind.
#include <preskin/Error.h>
#include <preskin/Renderer.h>

#include <OpenImageIO/imageio.h>
#include <fmt/core.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <cctype>
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
        throw Error(fmt::format("{}: output: type '{}' does not match the encoding (expected {})", path.string(), ext,
                                wanted));
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
        throw Error(fmt::format("{}: output: is a folder, not a file", path.string()));
    const std::filesystem::path dir = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
    if (!std::filesystem::is_directory(dir, ec))
        throw Error(fmt::format("{}: output: folder {} does not exist", path.string(), dir.string()));
    if (::access(dir.c_str(), W_OK) != 0)
        throw Error(fmt::format("{}: output: folder {} is not writable", path.string(), dir.string()));
    // An existing file is replaced only when it is a regular file its owner left writable: the
    // rename would otherwise replace a read-only file (or a FIFO, a device) without a word.
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0) {
        if (!S_ISREG(st.st_mode))
            throw Error(fmt::format("{}: output: exists and is not a regular file; not replaced", path.string()));
        if ((st.st_mode & (S_IWUSR | S_IWGRP | S_IWOTH)) == 0 || ::access(path.c_str(), W_OK) != 0)
            throw Error(fmt::format("{}: output: exists and is read-only; not replaced", path.string()));
    }
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
        throw Error(fmt::format("{}: image data does not match its size {}x{}", path.string(), image.width,
                                image.height));
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
    const std::filesystem::path dir = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
    const std::filesystem::path temp =
        dir / fmt::format(".{}.{}.partial{}", path.filename().string(), ::getpid(), lowerExtension(path));
    const std::string format = display ? "png" : "openexr";
    auto out = OIIO::ImageOutput::create(format);
    if (!out) throw Error(fmt::format("{}: no {} writer: {}", path.string(), format, OIIO::geterror()));
    OIIO::ImageSpec spec(int(image.width), int(image.height), 4, display ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::HALF);
    spec.attribute("oiio:ColorSpace", display ? "sRGB" : "Linear");
    if (!display) spec.attribute("compression", "zip");
    auto fail = [&](const std::string& what) {
        std::error_code ec;
        std::filesystem::remove(temp, ec);
        throw Error(fmt::format("{}: {}", path.string(), what));
    };
    if (!out->open(temp.string(), spec)) fail("cannot create file: " + out->geterror());
    const bool ok = display ? out->write_image(OIIO::TypeDesc::UINT8, image.rgba8.data())
                            : out->write_image(OIIO::TypeDesc::FLOAT, linear.data());
    if (!ok) {
        const std::string error = out->geterror();
        out->close();
        fail("cannot write image: " + error);
    }
    if (!out->close()) fail("cannot finish image: " + out->geterror());
    std::error_code ec;
    std::filesystem::rename(temp, path, ec);
    if (ec) fail("cannot move the finished image into place: " + ec.message());
}

}  // namespace preskin
