// OpenImageIO as an image codec (see <preskin/imageio/ImageIo.h>).
#include <preskin/imageio/ImageIo.h>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

namespace preskin::imageio {

namespace {

bool startsWith(std::span<const uint8_t> bytes, std::initializer_list<uint8_t> magic) {
    if (bytes.size() < magic.size()) return false;
    return std::equal(magic.begin(), magic.end(), bytes.begin());
}

// The formats this component adds, by magic number, and OpenImageIO's reader for each.
const char* readerFor(std::span<const uint8_t> head, std::string* formatName) {
    auto named = [&](const char* format, const char* reader) {
        if (formatName) *formatName = format;
        return reader;
    };
    if (startsWith(head, {0x76, 0x2F, 0x31, 0x01})) return named("OpenEXR", "openexr");
    if (startsWith(head, {'I', 'I', 42, 0}) || startsWith(head, {'M', 'M', 0, 42}) ||
        startsWith(head, {'I', 'I', 43, 0}) || startsWith(head, {'M', 'M', 0, 43}))
        return named("TIFF", "tiff");
    return nullptr;
}

// Takes OpenImageIO's pending error text (its messages are per thread and must be cleared).
std::string oiioError(const std::string& own) {
    std::string global = OIIO::geterror();
    if (!own.empty()) return own;
    return global.empty() ? std::string("unknown OpenImageIO error") : global;
}

// A temporary file removed on destruction, for readers without in-memory input.
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
                std::remove(path_.c_str());
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

class OpenImageIoCodec final : public ImageCodec {
public:
    std::string name() const override {
        return std::string("OpenImageIO ") + OIIO_VERSION_STRING + " (preskin::imageio)";
    }

    std::string decodes(std::span<const uint8_t> head) const override {
        std::string format;
        return readerFor(head, &format) ? format : std::string();
    }

    PixelImage decode(std::span<const uint8_t> bytes, const DecodeLimits& limits) const override {
        std::string formatName;
        const char* reader = readerFor(bytes, &formatName);
        if (!reader) throw std::runtime_error("not OpenEXR or TIFF data");
        auto input = OIIO::ImageInput::create(reader);
        if (!input) throw std::runtime_error("OpenImageIO has no " + std::string(reader) + " reader: " + oiioError({}));
        OIIO::Filesystem::IOMemReader memory(bytes.data(), bytes.size());
        std::unique_ptr<TempFile> temp;
        OIIO::ImageSpec config;
        config.attribute("oiio:UnassociatedAlpha", 1);  // straight alpha, as glTF's
        std::string openName;
        if (input->supports("ioproxy")) {
            void* proxy = &memory;
            config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
            openName = std::string("memory.") + reader;
        } else {
            temp = std::make_unique<TempFile>(bytes, formatName == "TIFF" ? ".tif" : ".exr");
            openName = temp->path();
        }
        OIIO::ImageSpec spec;
        if (!input->open(openName, spec, config))
            throw std::runtime_error("cannot decode the " + formatName + " data: " + oiioError(input->geterror()));
        if (spec.width <= 0 || spec.height <= 0 || spec.depth > 1 || spec.deep || spec.nchannels <= 0)
            throw std::runtime_error("cannot decode the " + formatName + " data: not a 2D image (" +
                                     std::to_string(spec.width) + "x" + std::to_string(spec.height) + "x" +
                                     std::to_string(spec.depth) + (spec.deep ? ", deep)" : ")"));
        const uint64_t width = uint64_t(spec.width), height = uint64_t(spec.height);
        if (width > limits.maxSide || height > limits.maxSide || width * height > limits.maxPixels)
            throw std::runtime_error(std::to_string(width) + " x " + std::to_string(height) +
                                     " pixels exceeds the limits of " + std::to_string(limits.maxSide) +
                                     " per side and " + std::to_string(limits.maxPixels) + " pixels");
        PixelImage out;
        out.width = uint32_t(width);
        out.height = uint32_t(height);
        out.channels = uint32_t(std::min(spec.nchannels, 4));
        const int channelEnd = int(out.channels);
        // Integer sources keep their depth (8 or 16 bits); everything else reads as float.
        // Scanline files are read in bands of rows, so a file whose pixels stop early fails before
        // the whole image is allocated; tiled files are read whole (OpenImageIO 2.4 faults reading
        // scanlines of a tiled EXR).
        const auto read = [&](auto& texels, OIIO::TypeDesc type) {
            if (spec.tile_width > 0) {
                texels.resize(out.valueCount());
                return input->read_image(0, 0, 0, channelEnd, type, texels.data());
            }
            constexpr int kBandRows = 64;
            const size_t rowValues = size_t(out.width) * out.channels;
            for (int y = 0; y < spec.height; y += kBandRows) {
                const int end = std::min(spec.height, y + kBandRows);
                const size_t offset = texels.size();
                texels.resize(offset + rowValues * size_t(end - y));
                if (!input->read_scanlines(0, 0, spec.y + y, spec.y + end, 0, 0, channelEnd, type,
                                           texels.data() + offset))
                    return false;
            }
            return true;
        };
        bool ok = false;
        if (spec.format == OIIO::TypeDesc::UINT8)
            ok = read(out.texels.emplace<std::vector<uint8_t>>(), OIIO::TypeDesc::UINT8);
        else if (spec.format == OIIO::TypeDesc::UINT16)
            ok = read(out.texels.emplace<std::vector<uint16_t>>(), OIIO::TypeDesc::UINT16);
        else
            ok = read(out.texels.emplace<std::vector<float>>(), OIIO::TypeDesc::FLOAT);
        const std::string why = input->geterror();
        OIIO::geterror();
        input->close();
        if (!ok || !why.empty())
            throw std::runtime_error("cannot decode the " + formatName +
                                     " data: " + (why.empty() ? std::string("read failed") : why));
        return out;
    }

    bool encodes(std::string_view extension) const override { return extension == ".exr"; }

    void encode(const std::filesystem::path& path, const PixelImage& image,
                const EncodeOptions& options) const override {
        const auto* values = std::get_if<std::vector<float>>(&image.texels);
        if (!values) throw std::runtime_error("OpenEXR output takes float images");
        OIIO::ImageSpec spec(int(image.width), int(image.height), int(image.channels),
                             options.halfFloat ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT);
        spec.attribute("compression", "zip");
        spec.attribute("oiio:ColorSpace", "Linear");
        spec.attribute("DateTime", "");  // no time stamp: the same image is the same bytes
        for (const auto& [key, value] : options.attributes) spec.attribute(key, value);
        auto out = OIIO::ImageOutput::create("openexr");
        if (!out) throw std::runtime_error("no OpenEXR writer: " + oiioError({}));
        if (!out->open(path.string(), spec))
            throw std::runtime_error("cannot create file: " + oiioError(out->geterror()));
        if (!out->write_image(OIIO::TypeDesc::FLOAT, values->data())) {
            const std::string error = oiioError(out->geterror());
            out->close();
            throw std::runtime_error("cannot write image: " + error);
        }
        if (!out->close()) throw std::runtime_error("cannot finish image: " + oiioError(out->geterror()));
    }
};

}  // namespace

std::shared_ptr<const ImageCodec> openImageIoCodec() {
    static const auto codec = std::make_shared<const OpenImageIoCodec>();
    return codec;
}

void registerCodecs() {
    static std::once_flag once;
    std::call_once(once, [] { registerImageCodec(openImageIoCodec()); });
}

}  // namespace preskin::imageio
