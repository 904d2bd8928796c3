// Depth- and size-limited JSON parsing (see JsonDocument.h).
#include "io/JsonDocument.h"
#include "io/MessageText.h"

#include <preskin/Error.h>

namespace preskin::io {

namespace {

using json = nlohmann::json;

// A first pass over the text that builds nothing: nlohmann's SAX interface reports each value
// and each container, so depth and count are checked in constant memory, and parsing stops at
// the first value past a limit. (The DOM parser with a callback would do it in one pass, but
// it removes values from their parent with a linear scan, quadratic in large arrays.)
class LimitCheck final : public nlohmann::json_sax<json> {
public:
    explicit LimitCheck(const JsonLimits& limits) : limits_(limits) {}

    bool null() override { return value(); }
    bool boolean(bool) override { return value(); }
    bool number_integer(number_integer_t) override { return value(); }
    bool number_unsigned(number_unsigned_t) override { return value(); }
    bool number_float(number_float_t, const string_t&) override { return value(); }
    bool string(string_t&) override { return value(); }
    bool binary(binary_t&) override { return value(); }
    bool start_object(std::size_t) override { return enter(); }
    bool key(string_t&) override { return true; }
    bool end_object() override { return leave(); }
    bool start_array(std::size_t) override { return enter(); }
    bool end_array() override { return leave(); }
    bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception& e) override {
        syntax_ = e.what();
        return false;
    }

    const std::string& problem() const { return problem_; }
    const std::string& syntax() const { return syntax_; }

private:
    bool value() {
        if (++values_ <= limits_.maxValues) return true;
        problem_ = "more than the limit of " + std::to_string(limits_.maxValues) + " values";
        return false;
    }
    bool enter() {
        if (++depth_ > limits_.maxDepth) {
            problem_ = "nested deeper than the limit of " + std::to_string(limits_.maxDepth) + " levels";
            return false;
        }
        return value();
    }
    bool leave() {
        --depth_;
        return true;
    }

    const JsonLimits& limits_;
    int depth_ = 0;
    uint64_t values_ = 0;
    std::string problem_;
    std::string syntax_;
};

// nlohmann's messages start with "[json.exception.parse_error.101] "; keep what follows.
std::string withoutPrefix(std::string what) {
    if (!what.empty() && what[0] == '[') {
        const size_t end = what.find("] ");
        if (end != std::string::npos) what = what.substr(end + 2);
    }
    return what;
}

template <typename Iterator>
json parseBounded(Iterator first, Iterator last, const std::string& label, const JsonLimits& limits) {
    LimitCheck check(limits);
    if (!json::sax_parse(first, last, &check)) {
        const std::string& problem = check.problem().empty() ? check.syntax() : check.problem();
        throw Error(label + ": JSON: " + messageText(withoutPrefix(problem), 2 * kMessageExcerptChars));
    }
    try {
        return json::parse(first, last);
    } catch (const json::exception& e) {  // not expected after the first pass accepted the text
        throw Error(label + ": JSON: " + messageText(withoutPrefix(e.what()), 2 * kMessageExcerptChars));
    }
}

}  // namespace

json parseJson(std::span<const uint8_t> text, const std::string& label, const JsonLimits& limits) {
    return parseBounded(text.begin(), text.end(), label, limits);
}

json parseJson(std::string_view text, const std::string& label, const JsonLimits& limits) {
    return parseBounded(text.begin(), text.end(), label, limits);
}

}  // namespace preskin::io
