// JsonWriter: a streaming front end over nlohmann::ordered_json for the tool's reports
// (`preskin bench`, `preskin compare`): values are added in the order they are measured (keys keep
// that order) and nlohmann serialises them (two-space indentation, doubles in their shortest
// round-trip form, non-finite numbers as null). Reports are written with preskin::writeTextFile.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace preskin::cli {

class JsonWriter {
public:
    void beginObject() { open(nlohmann::ordered_json::object()); }
    void endObject() { open_.pop_back(); }
    void beginArray() { open(nlohmann::ordered_json::array()); }
    void endArray() { open_.pop_back(); }
    void key(std::string_view k) { key_ = std::string(k); }
    void number(double v) { add(v); }
    void integer(uint64_t v) { add(v); }
    void boolean(bool v) { add(v); }
    void string(std::string_view v) { add(std::string(v)); }
    template <typename T>
    void field(std::string_view k, T v) {
        key(k);
        if constexpr (std::is_same_v<T, bool>)
            boolean(v);
        else if constexpr (std::is_integral_v<T>)
            integer(static_cast<uint64_t>(v));
        else if constexpr (std::is_floating_point_v<T>)
            number(double(v));
        else
            string(v);
    }
    std::string text() const { return root_.dump(2); }

private:
    nlohmann::ordered_json& add(nlohmann::ordered_json value) {
        if (open_.empty()) {
            root_ = std::move(value);
            return root_;
        }
        nlohmann::ordered_json& parent = *open_.back();
        if (parent.is_array()) {
            parent.push_back(std::move(value));
            return parent.back();
        }
        return parent[std::exchange(key_, {})] = std::move(value);
    }
    void open(nlohmann::ordered_json value) { open_.push_back(&add(std::move(value))); }

    nlohmann::ordered_json root_;
    std::vector<nlohmann::ordered_json*> open_;  // objects and arrays being filled, innermost last
    std::string key_;
};

}  // namespace preskin::cli
