// The one exception type of the public API. Every message names where the problem is (a file,
// and inside it a field or element) and what is wrong, in one line, e.g.
//   "scene.gltf: accessors[3].count: 4294967295 exceeds the buffer view (1024 bytes)".
#pragma once

#include <preskin/Export.h>

#include <stdexcept>
#include <string>

namespace preskin {

class PRESKIN_API Error : public std::runtime_error {
public:
    explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace preskin
