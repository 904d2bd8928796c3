// Names from a scene file in one-line error messages: control characters become '?' and long
// names are cut, so a message stays one short line whatever the file holds.
#pragma once

#include <string>

namespace preskin::anim {

inline std::string printable(const std::string& text, size_t maxChars = 200) {
    std::string out = text.substr(0, maxChars);
    for (char& c : out)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
    return out;
}

}  // namespace preskin::anim
