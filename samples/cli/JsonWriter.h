// JsonWriter: a small streaming JSON writer for the tool's reports (`preskin bench`, `preskin
// compare`): two-space indentation, one value per line, numbers with 6 significant digits (so a
// report is stable when the measured values are), non-finite numbers as null. Also the atomic
// text-file write the reports use.
#pragma once

#include <fmt/core.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace preskin::cli {

class JsonWriter {
public:
    void beginObject() { open('{'); }
    void endObject() { close('}'); }
    void beginArray() { open('['); }
    void endArray() { close(']'); }
    void key(std::string_view k) {
        separate();
        text_ += quote(k) + ": ";
        afterKey_ = true;
    }
    void number(double v) {
        separate();
        text_ += std::isfinite(v) ? fmt::format("{:.6g}", v) : "null";
    }
    void integer(uint64_t v) {
        separate();
        text_ += fmt::format("{}", v);
    }
    void boolean(bool v) {
        separate();
        text_ += v ? "true" : "false";
    }
    void string(std::string_view v) {
        separate();
        text_ += quote(v);
    }
    template <typename T>
    void field(std::string_view k, T v) {
        key(k);
        if constexpr (std::is_same_v<T, bool>) boolean(v);
        else if constexpr (std::is_integral_v<T>) integer(static_cast<uint64_t>(v));
        else if constexpr (std::is_floating_point_v<T>) number(double(v));
        else string(v);
    }
    const std::string& text() const { return text_; }

private:
    static std::string quote(std::string_view s) {
        std::string out = "\"";
        for (char c : s) {
            if (c == '"' || c == '\\') out += '\\', out += c;
            else if (static_cast<unsigned char>(c) < 0x20) out += fmt::format("\\u{:04x}", int(c));
            else out += c;
        }
        return out + "\"";
    }
    void separate() {
        if (afterKey_) {
            afterKey_ = false;
            return;
        }
        if (!first_.empty()) {
            if (!first_.back()) text_ += ",";
            first_.back() = false;
            text_ += "\n" + std::string(2 * first_.size(), ' ');
        }
    }
    void open(char c) {
        separate();
        text_ += c;
        first_.push_back(true);
    }
    void close(char c) {
        const bool empty = first_.back();
        first_.pop_back();
        if (!empty) text_ += "\n" + std::string(2 * first_.size(), ' ');
        text_ += c;
    }
    std::string text_;
    std::vector<bool> first_;
    bool afterKey_ = false;
};

// Writes `text` to `path` through a temporary file renamed into place; throws preskin::Error
// "<flag> <path>: cannot write" on failure (no partial file is left).
void writeTextFile(const std::filesystem::path& path, const std::string& text, const char* flag);

}  // namespace preskin::cli
