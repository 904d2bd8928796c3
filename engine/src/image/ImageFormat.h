// Image formats recognised by their leading bytes (magic numbers), never by names or media types.
#pragma once

#include <cstdint>
#include <span>
#include <string>

namespace preskin::image {

enum class ImageFormat { Png, Jpeg, RadianceHdr, OpenExr, Tiff, WebP, Ktx2, Gif, Bmp, Dds, Unknown };

ImageFormat sniffImageFormat(std::span<const uint8_t> head);
// "PNG", "JPEG", "Radiance HDR", "OpenEXR", "TIFF", ... "unknown".
const char* formatName(ImageFormat format);
// True for the formats the image component preskin::imageio decodes and the core does not.
bool decodedByImageComponent(ImageFormat format);

// The size check every decoder makes from the header, before it allocates for pixels: throws
// std::runtime_error "<w> x <h> pixels exceeds ..." beyond maxSide, limits::kMaxImagePixels (per
// image) or maxPixels (what the caller's budget, such as the scene's, leaves).
struct SizeLimits {
    uint64_t maxPixels = 0;
    uint32_t maxSide = 0;
};
void checkImageSize(uint64_t width, uint64_t height, const SizeLimits& limits);

}  // namespace preskin::image
