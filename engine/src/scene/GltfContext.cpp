// Typed, checked reads of extension fields held as tinygltf::Value (see GltfContext.h).
#include "scene/GltfContext.h"

#include <cmath>

namespace preskin::gltf {

namespace {

const tinygltf::Value* find(const tinygltf::Value& object, const char* key) {
    if (!object.IsObject() || !object.Has(key)) return nullptr;
    return &object.Get(key);
}

double finiteNumber(const LoadContext& ctx, const tinygltf::Value& v, const std::string& where) {
    if (!v.IsNumber()) ctx.fail(where, "not a number");
    return checkedNumber(ctx, v.GetNumberAsDouble(), where);
}

template <int N>
std::optional<glm::vec<N, float>> vecField(const LoadContext& ctx, const tinygltf::Value& object, const char* key,
                                           const std::string& where) {
    const tinygltf::Value* v = find(object, key);
    if (!v) return std::nullopt;
    const std::string at = where + "." + key;
    if (!v->IsArray() || v->ArrayLen() != static_cast<size_t>(N)) {
        ctx.fail(at, "not an array of " + std::to_string(N) + " numbers");
    }
    glm::vec<N, float> out(0.0f);
    for (int i = 0; i < N; ++i) {
        out[i] = static_cast<float>(finiteNumber(ctx, v->Get(i), at + "[" + std::to_string(i) + "]"));
    }
    return out;
}

}  // namespace

std::optional<double> numberField(const LoadContext& ctx, const tinygltf::Value& object, const char* key,
                                  const std::string& where) {
    const tinygltf::Value* v = find(object, key);
    if (!v) return std::nullopt;
    return finiteNumber(ctx, *v, where + "." + key);
}

std::optional<int> integerField(const LoadContext& ctx, const tinygltf::Value& object, const char* key,
                                const std::string& where) {
    const tinygltf::Value* v = find(object, key);
    if (!v) return std::nullopt;
    const double d = finiteNumber(ctx, *v, where + "." + key);
    if (d != std::floor(d) || d < -2147483648.0 || d > 2147483647.0) ctx.fail(where + "." + key, "not an integer");
    return static_cast<int>(d);
}

std::optional<bool> boolField(const LoadContext& ctx, const tinygltf::Value& object, const char* key,
                              const std::string& where) {
    const tinygltf::Value* v = find(object, key);
    if (!v) return std::nullopt;
    if (!v->IsBool()) ctx.fail(where + "." + key, "not a boolean");
    return v->Get<bool>();
}

std::optional<std::string> stringField(const LoadContext& ctx, const tinygltf::Value& object, const char* key,
                                       const std::string& where) {
    const tinygltf::Value* v = find(object, key);
    if (!v) return std::nullopt;
    if (!v->IsString()) ctx.fail(where + "." + key, "not a string");
    return v->Get<std::string>();
}

std::optional<glm::vec2> vec2Field(const LoadContext& ctx, const tinygltf::Value& object, const char* key,
                                   const std::string& where) {
    return vecField<2>(ctx, object, key, where);
}

std::optional<glm::vec3> vec3Field(const LoadContext& ctx, const tinygltf::Value& object, const char* key,
                                   const std::string& where) {
    return vecField<3>(ctx, object, key, where);
}

std::optional<std::vector<double>> fixedArray(const LoadContext& ctx, const std::vector<double>& values, size_t length,
                                              const std::string& where) {
    if (values.empty()) return std::nullopt;
    if (values.size() != length) {
        ctx.fail(where, std::to_string(values.size()) + " numbers, expected " + std::to_string(length));
    }
    for (size_t i = 0; i < values.size(); ++i) checkedNumber(ctx, values[i], where + "[" + std::to_string(i) + "]");
    return values;
}

}  // namespace preskin::gltf
