// Image format recognition and the decoders' size check (see ImageFormat.h).
#include "image/ImageFormat.h"

#include <preskin/Limits.h>

#include <initializer_list>
#include <stdexcept>

namespace preskin::image {

namespace {

bool startsWith(std::span<const uint8_t> bytes, std::initializer_list<uint8_t> magic, size_t offset = 0) {
    if (bytes.size() < offset + magic.size()) return false;
    size_t i = offset;
    for (uint8_t m : magic)
        if (bytes[i++] != m) return false;
    return true;
}

}  // namespace

ImageFormat sniffImageFormat(std::span<const uint8_t> b) {
    if (startsWith(b, {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A})) return ImageFormat::Png;
    if (startsWith(b, {0xFF, 0xD8, 0xFF})) return ImageFormat::Jpeg;
    if (startsWith(b, {'#', '?'})) return ImageFormat::RadianceHdr;
    if (startsWith(b, {0x76, 0x2F, 0x31, 0x01})) return ImageFormat::OpenExr;
    if (startsWith(b, {'I', 'I', 42, 0}) || startsWith(b, {'M', 'M', 0, 42}) || startsWith(b, {'I', 'I', 43, 0}) ||
        startsWith(b, {'M', 'M', 0, 43}))
        return ImageFormat::Tiff;
    if (startsWith(b, {'R', 'I', 'F', 'F'}) && startsWith(b, {'W', 'E', 'B', 'P'}, 8)) return ImageFormat::WebP;
    if (startsWith(b, {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB})) return ImageFormat::Ktx2;
    if (startsWith(b, {'G', 'I', 'F', '8'})) return ImageFormat::Gif;
    if (startsWith(b, {'B', 'M'})) return ImageFormat::Bmp;
    if (startsWith(b, {'D', 'D', 'S', ' '})) return ImageFormat::Dds;
    return ImageFormat::Unknown;
}

const char* formatName(ImageFormat format) {
    switch (format) {
    case ImageFormat::Png: return "PNG";
    case ImageFormat::Jpeg: return "JPEG";
    case ImageFormat::RadianceHdr: return "Radiance HDR";
    case ImageFormat::OpenExr: return "OpenEXR";
    case ImageFormat::Tiff: return "TIFF";
    case ImageFormat::WebP: return "WebP";
    case ImageFormat::Ktx2: return "KTX2";
    case ImageFormat::Gif: return "GIF";
    case ImageFormat::Bmp: return "BMP";
    case ImageFormat::Dds: return "DDS";
    case ImageFormat::Unknown: break;
    }
    return "unknown";
}

bool decodedByImageComponent(ImageFormat format) {
    return format == ImageFormat::OpenExr || format == ImageFormat::Tiff;
}

void checkImageSize(uint64_t width, uint64_t height, const SizeLimits& limits) {
    const std::string size = std::to_string(width) + " x " + std::to_string(height) + " pixels";
    if (width == 0 || height == 0) throw std::runtime_error("invalid image size " + size);
    if (width > limits.maxSide || height > limits.maxSide)
        throw std::runtime_error(size + " exceeds the limit of " + std::to_string(limits.maxSide) + " per side");
    if (width * height > limits::kMaxImagePixels)
        throw std::runtime_error(size + " exceeds the limit of " + std::to_string(limits::kMaxImagePixels) +
                                 " pixels per image");
    if (width * height > limits.maxPixels)
        throw std::runtime_error(size + " bring the scene's images over the limit of " +
                                 std::to_string(limits::kMaxSceneImagePixels) + " pixels");
}

}  // namespace preskin::image
