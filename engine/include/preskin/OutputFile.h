// The one way preskin writes a file (images, references, reports, LUT folders): a path that does
// not name a folder, under folders that exist or can be made, and never an existing file that is
// read-only or not a regular file. Missing folders are made when the file is written, not when
// it is checked, and the file is written to a temporary file beside it and renamed into place,
// so a failed run leaves neither a partial file nor an empty folder behind.
#pragma once

#include <preskin/Export.h>

#include <filesystem>
#include <functional>
#include <string>

namespace preskin {

// Throws preskin::Error "<path>: output: <problem>" unless `path` can be written under the rule
// above; call before expensive work.
PRESKIN_API void checkOutputFile(const std::filesystem::path& path);

// Checks `path`, makes its missing folders, calls `write(temporary)` to write the whole file
// there and renames it to `path`. On any failure (write throwing included) the temporary file
// and the folders made for it are removed and preskin::Error naming `path` is thrown.
PRESKIN_API void writeOutputFile(const std::filesystem::path& path,
                                 const std::function<void(const std::filesystem::path& temporary)>& write);

// writeOutputFile of `text`, byte for byte.
PRESKIN_API void writeTextFile(const std::filesystem::path& path, const std::string& text);

}  // namespace preskin
