// Image files in and out of preskin, and how decoders and encoders are plugged in.
//
// The library decodes by itself what a scene and its environment usually need, with small
// packaged libraries: PNG (libpng; 8 and 16 bits), JPEG (libjpeg-turbo) and Radiance .hdr
// (stb_image), and writes PNG (libpng). Every other format comes from a codec registered here:
//  - the optional image component preskin::imageio (<preskin/imageio/ImageIo.h>, OpenImageIO)
//    adds OpenEXR and TIFF: EXR environments, EXR LUT folders, EXR output;
//  - a host registers its own (KTX2, WebP, its asset pipeline's formats), or hands preskin images
//    it decoded itself (SceneLoadOptions::decodeImage for textures, Environment::fromImage).
// Codecs registered later are asked first, so a host can replace a built-in decoder; the
// built-in ones are asked last. A file no codec reads is refused with its format's name and, for
// the formats preskin::imageio reads, the component to link.
//
// A codec must check the size its header states (against DecodeLimits) before it allocates for
// the pixels, must not print, and reports problems by throwing (std::exception: the caller adds
// the file and field to the message).
#pragma once

#include <preskin/Export.h>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace preskin {

// Decoded pixels: `channels` interleaved values per texel (1 grey, 2 grey + alpha, 3 RGB, 4 RGBA),
// top row first, alpha straight (not premultiplied). 8- and 16-bit values are as stored (no
// colour conversion); float values are linear.
struct PixelImage {
    uint32_t width = 0;
    uint32_t height = 0;
    uint32_t channels = 0;
    std::variant<std::vector<uint8_t>, std::vector<uint16_t>, std::vector<float>> texels;

    size_t valueCount() const { return size_t(width) * height * channels; }
    // True when the texel storage holds exactly width x height x channels values (1..4 channels).
    PRESKIN_API bool consistent() const;
};

// What a decoder may allocate: checked against the size in the file's header first.
struct DecodeLimits {
    uint64_t maxPixels = 0;
    uint32_t maxSide = 0;
};

// Options a writer honours where its format can (EXR: half floats, zip; metadata as attributes).
struct EncodeOptions {
    bool halfFloat = true;  // float formats: 16-bit half instead of 32-bit float
    std::vector<std::pair<std::string, std::string>> attributes;
};

class PRESKIN_API ImageCodec {
public:
    virtual ~ImageCodec();
    // For messages: "OpenImageIO 2.4 (preskin::imageio)".
    virtual std::string name() const = 0;
    // The format's name ("OpenEXR") when this codec decodes data that starts with `head` (the
    // file's first bytes: all of them, or at least 64 KiB), else an empty string.
    virtual std::string decodes(std::span<const uint8_t> head) const;
    // Decodes a whole file held in memory.
    virtual PixelImage decode(std::span<const uint8_t> bytes, const DecodeLimits& limits) const;
    // True when it writes files with this extension (lower case, with the dot: ".exr").
    virtual bool encodes(std::string_view extension) const;
    // Writes `image` to `path` (preskin passes a temporary name and renames it into place).
    virtual void encode(const std::filesystem::path& path, const PixelImage& image, const EncodeOptions& options) const;
};

// Adds a codec for every later load and write in the process (thread-safe; asked before the
// codecs registered earlier and before the built-in ones).
PRESKIN_API void registerImageCodec(std::shared_ptr<const ImageCodec> codec);
// Every codec in the order they are asked: the registered ones (newest first), then the built-in.
PRESKIN_API std::vector<std::shared_ptr<const ImageCodec>> imageCodecs();

// The format name of data starting with `head` as far as preskin knows it ("PNG", "JPEG",
// "Radiance HDR", "OpenEXR", "TIFF", "WebP", "KTX2", ... or "unknown"), whether or not a codec reads it.
PRESKIN_API std::string describeImageFormat(std::span<const uint8_t> head);

// Decodes with the first codec that reads the data. Throws preskin::Error "<label>: <problem>"
// when none does (naming the format, and preskin::imageio where it would read it) or the codec
// fails.
PRESKIN_API PixelImage decodeImage(std::span<const uint8_t> bytes, const DecodeLimits& limits,
                                   const std::string& label);
// True when a codec reads data starting with `head`.
PRESKIN_API bool canDecodeImage(std::span<const uint8_t> head);

// Writes `image` to `path` with the first codec that writes its extension, under the output
// rule of <preskin/OutputFile.h> (temporary file renamed into place). Throws preskin::Error
// naming the path when none does or the write fails.
PRESKIN_API void encodeImage(const std::filesystem::path& path, const PixelImage& image,
                             const EncodeOptions& options = {});
// True when a codec writes files with `path`'s extension.
PRESKIN_API bool canEncodeImage(const std::filesystem::path& path);

}  // namespace preskin
