// Decodes an encoded image held in memory (PNG or JPEG, the formats core glTF allows) into 8-bit
// RGBA, top row first, with OpenImageIO. The bytes are read through an in-memory IOProxy; where
// the OIIO build cannot read a format from memory, through a private temporary file instead.
// Grey becomes RGB, missing alpha becomes 255, alpha stays straight (not premultiplied), 16-bit
// data is rounded to 8 bits; colour profiles are not applied. Sizes are checked before any pixel
// memory is allocated (at most kMaxImagePixels, kMaxImageDimension per side).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace preskin::gltf {

enum class ImageFormat { Png, Jpeg, Unsupported };

// Identifies the format from the leading bytes (magic numbers), not from names or media types.
ImageFormat sniffImageFormat(std::span<const uint8_t> bytes);
// A short name for messages: "PNG", "JPEG", or a guess such as "WebP", "KTX2", "GIF", "BMP".
std::string describeImageFormat(std::span<const uint8_t> bytes);

struct DecodedImage {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<uint8_t> rgba8;
};

// Throws std::runtime_error with the reason (the caller adds file and field).
DecodedImage decodeImageRgba8(std::span<const uint8_t> bytes, ImageFormat format);

}  // namespace preskin::gltf
