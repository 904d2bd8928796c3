// Radiance RGBE decoding through stb_image (see RadianceFile.h).
#include "image/RadianceFile.h"

#include "env/EnvironmentHeader.h"

#include <stb/stb_image.h>

#include <algorithm>
#include <climits>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>

namespace preskin::image {

namespace {

[[noreturn]] void corrupt(const std::string& what) {
    throw std::runtime_error("cannot decode the Radiance HDR data: " + what);
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
    const env::EnvironmentHeader header = env::readEnvironmentHeader(bytes.first(std::min(bytes.size(), env::kEnvironmentHeaderBytes)));
    if (header.format != env::EnvironmentFormat::RadianceHdr)
        throw std::runtime_error("cannot decode the Radiance HDR data: not a Radiance file");
    checkImageSize(uint64_t(header.width), uint64_t(header.height), limits);
    if (bytes.size() > size_t(INT_MAX)) throw std::runtime_error("cannot decode the Radiance HDR data: file too large");
    checkScanlines(bytes, header);
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
    out.texels = std::vector<float>(data.get(), data.get() + out.valueCount());
    return out;
}

}  // namespace preskin::image
