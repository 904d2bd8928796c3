// Decodes an encoded image held in memory (PNG or JPEG, the formats core glTF allows) into 8-bit
// RGBA, top row first, and 16-bit PNGs also into 16-bit RGBA: PNG with libpng (its error and
// warning handlers replaced, so it prints nothing), JPEG with OpenImageIO (through an in-memory
// IOProxy; where the OIIO build cannot read a format from memory, through a private temporary
// file instead). Grey becomes RGB, palettes are expanded, missing alpha becomes opaque, alpha
// stays straight (not premultiplied), the 8-bit copy of 16-bit data is rounded; gamma and colour
// profiles are not applied.
// Limits: the size is read from the header (PNG IHDR, JPEG SOF) and checked before any pixel
// memory is allocated: limits::kMaxImagePixels per image, kMaxImageSide per side, and the
// caller's remaining budget of the scene's limits::kMaxSceneImagePixels.
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
    std::vector<uint16_t> rgba16;  // 16-bit PNGs only, in full precision; empty otherwise
};

// Throws std::runtime_error with the reason (the caller adds file and field). `scenePixelsLeft`
// is what the scene's pixel limit still allows.
DecodedImage decodeImage(std::span<const uint8_t> bytes, ImageFormat format, uint64_t scenePixelsLeft);

}  // namespace preskin::gltf
