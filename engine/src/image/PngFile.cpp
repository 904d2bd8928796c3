// PNG decoding and writing through libpng (see PngFile.h).
#include "image/PngFile.h"

#include <png.h>

#include <bit>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace preskin::image {

namespace {

struct PngSource {
    std::span<const uint8_t> bytes;
    size_t offset = 0;
    std::string error;  // libpng's message when it gave up
};

// libpng's handlers: errors are recorded and unwound with longjmp (libpng's own mechanism);
// warnings are dropped. No object with a destructor lives in the frames they unwind.
void pngError(png_structp png, png_const_charp message) {
    static_cast<std::string*>(png_get_error_ptr(png))->assign(message ? message : "unknown libpng error");
    png_longjmp(png, 1);
}
void pngWarning(png_structp, png_const_charp) {}
void pngRead(png_structp png, png_bytep out, size_t length) {
    auto* source = static_cast<PngSource*>(png_get_io_ptr(png));
    if (length > source->bytes.size() - source->offset) png_error(png, "truncated PNG data");
    std::memcpy(out, source->bytes.data() + source->offset, length);
    source->offset += length;
}

// The part of the decode that libpng may leave by longjmp: it only touches objects owned by the
// caller. Returns false with source.error set, or with sizeProblem set after png_read_info
// (before any pixel memory).
bool readPng(png_structp png, png_infop info, PngSource& source, const SizeLimits& limits, PixelImage& out,
             std::vector<png_bytep>& rows, std::optional<std::string>& sizeProblem) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_set_read_fn(png, &source, &pngRead);
    png_set_chunk_malloc_max(png, 8u << 20);  // ancillary chunks (text, ICC profiles)
    png_read_info(png, info);
    const png_uint_32 width = png_get_image_width(png, info);
    const png_uint_32 height = png_get_image_height(png, info);
    try {
        checkImageSize(width, height, limits);
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
    out.channels = 4;
    const size_t samples = size_t(width) * height * 4;
    uint8_t* pixels = nullptr;
    if (sixteen) {
        auto& texels = out.texels.emplace<std::vector<uint16_t>>(samples);
        pixels = reinterpret_cast<uint8_t*>(texels.data());
    } else {
        pixels = out.texels.emplace<std::vector<uint8_t>>(samples).data();
    }
    rows.resize(height);
    for (png_uint_32 y = 0; y < height; ++y) rows[y] = pixels + size_t(y) * width * texelBytes;
    png_read_image(png, rows.data());
    png_read_end(png, nullptr);
    return true;
}

struct PngSink {
    std::FILE* file = nullptr;
    std::string error;
};

bool writePng(png_structp png, png_infop info, const PixelImage& image, std::vector<png_bytep>& rows,
              std::vector<uint8_t>& swapped) {
    if (setjmp(png_jmpbuf(png))) return false;
    static constexpr int kColourTypes[] = {PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                                           PNG_COLOR_TYPE_RGB_ALPHA};
    const bool sixteen = std::holds_alternative<std::vector<uint16_t>>(image.texels);
    png_set_IHDR(png, info, image.width, image.height, sixteen ? 16 : 8, kColourTypes[image.channels - 1],
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    const size_t rowBytes = size_t(image.width) * image.channels * (sixteen ? 2 : 1);
    const uint8_t* data = nullptr;
    if (sixteen) {
        // PNG stores 16-bit samples big-endian.
        const auto& texels = std::get<std::vector<uint16_t>>(image.texels);
        swapped.resize(texels.size() * 2);
        for (size_t i = 0; i < texels.size(); ++i) {
            swapped[2 * i] = uint8_t(texels[i] >> 8);
            swapped[2 * i + 1] = uint8_t(texels[i] & 0xFF);
        }
        data = swapped.data();
    } else {
        data = std::get<std::vector<uint8_t>>(image.texels).data();
    }
    rows.resize(image.height);
    for (uint32_t y = 0; y < image.height; ++y) rows[y] = const_cast<png_bytep>(data + size_t(y) * rowBytes);
    png_write_image(png, rows.data());
    png_write_end(png, nullptr);
    return true;
}

}  // namespace

PixelImage decodePng(std::span<const uint8_t> bytes, const SizeLimits& limits) {
    PngSource source{bytes, 0, {}};
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &source.error, &pngError, &pngWarning);
    if (!png) throw std::runtime_error("cannot start the PNG decoder");
    png_infop info = png_create_info_struct(png);
    if (!info) {
        png_destroy_read_struct(&png, nullptr, nullptr);
        throw std::runtime_error("cannot start the PNG decoder");
    }
    PixelImage out;
    std::vector<png_bytep> rows;
    std::optional<std::string> sizeProblem;
    const bool ok = readPng(png, info, source, limits, out, rows, sizeProblem);
    png_destroy_read_struct(&png, &info, nullptr);
    if (sizeProblem) throw std::runtime_error(*sizeProblem);
    if (!ok) throw std::runtime_error("cannot decode the PNG data: " + source.error);
    return out;
}

void encodePng(const std::filesystem::path& path, const PixelImage& image) {
    if (std::holds_alternative<std::vector<float>>(image.texels) || !image.consistent())
        throw std::runtime_error("PNG holds 8- or 16-bit images of 1 to 4 channels");
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "wb"), &std::fclose);
    if (!file) throw std::runtime_error("cannot create the file");
    std::string error;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &error, &pngError, &pngWarning);
    if (!png) throw std::runtime_error("cannot start the PNG encoder");
    png_infop info = png_create_info_struct(png);
    if (!info) {
        png_destroy_write_struct(&png, nullptr);
        throw std::runtime_error("cannot start the PNG encoder");
    }
    png_init_io(png, file.get());
    std::vector<png_bytep> rows;
    std::vector<uint8_t> swapped;
    const bool ok = writePng(png, info, image, rows, swapped);
    png_destroy_write_struct(&png, &info);
    if (!ok) throw std::runtime_error("cannot write PNG data: " + error);
    if (std::fflush(file.get()) != 0 || std::ferror(file.get())) throw std::runtime_error("cannot write the file");
}

}  // namespace preskin::image
