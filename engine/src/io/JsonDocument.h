// The one JSON parser of preskin's inputs (glTF, diffusion profiles, LUT manifests): nlohmann's
// DOM parser, after a first SAX pass (no memory) has checked the depth limit (nested arrays and
// objects) and the value-count limit, so a document can neither overflow the stack of anything
// that later walks it recursively (dump, comparison, tinygltf) nor blow up in memory. Errors are
// one preskin::Error "<label>: JSON: <problem>" (syntax errors as nlohmann words them).
#pragma once

#include <preskin/Limits.h>

#include <nlohmann/json.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace preskin::io {

struct JsonLimits {
    int maxDepth = limits::kMaxJsonDepth;
    uint64_t maxValues = limits::kMaxJsonValues;
};

nlohmann::json parseJson(std::span<const uint8_t> text, const std::string& label, const JsonLimits& limits = {});
nlohmann::json parseJson(std::string_view text, const std::string& label, const JsonLimits& limits = {});

}  // namespace preskin::io
