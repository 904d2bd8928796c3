// Environment image header parsing (see EnvironmentHeader.h).
#include "env/EnvironmentHeader.h"

#include <cstring>
#include <stdexcept>
#include <string_view>

namespace preskin::env {

namespace {

[[noreturn]] void fail(const std::string& field, const std::string& problem) {
    throw std::runtime_error(field + ": " + problem);
}

EnvironmentHeader radiance(std::span<const uint8_t> prefix) {
    const std::string_view text(reinterpret_cast<const char*>(prefix.data()), prefix.size());
    // Header lines up to an empty line, then the resolution line.
    size_t end = text.find("\n\n");
    if (end == std::string_view::npos) fail("header", "no end of the Radiance header in the first 64 KiB");
    const size_t lineStart = end + 2;
    const size_t lineEnd = text.find('\n', lineStart);
    const std::string_view line = text.substr(lineStart, lineEnd == std::string_view::npos ? 64 : lineEnd - lineStart);
    char ySign = 0, yAxis = 0, xSign = 0, xAxis = 0;
    long long height = 0, width = 0;
    const std::string copy(line.substr(0, 64));
    if (std::sscanf(copy.c_str(), "%c%c %lld %c%c %lld", &ySign, &yAxis, &height, &xSign, &xAxis, &width) != 6 ||
        yAxis != 'Y' || xAxis != 'X') {
        fail("resolution", "the Radiance resolution line is not '-Y <height> +X <width>'");
    }
    if (ySign != '-' || xSign != '+') fail("resolution", "orientation " + copy + " is not supported (only -Y +X)");
    if (lineEnd == std::string_view::npos) fail("resolution", "no end of the Radiance resolution line");
    return {EnvironmentFormat::RadianceHdr, width, height, lineEnd + 1};
}

int32_t readI32(std::span<const uint8_t> bytes, size_t offset) {
    int32_t v = 0;
    std::memcpy(&v, bytes.data() + offset, 4);  // little endian, as EXR and every supported platform
    return v;
}

EnvironmentHeader openExr(std::span<const uint8_t> prefix) {
    if (prefix.size() < 8) fail("header", "truncated OpenEXR header");
    const uint32_t version = static_cast<uint32_t>(readI32(prefix, 4));
    if ((version & 0xFF) != 2) fail("header", "OpenEXR version " + std::to_string(version & 0xFF) + " (2 is read)");
    if (version & 0x800) fail("header", "deep OpenEXR data is not an image here");
    if (version & 0x1000) fail("header", "multi-part OpenEXR files are not supported");
    size_t i = 8;
    auto nullTerminated = [&](const char* what) {
        const size_t start = i;
        while (i < prefix.size() && prefix[i] != 0) ++i;
        if (i >= prefix.size() || i - start > 255) fail("header", std::string("unreadable attribute ") + what);
        return std::string(reinterpret_cast<const char*>(prefix.data() + start), i++ - start);
    };
    while (true) {
        if (i >= prefix.size()) fail("header", "no dataWindow in the first 64 KiB of the OpenEXR header");
        const std::string name = nullTerminated("name");
        if (name.empty()) fail("header", "the OpenEXR header has no dataWindow");
        const std::string type = nullTerminated("type");
        if (i + 4 > prefix.size()) fail("header", "truncated OpenEXR attribute " + name);
        const int32_t size = readI32(prefix, i);
        i += 4;
        if (size < 0 || static_cast<size_t>(size) > prefix.size() - i)
            fail("header", "truncated OpenEXR attribute " + name);
        if (name == "dataWindow") {
            if (type != "box2i" || size != 16) fail("dataWindow", "not a box2i");
            const int64_t xMin = readI32(prefix, i), yMin = readI32(prefix, i + 4);
            const int64_t xMax = readI32(prefix, i + 8), yMax = readI32(prefix, i + 12);
            return {EnvironmentFormat::OpenExr, xMax - xMin + 1, yMax - yMin + 1};
        }
        i += static_cast<size_t>(size);
    }
}

}  // namespace

EnvironmentHeader readEnvironmentHeader(std::span<const uint8_t> prefix) {
    if (prefix.size() >= 2 && prefix[0] == '#' && prefix[1] == '?') return radiance(prefix);
    if (prefix.size() >= 4 && prefix[0] == 0x76 && prefix[1] == 0x2f && prefix[2] == 0x31 && prefix[3] == 0x01) {
        return openExr(prefix);
    }
    fail("format", "not a Radiance HDR or OpenEXR file");
}

}  // namespace preskin::env
