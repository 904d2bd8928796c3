// The codec registry, the built-in codec and the conversions (see ImageCodecs.h and
// <preskin/ImageCodec.h>).
#include "image/ImageCodecs.h"

#include <preskin/Error.h>
#include <preskin/OutputFile.h>

#include "image/ImageFormat.h"
#include "image/JpegFile.h"
#include "image/PngFile.h"
#include "image/RadianceFile.h"
#include "io/MessageText.h"

#include <fmt/core.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <mutex>
#include <stdexcept>

namespace preskin {

bool PixelImage::consistent() const {
    if (channels < 1 || channels > 4) return false;
    return std::visit([&](const auto& values) { return values.size() == valueCount(); }, texels);
}

ImageCodec::~ImageCodec() = default;
std::string ImageCodec::decodes(std::span<const uint8_t>) const { return {}; }
PixelImage ImageCodec::decode(std::span<const uint8_t>, const DecodeLimits&) const {
    throw std::runtime_error(name() + " decodes nothing");
}
bool ImageCodec::encodes(std::string_view) const { return false; }
void ImageCodec::encode(const std::filesystem::path&, const PixelImage&, const EncodeOptions&) const {
    throw std::runtime_error(name() + " writes nothing");
}

namespace image {

namespace {

class BuiltinCodec final : public ImageCodec {
public:
    std::string name() const override { return "preskin (libpng, libjpeg-turbo, stb_image)"; }
    std::string decodes(std::span<const uint8_t> head) const override {
        const ImageFormat format = sniffImageFormat(head);
        if (format == ImageFormat::Png || format == ImageFormat::Jpeg || format == ImageFormat::RadianceHdr)
            return formatName(format);
        return {};
    }
    PixelImage decode(std::span<const uint8_t> bytes, const DecodeLimits& limits) const override {
        const SizeLimits size{limits.maxPixels, limits.maxSide};
        switch (sniffImageFormat(bytes)) {
        case ImageFormat::Png: return decodePng(bytes, size);
        case ImageFormat::Jpeg: return decodeJpeg(bytes, size);
        case ImageFormat::RadianceHdr: return decodeRadiance(bytes, size);
        default: break;
        }
        throw std::runtime_error("not PNG, JPEG or Radiance HDR data");
    }
    bool encodes(std::string_view extension) const override { return extension == ".png"; }
    void encode(const std::filesystem::path& path, const PixelImage& image, const EncodeOptions&) const override {
        encodePng(path, image);
    }
};

struct Registry {
    std::mutex mutex;
    std::vector<std::shared_ptr<const ImageCodec>> registered;  // newest last
};

Registry& registry() {
    static Registry r;
    return r;
}

std::string lowerExtension(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

std::string componentHint(ImageFormat format) {
    return decodedByImageComponent(format)
        ? " (the image component preskin::imageio reads it: link preskin::imageio and call "
          "preskin::imageio::registerCodecs())"
        : "";
}

}  // namespace

std::shared_ptr<const ImageCodec> builtinCodec() {
    static const auto codec = std::make_shared<const BuiltinCodec>();
    return codec;
}

std::shared_ptr<const ImageCodec> encoderFor(const std::filesystem::path& path) {
    const std::string ext = lowerExtension(path);
    for (const auto& codec : imageCodecs())
        if (codec->encodes(ext)) return codec;
    const bool component = ext == ".exr" || ext == ".tif" || ext == ".tiff";
    throw Error(fmt::format("{}: output: no writer for '{}' files in this program{}", path.string(), ext,
                            component ? componentHint(ImageFormat::OpenExr) : std::string()));
}

ScopedCodecs::ScopedCodecs(std::vector<std::shared_ptr<const ImageCodec>> registered) {
    const std::lock_guard lock(registry().mutex);
    saved_ = std::exchange(registry().registered, std::move(registered));
}

ScopedCodecs::~ScopedCodecs() {
    const std::lock_guard lock(registry().mutex);
    registry().registered = std::move(saved_);
}

void toRgba(const PixelImage& image, std::vector<uint8_t>& rgba8, std::vector<uint16_t>& rgba16) {
    const size_t texels = size_t(image.width) * image.height;
    const uint32_t n = image.channels;
    rgba8.assign(texels * 4, 255);
    rgba16.clear();
    // Channel c of the RGBA texel from the source's n channels: grey to RGB, alpha or opaque.
    auto source = [n](uint32_t c) -> int {
        return c < 3 ? (n >= 3 ? int(c) : 0) : (n == 2 || n == 4 ? int(n) - 1 : -1);
    };
    if (const auto* u8 = std::get_if<std::vector<uint8_t>>(&image.texels)) {
        for (size_t i = 0; i < texels; ++i)
            for (uint32_t c = 0; c < 4; ++c)
                if (const int s = source(c); s >= 0) rgba8[i * 4 + c] = (*u8)[i * n + size_t(s)];
        return;
    }
    rgba16.assign(texels * 4, 65535);
    if (const auto* u16 = std::get_if<std::vector<uint16_t>>(&image.texels)) {
        for (size_t i = 0; i < texels; ++i)
            for (uint32_t c = 0; c < 4; ++c)
                if (const int s = source(c); s >= 0) rgba16[i * 4 + c] = (*u16)[i * n + size_t(s)];
    } else {
        const auto& f32 = std::get<std::vector<float>>(image.texels);
        for (size_t i = 0; i < texels; ++i)
            for (uint32_t c = 0; c < 4; ++c)
                if (const int s = source(c); s >= 0) {
                    const float v = f32[i * n + size_t(s)];
                    rgba16[i * 4 + c] =
                        uint16_t(std::lround(std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f) * 65535.0f));
                }
    }
    for (size_t i = 0; i < rgba16.size(); ++i)  // rounded, as libpng's png_set_scale_16
        rgba8[i] = static_cast<uint8_t>((uint32_t(rgba16[i]) * 255u + 32895u) >> 16);
}

std::vector<float> toRgbFloat(const PixelImage& image) {
    const size_t texels = size_t(image.width) * image.height;
    const uint32_t n = image.channels;
    std::vector<float> rgb(texels * 3);
    std::visit(
        [&](const auto& values) {
            using T = typename std::decay_t<decltype(values)>::value_type;
            const float scale = std::is_same_v<T, float> ? 1.0f : 1.0f / float(std::numeric_limits<T>::max());
            for (size_t i = 0; i < texels; ++i)
                for (uint32_t c = 0; c < 3; ++c) rgb[i * 3 + c] = float(values[i * n + (n >= 3 ? c : 0)]) * scale;
        },
        image.texels);
    return rgb;
}

}  // namespace image

void registerImageCodec(std::shared_ptr<const ImageCodec> codec) {
    if (!codec) throw Error("registerImageCodec: no codec given");
    const std::lock_guard lock(image::registry().mutex);
    image::registry().registered.push_back(std::move(codec));
}

std::vector<std::shared_ptr<const ImageCodec>> imageCodecs() {
    std::vector<std::shared_ptr<const ImageCodec>> all;
    {
        const std::lock_guard lock(image::registry().mutex);
        all.assign(image::registry().registered.rbegin(), image::registry().registered.rend());
    }
    all.push_back(image::builtinCodec());
    return all;
}

std::string describeImageFormat(std::span<const uint8_t> head) {
    return image::formatName(image::sniffImageFormat(head));
}

bool canDecodeImage(std::span<const uint8_t> head) {
    for (const auto& codec : imageCodecs())
        if (!codec->decodes(head).empty()) return true;
    return false;
}

PixelImage decodeImage(std::span<const uint8_t> bytes, const DecodeLimits& limits, const std::string& label) {
    for (const auto& codec : imageCodecs()) {
        if (codec->decodes(bytes).empty()) continue;
        PixelImage out;
        try {
            out = codec->decode(bytes, limits);
        } catch (const Error&) {
            throw;
        } catch (const std::exception& e) {
            throw Error(fmt::format("{}: {}", label, io::messageText(e.what(), 400)));
        }
        if (!out.consistent() || out.width == 0 || out.height == 0)
            throw Error(fmt::format("{}: {} returned {}x{} texels of {} channels that do not match its data", label,
                                    codec->name(), out.width, out.height, out.channels));
        if (out.width > limits.maxSide || out.height > limits.maxSide ||
            uint64_t(out.width) * out.height > limits.maxPixels)
            throw Error(fmt::format("{}: {} decoded {}x{} pixels, beyond the limits", label, codec->name(), out.width,
                                    out.height));
        return out;
    }
    const image::ImageFormat format = image::sniffImageFormat(bytes);
    throw Error(fmt::format("{}: {} data: no decoder for it in this program{}", label, image::formatName(format),
                            image::componentHint(format)));
}

bool canEncodeImage(const std::filesystem::path& path) {
    const std::string ext = image::lowerExtension(path);
    for (const auto& codec : imageCodecs())
        if (codec->encodes(ext)) return true;
    return false;
}

void encodeImage(const std::filesystem::path& path, const PixelImage& image, const EncodeOptions& options) {
    const std::shared_ptr<const ImageCodec> writer = image::encoderFor(path);
    if (!image.consistent() || image.width == 0 || image.height == 0)
        throw Error(fmt::format("{}: image data does not match its size {}x{}x{}", path.string(), image.width,
                                image.height, image.channels));
    writeOutputFile(path, [&](const std::filesystem::path& temporary) {
        try {
            writer->encode(temporary, image, options);
        } catch (const Error&) {
            throw;
        } catch (const std::exception& e) {
            throw Error(fmt::format("{}: cannot write: {}", path.string(), io::messageText(e.what(), 400)));
        }
    });
}

}  // namespace preskin
