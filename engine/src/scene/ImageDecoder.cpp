// PNG/JPEG decoding to RGBA8 with OpenImageIO from memory (see ImageDecoder.h).
#include "scene/ImageDecoder.h"
#include "scene/GltfFiles.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>

namespace preskin::gltf {

namespace {

bool startsWith(std::span<const uint8_t> bytes, std::initializer_list<uint8_t> magic, size_t offset = 0) {
    if (bytes.size() < offset + magic.size()) return false;
    size_t i = offset;
    for (uint8_t m : magic) {
        if (bytes[i++] != m) return false;
    }
    return true;
}

// A temporary file removed on destruction, for OIIO readers without IOProxy support.
class TempFile {
public:
    TempFile(std::span<const uint8_t> bytes, const char* extension) {
        const char* dir = std::getenv("TMPDIR");
        std::string pattern = std::string(dir && *dir ? dir : "/tmp") + "/preskin-image-XXXXXX" + extension;
        std::vector<char> name(pattern.begin(), pattern.end());
        name.push_back('\0');
        const int fd = mkstemps(name.data(), static_cast<int>(std::strlen(extension)));
        if (fd < 0) throw std::runtime_error("cannot create a temporary file to decode from");
        path_ = name.data();
        size_t written = 0;
        while (written < bytes.size()) {
            const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
            if (n <= 0) {
                ::close(fd);
                throw std::runtime_error("cannot write a temporary file to decode from");
            }
            written += static_cast<size_t>(n);
        }
        ::close(fd);
    }
    ~TempFile() { std::remove(path_.c_str()); }
    TempFile(const TempFile&) = delete;
    TempFile& operator=(const TempFile&) = delete;
    const std::string& path() const { return path_; }

private:
    std::string path_;
};

}  // namespace

ImageFormat sniffImageFormat(std::span<const uint8_t> bytes) {
    if (startsWith(bytes, {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A})) return ImageFormat::Png;
    if (startsWith(bytes, {0xFF, 0xD8, 0xFF})) return ImageFormat::Jpeg;
    return ImageFormat::Unsupported;
}

std::string describeImageFormat(std::span<const uint8_t> bytes) {
    switch (sniffImageFormat(bytes)) {
    case ImageFormat::Png: return "PNG";
    case ImageFormat::Jpeg: return "JPEG";
    case ImageFormat::Unsupported: break;
    }
    if (startsWith(bytes, {'R', 'I', 'F', 'F'}) && startsWith(bytes, {'W', 'E', 'B', 'P'}, 8)) return "WebP";
    if (startsWith(bytes, {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB})) return "KTX2";
    if (startsWith(bytes, {'G', 'I', 'F', '8'})) return "GIF";
    if (startsWith(bytes, {'B', 'M'})) return "BMP";
    if (startsWith(bytes, {'D', 'D', 'S', ' '})) return "DDS";
    if (startsWith(bytes, {'#', '?'})) return "Radiance HDR";
    if (startsWith(bytes, {0x76, 0x2F, 0x31, 0x01})) return "OpenEXR";
    return "unknown";
}

DecodedImage decodeImageRgba8(std::span<const uint8_t> bytes, ImageFormat format) {
    const char* formatName = format == ImageFormat::Png ? "png" : format == ImageFormat::Jpeg ? "jpeg" : nullptr;
    if (!formatName) throw std::runtime_error("unsupported image format " + describeImageFormat(bytes));

    auto input = OIIO::ImageInput::create(formatName);
    if (!input) throw std::runtime_error(std::string("OpenImageIO has no ") + formatName + " reader");

    OIIO::Filesystem::IOMemReader memory(bytes.data(), bytes.size());
    std::unique_ptr<TempFile> temp;
    OIIO::ImageSpec config;
    // glTF colours are straight (unassociated) alpha; OIIO would premultiply PNG alpha otherwise.
    config.attribute("oiio:UnassociatedAlpha", 1);
    std::string openName;
    if (input->supports("ioproxy")) {
        void* proxy = &memory;
        config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
        openName = format == ImageFormat::Png ? "memory.png" : "memory.jpg";
    } else {
        temp = std::make_unique<TempFile>(bytes, format == ImageFormat::Png ? ".png" : ".jpg");
        openName = temp->path();
    }
    OIIO::ImageSpec spec;
    if (!input->open(openName, spec, config)) {
        std::string why = input->geterror();
        OIIO::geterror();  // clear any global message as well
        throw std::runtime_error("cannot decode the " + describeImageFormat(bytes) + " data: " +
                                 (why.empty() ? "unreadable header" : why));
    }
    const int channels = spec.nchannels;
    if (spec.width <= 0 || spec.height <= 0 || channels <= 0 || spec.depth > 1) {
        throw std::runtime_error("invalid image size " + std::to_string(spec.width) + " x " +
                                 std::to_string(spec.height) + " x " + std::to_string(channels) + " channels");
    }
    const auto width = static_cast<uint64_t>(spec.width);
    const auto height = static_cast<uint64_t>(spec.height);
    if (width > kMaxImageDimension || height > kMaxImageDimension || width * height > kMaxImagePixels) {
        throw std::runtime_error(std::to_string(width) + " x " + std::to_string(height) +
                                 " pixels exceeds the limit (" + std::to_string(kMaxImagePixels) + " pixels, " +
                                 std::to_string(kMaxImageDimension) + " per side)");
    }
    if (channels > 16) throw std::runtime_error(std::to_string(channels) + " channels");

    const auto pixelCount = static_cast<size_t>(width * height);
    std::vector<uint8_t> pixels(pixelCount * static_cast<size_t>(channels));
    const bool ok = input->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, pixels.data());
    std::string why = input->geterror();  // also catches "premature end of data" on a successful read
    OIIO::geterror();
    input->close();
    if (!ok || !why.empty()) {
        throw std::runtime_error("cannot decode the " + describeImageFormat(bytes) + " data: " +
                                 (why.empty() ? "read failed" : why));
    }

    DecodedImage out;
    out.width = static_cast<uint32_t>(width);
    out.height = static_cast<uint32_t>(height);
    out.rgba8.resize(pixelCount * 4);
    const auto stride = static_cast<size_t>(channels);
    for (size_t i = 0; i < pixelCount; ++i) {
        const uint8_t* src = pixels.data() + i * stride;
        uint8_t* dst = out.rgba8.data() + i * 4;
        if (channels <= 2) {
            dst[0] = dst[1] = dst[2] = src[0];
            dst[3] = channels == 2 ? src[1] : 255;
        } else {
            dst[0] = src[0];
            dst[1] = src[1];
            dst[2] = src[2];
            dst[3] = channels >= 4 ? src[3] : 255;
        }
    }
    return out;
}

}  // namespace preskin::gltf
