// JPEG through libjpeg-turbo, the core's own decoder: baseline and progressive, grey, YCbCr and
// RGB (to RGB), CMYK and YCCK (Adobe's inverted ink values, multiplied out to RGB). libjpeg's
// default decoding (islow DCT, fancy upsampling), so pixels equal other libjpeg-based readers'.
// Colour profiles are not applied.
#pragma once

#include <preskin/ImageCodec.h>

#include "image/ImageFormat.h"

#include <span>

namespace preskin::image {

// Throws std::runtime_error "cannot decode the JPEG data: <reason>" or the size refusal (from the
// frame header, before any pixel memory is allocated). Returns 1 (grey) or 3 (RGB) channels.
PixelImage decodeJpeg(std::span<const uint8_t> bytes, const SizeLimits& limits);

}  // namespace preskin::image
