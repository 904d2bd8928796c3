// Radiance RGBE decoding through stb_image (see RadianceFile.h).
#include "image/RadianceFile.h"

#include "env/EnvironmentHeader.h"

#include <stb/stb_image.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <string_view>

namespace preskin::image {

namespace {

[[noreturn]] void corrupt(const std::string& what) {
    throw std::runtime_error("cannot decode the Radiance HDR data: " + what);
}

// What the header lines say about the pixels (Ward, "Real Pixels"; Radiance's file formats):
// FORMAT (32-bit_rle_rgbe, the default when absent, or 32-bit_rle_xyze) and EXPOSURE (each line
// multiplies the factor the stored values carry: radiance = stored / product).
struct RadianceEncoding {
    bool xyz = false;
    bool formatLine = false;
    double exposure = 1.0;
};

RadianceEncoding readEncoding(std::span<const uint8_t> bytes, size_t headerEnd) {
    RadianceEncoding e;
    const std::string_view text(reinterpret_cast<const char*>(bytes.data()), headerEnd);
    for (size_t at = 0; at < text.size();) {
        size_t end = text.find('\n', at);
        if (end == std::string_view::npos) end = text.size();
        const std::string_view line = text.substr(at, end - at);
        at = end + 1;
        if (line.rfind("FORMAT=", 0) == 0) {
            const std::string_view format = line.substr(7);
            if (format == "32-bit_rle_xyze")
                e.xyz = true;
            else if (format != "32-bit_rle_rgbe")
                corrupt("FORMAT=" + std::string(format.substr(0, 40)) +
                        " is not decoded (32-bit_rle_rgbe and 32-bit_rle_xyze are)");
            e.formatLine = true;
        } else if (line.rfind("EXPOSURE=", 0) == 0) {
            const std::string value(line.substr(9, 40));
            char* last = nullptr;
            const double factor = std::strtod(value.c_str(), &last);
            if (last == value.c_str() || !std::isfinite(factor) || !(factor > 0.0))
                corrupt("EXPOSURE=" + value + " is not a positive number");
            e.exposure *= factor;
        }
    }
    if (!(e.exposure >= 1e-30 && e.exposure <= 1e30)) corrupt("the EXPOSURE lines multiply to beyond 1e30");
    return e;
}

// Walks the scanlines as stb_image 2.27 reads them, before it runs: that version loops forever on
// a run-length count of 0 (which is also what it reads past the end of a cut file), and reads a
// first scanline that is not run-length encoded as the start of flat data, but a later one as a
// restart at the first row. Refused here: data cut short, zero or overlong counts, a flat scanline
// after encoded ones.
void checkScanlines(std::span<const uint8_t> bytes, const env::EnvironmentHeader& header) {
    const uint64_t width = uint64_t(header.width), height = uint64_t(header.height);
    size_t at = header.pixelOffset;
    auto truncated = [&](uint64_t row) {
        corrupt("truncated: the data ends in scanline " + std::to_string(row) + " of " + std::to_string(height));
    };
    auto flat = [&] {
        if (bytes.size() < at || (bytes.size() - at) / 4 / width < height)
            truncated(bytes.size() < at ? 0 : (bytes.size() - at) / 4 / width);
    };
    if (width < 8 || width >= 32768) return flat();
    for (uint64_t row = 0; row < height; ++row) {
        if (bytes.size() - std::min(bytes.size(), at) < 4) truncated(row);
        if (bytes[at] != 2 || bytes[at + 1] != 2 || (bytes[at + 2] & 0x80)) {
            if (row == 0) return flat();
            corrupt("scanline " + std::to_string(row) + " is not run-length encoded, the ones before it are");
        }
        if ((uint64_t(bytes[at + 2]) << 8 | bytes[at + 3]) != width)
            corrupt("scanline " + std::to_string(row) + " states another width than the header");
        at += 4;
        for (int channel = 0; channel < 4; ++channel)
            for (uint64_t filled = 0; filled < width;) {
                if (at >= bytes.size()) truncated(row);
                const uint64_t count = bytes[at] > 128 ? bytes[at] - 128u : bytes[at];
                const bool run = bytes[at] > 128;
                if (count == 0 || count > width - filled)
                    corrupt("scanline " + std::to_string(row) + ": a run-length count of " + std::to_string(count) +
                            " where " + std::to_string(width - filled) + " texels are left");
                at += 1 + (run ? 1 : count);
                if (at > bytes.size()) truncated(row);
                filled += count;
            }
    }
}

}  // namespace

PixelImage decodeRadiance(std::span<const uint8_t> bytes, const SizeLimits& limits) {
    // (bytes may be replaced by a normalised copy of the header below)
    const env::EnvironmentHeader header =
        env::readEnvironmentHeader(bytes.first(std::min(bytes.size(), env::kEnvironmentHeaderBytes)));
    if (header.format != env::EnvironmentFormat::RadianceHdr)
        throw std::runtime_error("cannot decode the Radiance HDR data: not a Radiance file");
    checkImageSize(uint64_t(header.width), uint64_t(header.height), limits);
    if (bytes.size() > size_t(INT_MAX)) throw std::runtime_error("cannot decode the Radiance HDR data: file too large");
    checkScanlines(bytes, header);
    // stb_image reads RGBE with a FORMAT line: a header without one (RGBE by default), with XYZE
    // (its pixels are converted below) or with another program's signature is handed over with
    // the lines it reads.
    const RadianceEncoding encoding = readEncoding(bytes, header.pixelOffset);
    std::vector<uint8_t> normalised;
    const std::string_view whole(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    const size_t firstLine = whole.find('\n');
    const std::string_view signature = whole.substr(0, firstLine);
    if (encoding.xyz || !encoding.formatLine || (signature != "#?RADIANCE" && signature != "#?RGBE")) {
        // (stb_image also knows only the #?RADIANCE and #?RGBE signatures of "#?<program>")
        const std::string_view lines = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n";
        normalised.reserve(bytes.size() + lines.size());
        normalised.insert(normalised.end(), lines.begin(), lines.end());
        for (size_t at = firstLine + 1; at < header.pixelOffset;) {  // the other lines, FORMAT dropped
            size_t end = at;
            while (end < header.pixelOffset && bytes[end] != '\n') ++end;
            const std::string_view text(reinterpret_cast<const char*>(bytes.data()) + at, end - at);
            if (text.rfind("FORMAT=", 0) != 0)
                normalised.insert(normalised.end(), bytes.begin() + std::ptrdiff_t(at),
                                  bytes.begin() + std::ptrdiff_t(std::min(end + 1, header.pixelOffset)));
            at = end + 1;
        }
        normalised.insert(normalised.end(), bytes.begin() + std::ptrdiff_t(header.pixelOffset), bytes.end());
        bytes = normalised;
    }
    // stb_image reports failures in one process-wide string: decodes are serialised to read it.
    static std::mutex mutex;
    const std::lock_guard lock(mutex);
    int width = 0, height = 0, channels = 0;
    std::unique_ptr<float, void (*)(void*)> data(
        stbi_loadf_from_memory(bytes.data(), int(bytes.size()), &width, &height, &channels, 3), &stbi_image_free);
    if (!data) {
        const char* why = stbi_failure_reason();
        throw std::runtime_error(std::string("cannot decode the Radiance HDR data: ") + (why ? why : "unknown error"));
    }
    if (int64_t(width) != header.width || int64_t(height) != header.height)
        throw std::runtime_error("cannot decode the Radiance HDR data: the decoder reads " + std::to_string(width) +
                                 "x" + std::to_string(height) + ", the header says " + std::to_string(header.width) +
                                 "x" + std::to_string(header.height));
    PixelImage out;
    out.width = uint32_t(width);
    out.height = uint32_t(height);
    out.channels = 3;
    std::vector<float> rgb(data.get(), data.get() + out.valueCount());
    data.reset();
    // XYZE: CIE XYZ to RGB with Radiance's own primaries (0.640 0.330, 0.290 0.600, 0.150 0.060)
    // and equal-energy white (its color.h), so an XYZE file gives what Radiance's RGBE would.
    constexpr float kXyzToRgb[3][3] = {{2.5653128f, -1.1668496f, -0.3984632f},
                                       {-1.0221082f, 1.9782866f, 0.0438216f},
                                       {0.0747244f, -0.2519396f, 1.1772152f}};
    const float scale = float(1.0 / encoding.exposure);
    for (size_t i = 0; i < rgb.size(); i += 3) {
        const float x = rgb[i], y = rgb[i + 1], z = rgb[i + 2];
        for (int c = 0; c < 3 && encoding.xyz; ++c)
            rgb[i + size_t(c)] = kXyzToRgb[c][0] * x + kXyzToRgb[c][1] * y + kXyzToRgb[c][2] * z;
        for (int c = 0; c < 3; ++c) rgb[i + size_t(c)] *= scale;
    }
    out.texels = std::move(rgb);
    return out;
}

}  // namespace preskin::image
