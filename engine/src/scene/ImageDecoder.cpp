// PNG (libpng) and JPEG (OpenImageIO) decoding to RGBA8 from memory (see ImageDecoder.h).
#include "scene/ImageDecoder.h"

#include <preskin/Limits.h>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <png.h>

#include <unistd.h>

#include <bit>
#include <csetjmp>
#include <optional>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>

namespace preskin::gltf {

namespace {

bool startsWith(std::span<const uint8_t> bytes, std::initializer_list<uint8_t> magic, size_t offset = 0) {
    if (bytes.size() < offset + magic.size()) return false;
    size_t i = offset;
    for (uint8_t m : magic) {
        if (bytes[i++] != m) return false;
    }
    return true;
}

// A temporary file removed on destruction, for OIIO readers without IOProxy support.
class TempFile {
public:
    TempFile(std::span<const uint8_t> bytes, const char* extension) {
        const char* dir = std::getenv("TMPDIR");
        std::string pattern = std::string(dir && *dir ? dir : "/tmp") + "/preskin-image-XXXXXX" + extension;
        std::vector<char> name(pattern.begin(), pattern.end());
        name.push_back('\0');
        const int fd = mkstemps(name.data(), static_cast<int>(std::strlen(extension)));
        if (fd < 0) throw std::runtime_error("cannot create a temporary file to decode from");
        path_ = name.data();
        size_t written = 0;
        while (written < bytes.size()) {
            const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
            if (n <= 0) {
                ::close(fd);
                throw std::runtime_error("cannot write a temporary file to decode from");
            }
            written += static_cast<size_t>(n);
        }
        ::close(fd);
    }
    ~TempFile() { std::remove(path_.c_str()); }
    TempFile(const TempFile&) = delete;
    TempFile& operator=(const TempFile&) = delete;
    const std::string& path() const { return path_; }

private:
    std::string path_;
};

// Refuses a size beyond the per-image limits or the scene's remaining pixel budget.
void checkSize(uint64_t width, uint64_t height, uint64_t scenePixelsLeft) {
    const std::string size = std::to_string(width) + " x " + std::to_string(height) + " pixels";
    if (width == 0 || height == 0) throw std::runtime_error("invalid image size " + size);
    if (width > limits::kMaxImageSide || height > limits::kMaxImageSide) {
        throw std::runtime_error(size + " exceeds the limit of " + std::to_string(limits::kMaxImageSide) + " per side");
    }
    if (width * height > limits::kMaxImagePixels) {
        throw std::runtime_error(size + " exceeds the limit of " + std::to_string(limits::kMaxImagePixels) +
                                 " pixels per image");
    }
    if (width * height > scenePixelsLeft) {
        throw std::runtime_error(size + " bring the scene's images over the limit of " +
                                 std::to_string(limits::kMaxSceneImagePixels) + " pixels");
    }
}

// ---- PNG through libpng ---------------------------------------------------------------------

struct PngSource {
    std::span<const uint8_t> bytes;
    size_t offset = 0;
    std::string error;  // libpng's message when it gave up
};

// libpng's handlers: errors are recorded and unwound with longjmp (libpng's own mechanism);
// warnings are dropped. Nothing is printed. No object with a destructor lives in these frames.
void pngError(png_structp png, png_const_charp message) {
    static_cast<PngSource*>(png_get_error_ptr(png))->error = message ? message : "unknown libpng error";
    png_longjmp(png, 1);
}
void pngWarning(png_structp, png_const_charp) {}
void pngRead(png_structp png, png_bytep out, size_t length) {
    auto* source = static_cast<PngSource*>(png_get_io_ptr(png));
    if (length > source->bytes.size() - source->offset) png_error(png, "truncated PNG data");
    std::memcpy(out, source->bytes.data() + source->offset, length);
    source->offset += length;
}

// The part of the decode that libpng may leave by longjmp: it only touches objects owned by
// the caller, so no destructor is skipped. Returns false with source.error set, or throws the
// size refusal after png_read_info (before any pixel memory).
bool readPng(png_structp png, png_infop info, PngSource& source, uint64_t scenePixelsLeft, DecodedImage& out,
             std::vector<png_bytep>& rows, std::optional<std::string>& sizeProblem) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_set_read_fn(png, &source, &pngRead);
    png_set_chunk_malloc_max(png, 8u << 20);  // ancillary chunks (text, ICC profiles)
    png_read_info(png, info);
    const png_uint_32 width = png_get_image_width(png, info);
    const png_uint_32 height = png_get_image_height(png, info);
    try {
        checkSize(width, height, scenePixelsLeft);
    } catch (const std::exception& e) {
        sizeProblem = e.what();
        return false;
    }
    const bool sixteen = png_get_bit_depth(png, info) == 16;
    png_set_expand(png);  // palette to RGB, grey below 8 bits to 8, tRNS to alpha
    if (sixteen && std::endian::native == std::endian::little) png_set_swap(png);  // PNG stores big-endian
    png_set_gray_to_rgb(png);
    png_set_add_alpha(png, sixteen ? 0xFFFF : 0xFF, PNG_FILLER_AFTER);
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
    const size_t texelBytes = sixteen ? 8 : 4;
    if (png_get_rowbytes(png, info) != size_t(width) * texelBytes)
        png_error(png, "unexpected row layout after conversion");
    out.width = width;
    out.height = height;
    const size_t samples = size_t(width) * height * 4;
    uint8_t* pixels = nullptr;
    if (sixteen) {
        out.rgba16.resize(samples);
        pixels = reinterpret_cast<uint8_t*>(out.rgba16.data());
    } else {
        out.rgba8.resize(samples);
        pixels = out.rgba8.data();
    }
    rows.resize(height);
    for (png_uint_32 y = 0; y < height; ++y) rows[y] = pixels + size_t(y) * width * texelBytes;
    png_read_image(png, rows.data());
    png_read_end(png, nullptr);
    return true;
}

DecodedImage decodePng(std::span<const uint8_t> bytes, uint64_t scenePixelsLeft) {
    PngSource source{bytes, 0, {}};
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &source, &pngError, &pngWarning);
    if (!png) throw std::runtime_error("cannot start the PNG decoder");
    png_infop info = png_create_info_struct(png);
    if (!info) {
        png_destroy_read_struct(&png, nullptr, nullptr);
        throw std::runtime_error("cannot start the PNG decoder");
    }
    DecodedImage out;
    std::vector<png_bytep> rows;
    std::optional<std::string> sizeProblem;
    const bool ok = readPng(png, info, source, scenePixelsLeft, out, rows, sizeProblem);
    png_destroy_read_struct(&png, &info, nullptr);
    if (sizeProblem) throw std::runtime_error(*sizeProblem);
    if (!ok) throw std::runtime_error("cannot decode the PNG data: " + source.error);
    if (!out.rgba16.empty()) {
        out.rgba8.resize(out.rgba16.size());
        for (size_t i = 0; i < out.rgba16.size(); ++i)  // rounded, as png_set_scale_16
            out.rgba8[i] = static_cast<uint8_t>((uint32_t(out.rgba16[i]) * 255u + 32895u) >> 16);
    }
    return out;
}

// ---- JPEG through OpenImageIO ---------------------------------------------------------------

// Width and height from the first start-of-frame marker (ITU T.81, B.2.2), or nullopt.
std::optional<std::pair<uint32_t, uint32_t>> jpegSize(std::span<const uint8_t> bytes) {
    size_t i = 2;  // after SOI
    while (i + 4 <= bytes.size()) {
        if (bytes[i] != 0xFF) return std::nullopt;
        const uint8_t marker = bytes[i + 1];
        if (marker == 0xFF) {  // fill byte
            ++i;
            continue;
        }
        const size_t length = (size_t(bytes[i + 2]) << 8) | bytes[i + 3];
        const bool startOfFrame =
            marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
        if (startOfFrame) {
            if (i + 9 > bytes.size() || length < 7) return std::nullopt;
            const uint32_t height = (uint32_t(bytes[i + 5]) << 8) | bytes[i + 6];
            const uint32_t width = (uint32_t(bytes[i + 7]) << 8) | bytes[i + 8];
            return std::make_pair(width, height);
        }
        if (length < 2) return std::nullopt;
        i += 2 + length;
    }
    return std::nullopt;
}

DecodedImage decodeJpeg(std::span<const uint8_t> bytes, uint64_t scenePixelsLeft);

}  // namespace

ImageFormat sniffImageFormat(std::span<const uint8_t> bytes) {
    if (startsWith(bytes, {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A})) return ImageFormat::Png;
    if (startsWith(bytes, {0xFF, 0xD8, 0xFF})) return ImageFormat::Jpeg;
    return ImageFormat::Unsupported;
}

std::string describeImageFormat(std::span<const uint8_t> bytes) {
    switch (sniffImageFormat(bytes)) {
    case ImageFormat::Png: return "PNG";
    case ImageFormat::Jpeg: return "JPEG";
    case ImageFormat::Unsupported: break;
    }
    if (startsWith(bytes, {'R', 'I', 'F', 'F'}) && startsWith(bytes, {'W', 'E', 'B', 'P'}, 8)) return "WebP";
    if (startsWith(bytes, {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB})) return "KTX2";
    if (startsWith(bytes, {'G', 'I', 'F', '8'})) return "GIF";
    if (startsWith(bytes, {'B', 'M'})) return "BMP";
    if (startsWith(bytes, {'D', 'D', 'S', ' '})) return "DDS";
    if (startsWith(bytes, {'#', '?'})) return "Radiance HDR";
    if (startsWith(bytes, {0x76, 0x2F, 0x31, 0x01})) return "OpenEXR";
    return "unknown";
}

DecodedImage decodeImage(std::span<const uint8_t> bytes, ImageFormat format, uint64_t scenePixelsLeft) {
    if (format == ImageFormat::Png) return decodePng(bytes, scenePixelsLeft);
    if (format == ImageFormat::Jpeg) return decodeJpeg(bytes, scenePixelsLeft);
    throw std::runtime_error("unsupported image format " + describeImageFormat(bytes));
}

namespace {

DecodedImage decodeJpeg(std::span<const uint8_t> bytes, uint64_t scenePixelsLeft) {
    const auto size = jpegSize(bytes);
    if (!size) throw std::runtime_error("cannot decode the JPEG data: no frame header");
    checkSize(size->first, size->second, scenePixelsLeft);
    auto input = OIIO::ImageInput::create("jpeg");
    if (!input) {
        OIIO::geterror();
        throw std::runtime_error("OpenImageIO has no jpeg reader");
    }

    OIIO::Filesystem::IOMemReader memory(bytes.data(), bytes.size());
    std::unique_ptr<TempFile> temp;
    OIIO::ImageSpec config;
    // glTF colours are straight (unassociated) alpha; OIIO would premultiply PNG alpha otherwise.
    config.attribute("oiio:UnassociatedAlpha", 1);
    std::string openName;
    if (input->supports("ioproxy")) {
        void* proxy = &memory;
        config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
        openName = "memory.jpg";
    } else {
        temp = std::make_unique<TempFile>(bytes, ".jpg");
        openName = temp->path();
    }
    OIIO::ImageSpec spec;
    if (!input->open(openName, spec, config)) {
        std::string why = input->geterror();
        OIIO::geterror();  // clear any global message as well
        throw std::runtime_error("cannot decode the " + describeImageFormat(bytes) +
                                 " data: " + (why.empty() ? "unreadable header" : why));
    }
    const int channels = spec.nchannels;
    if (spec.width <= 0 || spec.height <= 0 || channels <= 0 || channels > 4 || spec.depth > 1) {
        input->geterror();
        throw std::runtime_error("invalid image size " + std::to_string(spec.width) + " x " +
                                 std::to_string(spec.height) + " x " + std::to_string(channels) + " channels");
    }
    const auto width = static_cast<uint64_t>(spec.width);
    const auto height = static_cast<uint64_t>(spec.height);
    checkSize(width, height, scenePixelsLeft);

    const auto pixelCount = static_cast<size_t>(width * height);
    std::vector<uint8_t> pixels(pixelCount * static_cast<size_t>(channels));
    const bool ok = input->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, pixels.data());
    std::string why = input->geterror();  // also catches "premature end of data" on a successful read
    OIIO::geterror();
    input->close();
    if (!ok || !why.empty()) {
        throw std::runtime_error("cannot decode the " + describeImageFormat(bytes) +
                                 " data: " + (why.empty() ? "read failed" : why));
    }

    DecodedImage out;
    out.width = static_cast<uint32_t>(width);
    out.height = static_cast<uint32_t>(height);
    out.rgba8.resize(pixelCount * 4);
    const auto stride = static_cast<size_t>(channels);
    for (size_t i = 0; i < pixelCount; ++i) {
        const uint8_t* src = pixels.data() + i * stride;
        uint8_t* dst = out.rgba8.data() + i * 4;
        if (channels <= 2) {
            dst[0] = dst[1] = dst[2] = src[0];
            dst[3] = channels == 2 ? src[1] : 255;
        } else {
            dst[0] = src[0];
            dst[1] = src[1];
            dst[2] = src[2];
            dst[3] = channels >= 4 ? src[3] : 255;
        }
    }
    return out;
}

}  // namespace

}  // namespace preskin::gltf
