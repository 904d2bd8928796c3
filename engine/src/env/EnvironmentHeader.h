// The format and the size of an environment image (or of any EXR, such as a LUT table), read from
// the first bytes of its file before any decoder allocates for it: Radiance RGBE (.hdr: "#?"
// signature, header lines, then the resolution line "-Y H +X W"; Greg Ward, "Real Pixels",
// Graphics Gems II) and OpenEXR (magic 76 2f 31 01, version 2, then the header's attributes, of
// which dataWindow gives the size; "The OpenEXR File Layout"). Only single-part, non-deep EXR
// files are images here.
// Limits: Radiance files in another orientation than -Y +X are reported as such.
#pragma once

#include <cstdint>
#include <span>
#include <string>

namespace preskin::env {

enum class EnvironmentFormat { RadianceHdr, OpenExr };

struct EnvironmentHeader {
    EnvironmentFormat format = EnvironmentFormat::RadianceHdr;
    int64_t width = 0;
    int64_t height = 0;
    size_t pixelOffset = 0;  // Radiance: where the scanlines start (after the resolution line)
};

// Parses `prefix` (the file's first bytes, up to 64 KiB). Throws std::runtime_error naming the
// problem ("format: ...", "size: ...") when the header cannot be read.
EnvironmentHeader readEnvironmentHeader(std::span<const uint8_t> prefix);

inline constexpr size_t kEnvironmentHeaderBytes = 64 * 1024;

}  // namespace preskin::env
