// The codec registry behind <preskin/ImageCodec.h>, and conversions of decoded pixels to what
// preskin's users of images hold.
#pragma once

#include <preskin/ImageCodec.h>

#include <memory>
#include <vector>

namespace preskin::image {

// The built-in codec: PNG, JPEG and Radiance HDR in, PNG out.
std::shared_ptr<const ImageCodec> builtinCodec();

// The first codec that writes `path`'s extension; throws preskin::Error "<path>: output: no
// writer for '.exr' files ..." (naming preskin::imageio where it writes them) when none does.
std::shared_ptr<const ImageCodec> encoderFor(const std::filesystem::path& path);

// Replaces the registered codecs for its lifetime (tests: the core as a host sees it without
// the image component), restoring them after.
class ScopedCodecs {
public:
    explicit ScopedCodecs(std::vector<std::shared_ptr<const ImageCodec>> registered);
    ~ScopedCodecs();
    ScopedCodecs(const ScopedCodecs&) = delete;
    ScopedCodecs& operator=(const ScopedCodecs&) = delete;

private:
    std::vector<std::shared_ptr<const ImageCodec>> saved_;
};

// RGBA at 8 bits, and at 16 bits when the source has more than 8 (16-bit integers; floats,
// clamped to [0, 1]); the 8-bit copy of 16-bit data is rounded. Grey becomes RGB, missing alpha
// opaque.
void toRgba(const PixelImage& image, std::vector<uint8_t>& rgba8, std::vector<uint16_t>& rgba16);
// The first three channels as floats (8- and 16-bit values scaled to [0, 1]); grey is repeated.
std::vector<float> toRgbFloat(const PixelImage& image);

}  // namespace preskin::image
