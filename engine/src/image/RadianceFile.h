// Radiance RGBE (.hdr) through stb_image (Debian's libstb), the core's own decoder: run-length
// encoded and flat scanlines, RGBE to linear RGB floats as Ward's reference code converts them
// (mantissa x 2^(exponent - 136), exponent 0 is black). FORMAT=32-bit_rle_xyze (CIE XYZ, turned
// into RGB with Radiance's primaries and white) and EXPOSURE lines (divided out) are honoured; a
// header without a FORMAT line is RGBE. The header's size is checked before
// decoding (EnvironmentHeader reads it the same way), and the scanlines are walked first (stb 2.27
// loops forever on some corrupt data: see RadianceFile.cpp). Orientations other than
// -Y +X are refused by EnvironmentHeader; other FORMATs are refused.
#pragma once

#include <preskin/ImageCodec.h>

#include "image/ImageFormat.h"

#include <span>

namespace preskin::image {

// Throws std::runtime_error "cannot decode the Radiance HDR data: <reason>" or the size refusal.
// Returns 3 float channels.
PixelImage decodeRadiance(std::span<const uint8_t> bytes, const SizeLimits& limits);

}  // namespace preskin::image
