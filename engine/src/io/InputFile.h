// The one way preskin reads a file it was given (scenes, buffers, images, profiles, manifests,
// environments, LUT tables): the path must name a regular file (a FIFO would block, a device
// such as /dev/zero never ends, a folder is not data) of at most `maxBytes`, all checked before
// a byte is read or allocated. Errors are one preskin::Error "<label>: file: <problem>".
// Exported (not installed) for preskin_reference, which reads its files under the same rule.
// Limits: the checks and the read are not atomic against a file changed meanwhile; a file that
// grows past its checked size is refused.
#pragma once

#include <preskin/Export.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace preskin::io {

// Reads the whole file.
PRESKIN_API std::vector<uint8_t> readInputFile(const std::filesystem::path& path, const std::string& label,
                                               uint64_t maxBytes);

// Checks the whole file, reads only its first `count` bytes (fewer when it is shorter): the
// header of a file a third-party reader then opens by name.
std::vector<uint8_t> readInputFileStart(const std::filesystem::path& path, const std::string& label, uint64_t maxBytes,
                                        uint64_t count);

// Checks the file without reading it, for files a third-party reader opens by name; returns its size.
PRESKIN_API uint64_t checkInputFile(const std::filesystem::path& path, const std::string& label, uint64_t maxBytes);

}  // namespace preskin::io
