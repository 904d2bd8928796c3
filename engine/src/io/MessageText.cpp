// One-line, length-bounded message text (see MessageText.h).
#include "io/MessageText.h"

namespace preskin::io {

std::string messageText(std::string_view text, size_t maxChars) {
    std::string out;
    for (const char c : text) {
        if (out.size() >= maxChars) {
            out += "...";
            break;
        }
        if (c == '\n' || c == '\r') {
            if (!out.empty() && out.back() != ' ') out += "; ";
        } else if (static_cast<unsigned char>(c) >= 0x20 && c != 0x7f) {
            out += c;
        }
    }
    while (!out.empty() && (out.back() == ' ' || out.back() == ';')) out.pop_back();
    return out;
}

std::string jsonExcerpt(const nlohmann::json& value, size_t maxChars) {
    // Values reach here only from documents whose depth was bounded when they were parsed.
    return messageText(value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace), maxChars);
}

}  // namespace preskin::io
