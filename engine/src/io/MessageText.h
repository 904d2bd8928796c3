// Text from input files or third-party libraries placed into an error message: one line (line
// breaks become "; ", other control characters are dropped) and at most `maxChars` characters
// (cut with "..."), so no input can stretch a message over lines or megabytes.
#pragma once

#include <preskin/Export.h>

#include <nlohmann/json.hpp>

#include <string>
#include <string_view>

namespace preskin::io {

inline constexpr size_t kMessageExcerptChars = 120;

// Exported (not installed) for preskin_reference.
PRESKIN_API std::string messageText(std::string_view text, size_t maxChars = kMessageExcerptChars);

// A JSON value as written in JSON, for messages ("got {\"a\": 1}"), cut as above.
std::string jsonExcerpt(const nlohmann::json& value, size_t maxChars = kMessageExcerptChars);

}  // namespace preskin::io
