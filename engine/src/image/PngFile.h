// PNG through libpng, the core's own: decoding to RGBA (8 or 16 bits as stored; grey becomes RGB,
// palettes are expanded, missing alpha becomes opaque) and writing 1 to 4 channels at 8 or 16
// bits. libpng's error and warning handlers are replaced, so it prints nothing.
#pragma once

#include <preskin/ImageCodec.h>

#include "image/ImageFormat.h"

#include <filesystem>
#include <span>

namespace preskin::image {

// Throws std::runtime_error "cannot decode the PNG data: <libpng's reason>" or the size refusal
// (before any pixel memory is allocated).
PixelImage decodePng(std::span<const uint8_t> bytes, const SizeLimits& limits);
// 8- or 16-bit texels; throws std::runtime_error on a float image or a failed write.
void encodePng(const std::filesystem::path& path, const PixelImage& image);

}  // namespace preskin::image
