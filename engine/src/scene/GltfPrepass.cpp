// JSON-level checks before tinygltf parses the document (see GltfPrepass.h).
#include "scene/GltfPrepass.h"
#include "io/MessageText.h"
#include "io/NumberRule.h"
#include "scene/TinyGltf.h"
#include "skin/ProfileJson.h"

#include <preskin/Error.h>
#include <preskin/Limits.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <numbers>
#include <system_error>

namespace preskin::gltf {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Top-level arrays, and whether each is one of the large kinds with its own smaller limit.
struct TopLevelArray {
    const char* name;
    bool large;
};
constexpr TopLevelArray kTopLevelArrays[] = {
    {"accessors", false}, {"animations", false}, {"buffers", false}, {"bufferViews", false}, {"cameras", true},
    {"images", true},     {"materials", true},   {"meshes", false},  {"nodes", false},       {"samplers", true},
    {"scenes", false},    {"skins", false},      {"textures", true},
};

// The textureInfo objects of a core material, by path below the material.
constexpr const char* kMaterialTextures[][2] = {
    {"pbrMetallicRoughness", "baseColorTexture"},
    {"pbrMetallicRoughness", "metallicRoughnessTexture"},
    {nullptr, "normalTexture"},
    {nullptr, "occlusionTexture"},
    {nullptr, "emissiveTexture"},
};

struct Checker {
    const std::string& file;
    const fs::path& folder;
    bool allowOutsideLinks;

    [[noreturn]] void error(const std::string& where, const std::string& what) const { fail(file, where, what); }

    static const json* member(const json& object, const char* key) {
        if (!object.is_object()) return nullptr;
        auto it = object.find(key);
        return it == object.end() ? nullptr : &*it;
    }

    const json& array(const json& object, const char* key, const std::string& where) const {
        static const json empty = json::array();
        const json* v = member(object, key);
        if (!v) return empty;
        if (!v->is_array()) error(where.empty() ? key : where + "." + key, "not an array");
        return *v;
    }

    const json& object(const json& array, size_t i, const std::string& name) const {
        const json& v = array[i];
        if (!v.is_object()) error(indexed(name, i), "not an object");
        return v;
    }

    static std::string indexed(const std::string& name, size_t i) { return name + "[" + std::to_string(i) + "]"; }
    static std::string field(const std::string& where, const char* key) {
        return where.empty() ? key : where + "." + key;
    }

    // A non-negative integer field; nullopt when absent.
    std::optional<uint64_t> unsignedField(const json& object, const char* key, const std::string& where) const {
        const json* v = member(object, key);
        if (!v) return std::nullopt;
        return unsignedValue(*v, field(where, key));
    }

    uint64_t unsignedValue(const json& v, const std::string& where) const {
        if (v.is_number_unsigned()) return v.get<uint64_t>();
        if (v.is_number_integer()) error(where, std::to_string(v.get<int64_t>()) + " is negative");
        if (v.is_number_float()) {
            const double d = v.get<double>();
            if (std::isfinite(d) && d >= 0.0 && d == std::floor(d) && d < 9007199254740992.0) {
                return static_cast<uint64_t>(d);
            }
        }
        error(where, io::jsonExcerpt(v) + " is not a non-negative integer");
    }

    uint64_t requiredUnsigned(const json& object, const char* key, const std::string& where) const {
        auto v = unsignedField(object, key, where);
        if (!v) error(field(where, key), "missing");
        return *v;
    }

    void checkIndex(uint64_t index, size_t count, const std::string& where, const char* what) const {
        if (index >= count) {
            error(where,
                  std::to_string(index) + " is out of range: the file has " + std::to_string(count) + " " + what);
        }
    }

    // A glTFid: an integer >= 0 that indexes an array of `count` `what`.
    void idValue(const json& v, size_t count, const std::string& where, const char* what) const {
        checkIndex(unsignedValue(v, where), count, where, what);
    }
    void idField(const json& object, const char* key, size_t count, const std::string& where, const char* what,
                 bool required = false) const {
        const json* v = member(object, key);
        if (!v) {
            if (required) error(field(where, key), "missing");
            return;
        }
        idValue(*v, count, field(where, key), what);
    }
    void idArray(const json& object, const char* key, size_t count, const std::string& where, const char* what) const {
        const json& ids = array(object, key, where);
        for (size_t k = 0; k < ids.size(); ++k) idValue(ids[k], count, indexed(field(where, key), k), what);
    }

    // A number that passes the input-number rule; nullopt when absent.
    std::optional<double> numberField(const json& object, const char* key, const std::string& where) const {
        const json* v = member(object, key);
        if (!v) return std::nullopt;
        if (!v->is_number()) error(field(where, key), io::jsonExcerpt(*v) + " is not a number");
        const double d = v->get<double>();
        if (auto problem = io::numberProblem(d)) error(field(where, key), *problem);
        return d;
    }

    fs::path existingFile(const std::string& uri, const std::string& where) const {
        const fs::path path = resolveUri(uri, folder, file, where, allowOutsideLinks);
        std::error_code ec;
        const auto status = fs::status(path, ec);
        if (ec || !fs::exists(status)) error(where, "file '" + uri + "' not found next to the scene");
        if (!fs::is_regular_file(status)) error(where, "'" + uri + "' is not a regular file");
        return path;
    }

    // Every "extensions" member of every object must be an object of objects (glTF 2.0 schema:
    // extension.schema.json); tinygltf would drop other values without a word. Values inside
    // "extras" and "extensions" are counted: tinygltf keeps each as a large generic value.
    // In extensions preskin reads (`read`) tinygltf would also drop nulls and empty arrays (read as
    // absent) and wrap integers beyond 32 bits: errors. (Recursion is bounded by the JSON depth
    // limit.) `where` is built only for messages; `extensionMap`: `value` is an "extensions" object.
    void checkExtensions(const json& value, const std::function<std::string()>& where, bool generic, bool inExtras,
                         uint64_t& genericValues, bool read = false, bool extensionMap = false) const {
        if (generic && ++genericValues > limits::kMaxGltfExtraValues) {
            error(where(),
                  "the values inside extras and extensions exceed the limit of " +
                      std::to_string(limits::kMaxGltfExtraValues));
        }
        if (read && !inExtras) {
            if (value.is_null()) error(where(), "null is not a value (leave the field out for its default)");
            if (value.is_array() && value.empty())
                error(where(), "an empty array is not a value (leave the field out for its default)");
            const bool tooLarge = value.is_number_unsigned()
                ? value.get<uint64_t>() > uint64_t(std::numeric_limits<int32_t>::max())
                : value.is_number_integer() &&
                    (value.get<int64_t>() > std::numeric_limits<int32_t>::max() ||
                     value.get<int64_t>() < std::numeric_limits<int32_t>::min());
            if (tooLarge) error(where(), io::jsonExcerpt(value) + " is out of range for an integer");
        }
        if (value.is_array()) {
            for (size_t i = 0; i < value.size(); ++i) {
                checkExtensions(
                    value[i], [&] { return where() + "[" + std::to_string(i) + "]"; }, generic, inExtras, genericValues,
                    read);
            }
            return;
        }
        if (!value.is_object()) return;
        const std::vector<std::string>& supported = supportedRequiredExtensions();
        for (auto it = value.begin(); it != value.end(); ++it) {
            const auto at = [&] { return field(where(), io::messageText(it.key()).c_str()); };
            const bool isExtensions = it.key() == "extensions";
            const bool isExtras = it.key() == "extras";
            if (isExtensions && !inExtras) {
                if (!it->is_object()) error(at(), io::jsonExcerpt(*it) + " is not an object");
                for (auto ext = it->begin(); ext != it->end(); ++ext) {
                    if (!ext->is_object()) {
                        error(at() + "." + io::messageText(ext.key()), io::jsonExcerpt(*ext) + " is not an object");
                    }
                }
            }
            const bool readByPreskin =
                extensionMap && std::find(supported.begin(), supported.end(), it.key()) != supported.end();
            checkExtensions(*it, at, generic || isExtensions || isExtras, inExtras || isExtras, genericValues,
                            read || readByPreskin, isExtensions && !inExtras);
        }
    }
};

void checkCounts(const Checker& c, const json& doc) {
    uint64_t total = 0;
    for (const TopLevelArray& a : kTopLevelArrays) {
        const uint64_t n = c.array(doc, a.name, "").size();
        if (a.large && n > limits::kMaxGltfLargeObjects) {
            c.error(
                a.name,
                std::to_string(n) + " elements exceeds the limit of " + std::to_string(limits::kMaxGltfLargeObjects));
        }
        total += n;
    }
    if (total > limits::kMaxGltfObjects) {
        c.error("JSON",
                std::to_string(total) + " objects in the top-level arrays exceeds the limit of " +
                    std::to_string(limits::kMaxGltfObjects));
    }
}

// The media types a buffer's data URI may have (glTF 2.0, "Buffers and Buffer Views").
// The text of `where`.uri, a string; a data URI's base64 checked.
std::string uriText(const Checker& c, const json& uri, const std::string& where) {
    if (!uri.is_string()) c.error(where + ".uri", "not a string");
    std::string text = uri.get<std::string>();
    if (isDecodableDataUri(text)) {
        if (const std::string problem = base64Problem(text); !problem.empty())
            c.error(where + ".uri", "data URI: " + problem);
    }
    return text;
}

bool isBufferMediaType(const std::string& uri) {
    for (const char* type : {"data:application/octet-stream;", "data:application/gltf-buffer;"})
        if (uri.rfind(type, 0) == 0) return true;
    return false;
}

void checkBuffers(const Checker& c, const json& doc, const GlbChunks* glb, std::vector<uint64_t>& bufferLength,
                  std::vector<std::string>& warnings) {
    const json& buffers = c.array(doc, "buffers", "");
    bufferLength.assign(buffers.size(), 0);
    for (size_t i = 0; i < buffers.size(); ++i) {
        const std::string where = Checker::indexed("buffers", i);
        const json& buffer = c.object(buffers, i, "buffers");
        const uint64_t byteLength = c.requiredUnsigned(buffer, "byteLength", where);
        if (byteLength == 0) c.error(where + ".byteLength", "0 (must be at least 1)");
        if (byteLength > limits::kMaxSceneFileBytes) {
            c.error(where + ".byteLength",
                    std::to_string(byteLength) + " bytes exceeds the limit of " +
                        std::to_string(limits::kMaxSceneFileBytes));
        }
        bufferLength[i] = byteLength;
        const json* uri = Checker::member(buffer, "uri");
        if (!uri) {
            if (!glb || i != 0) c.error(where + ".uri", "missing (only the first buffer of a .glb may omit it)");
            if (!glb->hasBin) c.error(where, "refers to the GLB BIN chunk, but the file has none");
            if (byteLength > glb->bin.size()) {
                c.error(where + ".byteLength",
                        std::to_string(byteLength) + " exceeds the GLB BIN chunk (" + std::to_string(glb->bin.size()) +
                            " bytes)");
            }
            continue;
        }
        const std::string text = uriText(c, *uri, where);
        if (isDecodableDataUri(text)) {
            std::vector<unsigned char> decoded;
            std::string mime;
            if (!tinygltf::DecodeDataURI(&decoded, mime, text, 0, false))
                c.error(where + ".uri", "data URI does not decode");
            if (decoded.size() != byteLength) {
                c.error(where + ".uri",
                        "data URI holds " + std::to_string(decoded.size()) + " bytes, byteLength says " +
                            std::to_string(byteLength));
            }
            if (!isBufferMediaType(text)) {
                warnings.push_back(
                    c.file + ": " + where + ".uri: data URI media type '" +
                    io::messageText(text.substr(5, text.find_first_of(";,") - 5)) +
                    "' is not application/octet-stream or application/gltf-buffer; read as binary anyway");
            }
            continue;
        }
        const fs::path path = c.existingFile(text, where + ".uri");
        std::error_code ec;
        const uintmax_t size = fs::file_size(path, ec);
        if (ec) c.error(where + ".uri", "cannot read the size of '" + text + "'");
        if (size != byteLength) {
            c.error(where + ".uri",
                    "'" + text + "' has " + std::to_string(size) + " bytes, byteLength says " +
                        std::to_string(byteLength) + (size < byteLength ? " (truncated)" : ""));
        }
    }
}

// Returns each view's byteLength.
std::vector<uint64_t> checkBufferViews(const Checker& c, const json& doc, const std::vector<uint64_t>& bufferLength) {
    const json& views = c.array(doc, "bufferViews", "");
    std::vector<uint64_t> viewLength(views.size());
    for (size_t i = 0; i < views.size(); ++i) {
        const std::string where = Checker::indexed("bufferViews", i);
        const json& view = c.object(views, i, "bufferViews");
        const uint64_t buffer = c.requiredUnsigned(view, "buffer", where);
        c.checkIndex(buffer, bufferLength.size(), where + ".buffer", "buffers");
        const uint64_t offset = c.unsignedField(view, "byteOffset", where).value_or(0);
        const uint64_t length = c.requiredUnsigned(view, "byteLength", where);
        if (length == 0) c.error(where + ".byteLength", "0 (must be at least 1)");
        if (offset > bufferLength[buffer] || length > bufferLength[buffer] - offset) {
            c.error(where,
                    "byteOffset " + std::to_string(offset) + " + byteLength " + std::to_string(length) +
                        " exceeds buffers[" + std::to_string(buffer) + "] (" + std::to_string(bufferLength[buffer]) +
                        " bytes)");
        }
        if (auto stride = c.unsignedField(view, "byteStride", where)) {
            if (*stride < 4 || *stride > 252 || *stride % 4 != 0) {
                c.error(where + ".byteStride", std::to_string(*stride) + " (must be a multiple of 4 in 4..252)");
            }
        }
        viewLength[i] = length;
    }
    return viewLength;
}

// An offset into a bufferView that must lie inside it (so that it also fits tinygltf's int).
void checkViewOffset(const Checker& c, const json& object, const std::string& where,
                     const std::vector<uint64_t>& viewLength) {
    const uint64_t view = c.requiredUnsigned(object, "bufferView", where);
    c.checkIndex(view, viewLength.size(), where + ".bufferView", "bufferViews");
    const uint64_t offset = c.unsignedField(object, "byteOffset", where).value_or(0);
    if (offset >= viewLength[view]) {
        c.error(where + ".byteOffset",
                std::to_string(offset) + " is not inside bufferViews[" + std::to_string(view) + "] (" +
                    std::to_string(viewLength[view]) + " bytes)");
    }
}

void checkAccessors(const Checker& c, const json& doc, const std::vector<uint64_t>& viewLength) {
    static const std::vector<uint64_t> componentTypes = {5120, 5121, 5122, 5123, 5125, 5126};
    static const std::vector<std::string> types = {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"};
    const json& accessors = c.array(doc, "accessors", "");
    for (size_t i = 0; i < accessors.size(); ++i) {
        const std::string where = Checker::indexed("accessors", i);
        const json& accessor = c.object(accessors, i, "accessors");
        c.idField(accessor, "bufferView", viewLength.size(), where, "bufferViews");
        c.unsignedField(accessor, "byteOffset", where);
        const uint64_t componentType = c.requiredUnsigned(accessor, "componentType", where);
        if (std::find(componentTypes.begin(), componentTypes.end(), componentType) == componentTypes.end()) {
            c.error(where + ".componentType", std::to_string(componentType) + " is not a glTF component type");
        }
        const json* type = Checker::member(accessor, "type");
        if (!type) c.error(where + ".type", "missing");
        if (!type->is_string() || std::find(types.begin(), types.end(), type->get<std::string>()) == types.end()) {
            c.error(where + ".type", io::jsonExcerpt(*type) + " is not a glTF accessor type");
        }
        if (const json* normalized = Checker::member(accessor, "normalized"); normalized && !normalized->is_boolean()) {
            c.error(where + ".normalized", "not a boolean");
        }
        const uint64_t count = c.requiredUnsigned(accessor, "count", where);
        if (count == 0) c.error(where + ".count", "0 (must be at least 1)");
        if (count > limits::kMaxSceneIndices) {
            c.error(where + ".count",
                    std::to_string(count) + " exceeds the limit of " + std::to_string(limits::kMaxSceneIndices) +
                        " elements");
        }
        const json* sparse = Checker::member(accessor, "sparse");
        if (!sparse) continue;
        const std::string at = where + ".sparse";
        if (!sparse->is_object()) c.error(at, "not an object");
        const uint64_t sparseCount = c.requiredUnsigned(*sparse, "count", at);
        if (sparseCount < 1 || sparseCount > count) {
            c.error(at + ".count", std::to_string(sparseCount) + " (must be in 1.." + std::to_string(count) + ")");
        }
        const json* indices = Checker::member(*sparse, "indices");
        if (!indices || !indices->is_object()) c.error(at + ".indices", "missing or not an object");
        checkViewOffset(c, *indices, at + ".indices", viewLength);
        // Another index type is a validator warning: the loader ignores the substitution and says so.
        c.requiredUnsigned(*indices, "componentType", at + ".indices");
        const json* values = Checker::member(*sparse, "values");
        if (!values || !values->is_object()) c.error(at + ".values", "missing or not an object");
        checkViewOffset(c, *values, at + ".values", viewLength);
    }
}

void checkImagesAndTextures(const Checker& c, const json& doc, size_t viewCount) {
    const json& images = c.array(doc, "images", "");
    for (size_t i = 0; i < images.size(); ++i) {
        const std::string where = Checker::indexed("images", i);
        const json& image = c.object(images, i, "images");
        const json* uri = Checker::member(image, "uri");
        const bool hasView = Checker::member(image, "bufferView") != nullptr;
        if (uri && hasView) c.error(where, "has both uri and bufferView");
        if (!uri && !hasView) c.error(where, "has neither uri nor bufferView");
        if (hasView) {
            c.idField(image, "bufferView", viewCount, where, "bufferViews");
            continue;
        }
        const std::string text = uriText(c, *uri, where);
        if (!isDecodableDataUri(text)) c.existingFile(text, where + ".uri");
    }
    const json& textures = c.array(doc, "textures", "");
    const size_t samplers = c.array(doc, "samplers", "").size();
    for (size_t i = 0; i < textures.size(); ++i) {
        const std::string where = Checker::indexed("textures", i);
        const json& texture = c.object(textures, i, "textures");
        c.idField(texture, "sampler", samplers, where, "samplers");
        c.idField(texture, "source", images.size(), where, "images");
    }
}

void checkMaterials(const Checker& c, const json& doc) {
    const json& materials = c.array(doc, "materials", "");
    const size_t textures = c.array(doc, "textures", "").size();
    for (size_t i = 0; i < materials.size(); ++i) {
        const std::string where = Checker::indexed("materials", i);
        const json& material = c.object(materials, i, "materials");
        for (const auto& path : kMaterialTextures) {
            const json* parent = &material;
            std::string at = where;
            if (path[0]) {
                parent = Checker::member(material, path[0]);
                at += std::string(".") + path[0];
                if (!parent) continue;
                if (!parent->is_object()) c.error(at, "not an object");
            }
            const json* info = Checker::member(*parent, path[1]);
            if (!info) continue;
            at += std::string(".") + path[1];
            if (!info->is_object()) c.error(at, "not an object");
            c.idField(*info, "index", textures, at, "textures", true);
            c.unsignedField(*info, "texCoord", at);
        }
    }
}

void checkMeshes(const Checker& c, const json& doc) {
    const json& meshes = c.array(doc, "meshes", "");
    const size_t accessors = c.array(doc, "accessors", "").size();
    const size_t materials = c.array(doc, "materials", "").size();
    uint64_t primitiveCount = 0;
    for (size_t m = 0; m < meshes.size(); ++m) {
        const std::string meshWhere = Checker::indexed("meshes", m);
        const json& mesh = c.object(meshes, m, "meshes");
        const json* primitives = Checker::member(mesh, "primitives");
        if (!primitives || !primitives->is_array()) c.error(meshWhere + ".primitives", "missing or not an array");
        if (primitives->empty()) c.error(meshWhere + ".primitives", "empty (a mesh has at least one primitive)");
        primitiveCount += primitives->size();
        if (primitiveCount > limits::kMaxScenePrimitives) {
            c.error(meshWhere + ".primitives",
                    "the file exceeds the limit of " + std::to_string(limits::kMaxScenePrimitives) + " primitives");
        }
        for (size_t p = 0; p < primitives->size(); ++p) {
            const std::string where = meshWhere + Checker::indexed(".primitives", p);
            const json& primitive = c.object(*primitives, p, meshWhere + ".primitives");
            if (c.member(primitive, "indices")) {
                const uint64_t indices = c.unsignedField(primitive, "indices", where).value();
                c.checkIndex(indices, accessors, where + ".indices", "accessors");
            }
            c.idField(primitive, "material", materials, where, "materials");
            if (auto mode = c.unsignedField(primitive, "mode", where); mode && *mode > 6) {
                c.error(where + ".mode", std::to_string(*mode) + " is not a glTF primitive mode");
            }
            const json* attributes = Checker::member(primitive, "attributes");
            if (!attributes || !attributes->is_object()) c.error(where + ".attributes", "missing or not an object");
            for (auto it = attributes->begin(); it != attributes->end(); ++it) {
                c.idValue(*it, accessors, where + ".attributes." + it.key(), "accessors");
            }
            const json& targets = c.array(primitive, "targets", where);
            for (size_t t = 0; t < targets.size(); ++t) {
                const std::string at = where + Checker::indexed(".targets", t);
                if (!targets[t].is_object()) c.error(at, "not an object");
                for (auto it = targets[t].begin(); it != targets[t].end(); ++it) {
                    c.idValue(*it, accessors, at + "." + it.key(), "accessors");
                }
            }
        }
    }
}

void checkNodesAndScenes(const Checker& c, const json& doc) {
    const json& nodes = c.array(doc, "nodes", "");
    const size_t meshes = c.array(doc, "meshes", "").size();
    const size_t cameras = c.array(doc, "cameras", "").size();
    const size_t skins = c.array(doc, "skins", "").size();
    for (size_t i = 0; i < nodes.size(); ++i) {
        const std::string where = Checker::indexed("nodes", i);
        const json& node = c.object(nodes, i, "nodes");
        c.idField(node, "mesh", meshes, where, "meshes");
        c.idField(node, "camera", cameras, where, "cameras");
        c.idField(node, "skin", skins, where, "skins");
        c.idArray(node, "children", nodes.size(), where, "nodes");
    }
    const json& scenes = c.array(doc, "scenes", "");
    for (size_t i = 0; i < scenes.size(); ++i) {
        const json& scene = c.object(scenes, i, "scenes");
        c.idArray(scene, "nodes", nodes.size(), Checker::indexed("scenes", i), "nodes");
    }
    c.idField(doc, "scene", scenes.size(), "", "scenes");

    // Skins and animations are not used, but tinygltf parses them: their indices must hold too.
    const size_t accessors = c.array(doc, "accessors", "").size();
    const json& skinArray = c.array(doc, "skins", "");
    for (size_t i = 0; i < skinArray.size(); ++i) {
        const std::string where = Checker::indexed("skins", i);
        const json& skin = c.object(skinArray, i, "skins");
        c.idField(skin, "inverseBindMatrices", accessors, where, "accessors");
        c.idField(skin, "skeleton", nodes.size(), where, "nodes");
        c.idArray(skin, "joints", nodes.size(), where, "nodes");
    }
    const json& animations = c.array(doc, "animations", "");
    for (size_t i = 0; i < animations.size(); ++i) {
        const std::string where = Checker::indexed("animations", i);
        const json& animation = c.object(animations, i, "animations");
        const json& samplers = c.array(animation, "samplers", where);
        for (size_t s = 0; s < samplers.size(); ++s) {
            const std::string at = where + Checker::indexed(".samplers", s);
            if (!samplers[s].is_object()) c.error(at, "not an object");
            c.idField(samplers[s], "input", accessors, at, "accessors", true);
            c.idField(samplers[s], "output", accessors, at, "accessors", true);
        }
        const json& channels = c.array(animation, "channels", where);
        for (size_t k = 0; k < channels.size(); ++k) {
            const std::string at = where + Checker::indexed(".channels", k);
            if (!channels[k].is_object()) c.error(at, "not an object");
            c.idField(channels[k], "sampler", samplers.size(), at, "samplers in this animation", true);
            const json* target = Checker::member(channels[k], "target");
            if (!target || !target->is_object()) c.error(at + ".target", "missing or not an object");
            c.idField(*target, "node", nodes.size(), at + ".target", "nodes");
        }
    }
}

// KHR_lights_punctual (its schema): type; colour components in [0, 1]; intensity >= 0; range > 0
// when present; spot cones with 0 <= inner < outer <= pi/2.
void checkLights(const Checker& c, const json& doc) {
    const json* extensions = Checker::member(doc, "extensions");
    const json* khr = extensions ? Checker::member(*extensions, "KHR_lights_punctual") : nullptr;
    size_t lightCount = 0;
    if (khr) {
        const std::string base = "extensions.KHR_lights_punctual";
        const json& lights = c.array(*khr, "lights", base);
        if (lights.size() > limits::kMaxGltfLargeObjects) {
            c.error(base + ".lights",
                    std::to_string(lights.size()) + " elements exceeds the limit of " +
                        std::to_string(limits::kMaxGltfLargeObjects));
        }
        lightCount = lights.size();
        for (size_t i = 0; i < lights.size(); ++i) {
            const std::string where = Checker::indexed(base + ".lights", i);
            const json& light = c.object(lights, i, base + ".lights");
            const json* type = Checker::member(light, "type");
            if (!type) c.error(where + ".type", "missing");
            // A type string glTF does not define is a validator warning: the loader skips the light.
            if (!type->is_string()) c.error(where + ".type", io::jsonExcerpt(*type) + " is not a string");
            const std::string typeName = type->get<std::string>();
            if (const json* color = Checker::member(light, "color")) {
                if (!color->is_array() || color->size() != 3) c.error(where + ".color", "not an array of 3 numbers");
                for (size_t k = 0; k < 3; ++k) {
                    const std::string at = Checker::indexed(where + ".color", k);
                    if (!(*color)[k].is_number()) c.error(at, "not a number");
                    const double v = (*color)[k].get<double>();
                    if (auto problem = io::numberProblem(v)) c.error(at, *problem);
                    if (v < 0.0 || v > 1.0) c.error(at, io::numberText(v) + " is outside [0, 1]");
                }
            }
            if (auto intensity = c.numberField(light, "intensity", where); intensity && *intensity < 0.0) {
                c.error(where + ".intensity", io::numberText(*intensity) + " is negative");
            }
            if (auto range = c.numberField(light, "range", where); range && !(*range > 0.0)) {
                c.error(where + ".range", io::numberText(*range) + " (must be > 0 when present)");
            }
            if (typeName == "spot") {
                const json* spot = Checker::member(light, "spot");
                if (!spot || !spot->is_object())
                    c.error(where + ".spot", "missing or not an object (a spot light needs it)");
                const double inner = c.numberField(*spot, "innerConeAngle", where + ".spot").value_or(0.0);
                const double outer =
                    c.numberField(*spot, "outerConeAngle", where + ".spot").value_or(std::numbers::pi / 4);
                if (!(inner >= 0.0 && inner < outer && outer <= std::numbers::pi / 2 + 1e-6)) {
                    c.error(where + ".spot",
                            "cone angles inner " + io::numberText(inner) + ", outer " + io::numberText(outer) +
                                " (need 0 <= inner < outer <= pi/2)");
                }
            }
        }
    }
    const json& nodes = c.array(doc, "nodes", "");
    for (size_t i = 0; i < nodes.size(); ++i) {
        const json* nodeExtensions = Checker::member(nodes[i], "extensions");
        const json* light = nodeExtensions ? Checker::member(*nodeExtensions, "KHR_lights_punctual") : nullptr;
        if (light) {
            c.idField(*light, "light", lightCount, Checker::indexed("nodes", i) + ".extensions.KHR_lights_punctual",
                      "lights", true);
        }
    }
}

void checkEnvironment(const Checker& c, const json& doc, PrepassResult& result) {
    const json* extensions = Checker::member(doc, "extensions");
    const json* env = extensions ? Checker::member(*extensions, "PRESKIN_environment") : nullptr;
    if (!env) return;
    const std::string where = "extensions.PRESKIN_environment";
    const json* uri = Checker::member(*env, "uri");
    if (!uri || !uri->is_string()) c.error(where + ".uri", "missing or not a string");
    if (const std::string text = uri->get<std::string>(); text.rfind("data:", 0) == 0)
        result.environmentData = decodeBase64DataUri(text, c.file, where + ".uri");
    else
        result.environmentPath = c.existingFile(text, where + ".uri");
    if (auto intensity = c.numberField(*env, "intensity", where)) {
        if (*intensity < 0.0) c.error(where + ".intensity", io::numberText(*intensity) + " is negative");
        result.environmentIntensity = static_cast<float>(*intensity);
    }
    if (auto rotation = c.numberField(*env, "rotation", where))
        result.environmentRotation = static_cast<float>(*rotation);
}

// The root PRESKIN_materials_skin extension: {"profiles": [profile, ...]}. A profile is
// {"type": "deonLuebke"}, a sum of Gaussians or normalized diffusion (DiffusionProfile's JSON),
// or {"type": "lutFolder", "uri": folder of a baked LUT set}; each may have a "name".
void checkSkinProfiles(const Checker& c, const json& doc, PrepassResult& result) {
    const json* extensions = Checker::member(doc, "extensions");
    const json* skin = extensions ? Checker::member(*extensions, "PRESKIN_materials_skin") : nullptr;
    if (!skin) return;
    const std::string where = "extensions.PRESKIN_materials_skin";
    for (auto it = skin->begin(); it != skin->end(); ++it) {
        if (it.key() != "profiles" && it.key() != "extras" && it.key() != "extensions")
            result.warnings.push_back(c.file + ": " + where + "." + io::messageText(it.key()) +
                                      ": unknown field; ignored");
    }
    const json* profiles = Checker::member(*skin, "profiles");
    if (!profiles) return;
    if (!profiles->is_array()) c.error(where + ".profiles", "not an array");
    if (profiles->size() > limits::kMaxSkinProfiles) {
        c.error(where + ".profiles",
                std::to_string(profiles->size()) + " profiles exceed the limit of " +
                    std::to_string(limits::kMaxSkinProfiles));
    }
    for (size_t i = 0; i < profiles->size(); ++i) {
        const std::string at = where + Checker::indexed(".profiles", i);
        const json& entry = (*profiles)[i];
        if (!entry.is_object()) c.error(at, "not an object");
        SkinProfile profile;
        const json* name = Checker::member(entry, "name");
        if (name && !name->is_string()) c.error(at + ".name", "not a string");
        profile.name = name ? name->get<std::string>() : Checker::indexed("profiles", i);
        const json* type = Checker::member(entry, "type");
        if (type && *type == "deonLuebke") {
            for (auto f = entry.begin(); f != entry.end(); ++f) {
                if (f.key() != "type" && f.key() != "name")
                    c.error(at + "." + io::messageText(f.key()), "unknown field");
            }
            profile.profile = DiffusionProfile::deonLuebke();
        } else if (type && *type == "lutFolder") {
            for (auto f = entry.begin(); f != entry.end(); ++f) {
                if (f.key() != "type" && f.key() != "name" && f.key() != "uri")
                    c.error(at + "." + io::messageText(f.key()), "unknown field");
            }
            const json* uri = Checker::member(entry, "uri");
            if (!uri || !uri->is_string()) c.error(at + ".uri", "missing or not a string");
            const std::string text = uri->get<std::string>();
            profile.lutFolder = resolveUri(text, c.folder, c.file, at + ".uri", c.allowOutsideLinks);
            std::error_code ec;
            if (!fs::is_directory(profile.lutFolder, ec))
                c.error(at + ".uri", "LUT folder '" + io::messageText(text) + "' not found next to the scene");
        } else {
            // Reports an unknown type as "must be sumOfGaussians or normalizedDiffusion"; the two
            // kinds above are named in docs/gltf-extensions.md.
            try {
                profile.profile = skin::parseProfileJson(entry, c.file, at + ".");
            } catch (const Error& e) {
                if (type && type->is_string()) {
                    const std::string kind = type->get<std::string>();
                    if (kind != "sumOfGaussians" && kind != "normalizedDiffusion") {
                        c.error(at + ".type",
                                "'" + io::messageText(kind) +
                                    "' is not a profile type (deonLuebke, normalizedDiffusion, "
                                    "sumOfGaussians or lutFolder)");
                    }
                }
                throw;
            }
        }
        result.profiles.push_back(std::move(profile));
    }
}

}  // namespace

PrepassResult checkDocument(const json& doc, const std::string& file, const fs::path& folder, const GlbChunks* glb,
                            bool allowOutsideLinks) {
    const Checker c{file, folder, allowOutsideLinks};
    PrepassResult result;
    if (!doc.is_object()) c.error("JSON", "the root is not an object");

    // asset
    const json* asset = Checker::member(doc, "asset");
    if (!asset || !asset->is_object()) c.error("asset", "missing (every glTF file has asset.version)");
    const json* version = Checker::member(*asset, "version");
    if (!version || !version->is_string()) c.error("asset.version", "missing or not a string");
    const std::string versionText = version->get<std::string>();
    if (versionText.rfind("2.", 0) != 0) {
        c.error("asset.version", "'" + io::messageText(versionText) + "', only glTF 2.x is supported");
    }
    if (const json* minVersion = Checker::member(*asset, "minVersion")) {
        if (!minVersion->is_string() || minVersion->get<std::string>() != "2.0") {
            c.error("asset.minVersion", io::jsonExcerpt(*minVersion) + ", only 2.0 is supported");
        }
    }

    // skins (tinygltf refuses a skin without joints without naming it)
    const json& skins = c.array(doc, "skins", "");
    for (size_t i = 0; i < skins.size(); ++i) {
        const json* joints = skins[i].is_object() ? Checker::member(skins[i], "joints") : nullptr;
        if (!joints || !joints->is_array() || joints->empty())
            c.error(Checker::indexed("skins", i) + ".joints",
                    "missing, empty or not an array (a skin needs at least one joint)");
    }

    // extensions
    const auto& supported = supportedRequiredExtensions();
    const json& required = c.array(doc, "extensionsRequired", "");
    for (size_t i = 0; i < required.size(); ++i) {
        if (!required[i].is_string()) c.error(Checker::indexed("extensionsRequired", i), "not a string");
        const std::string name = required[i].get<std::string>();
        if (std::find(supported.begin(), supported.end(), name) == supported.end()) {
            std::string list;
            for (const auto& s : supported) list += (list.empty() ? "" : ", ") + s;
            c.error(Checker::indexed("extensionsRequired", i),
                    "'" + io::messageText(name) + "' is not supported (supported: " + list + ")");
        }
    }
    const json& used = c.array(doc, "extensionsUsed", "");
    for (size_t i = 0; i < used.size(); ++i) {
        if (!used[i].is_string()) c.error(Checker::indexed("extensionsUsed", i), "not a string");
        const std::string name = used[i].get<std::string>();
        if (std::find(supported.begin(), supported.end(), name) == supported.end()) {
            result.warnings.push_back(file + ": " + Checker::indexed("extensionsUsed", i) + ": '" +
                                      io::messageText(name) + "' is not implemented; ignored");
        }
    }
    uint64_t genericValues = 0;
    c.checkExtensions(
        doc, [] { return std::string(); }, false, false, genericValues);
    checkCounts(c, doc);

    std::vector<uint64_t> bufferLength;
    checkBuffers(c, doc, glb, bufferLength, result.warnings);
    // Cameras of a type glTF does not define: the validator warns only, so they are skipped (and
    // replaced before tinygltf, which refuses them, parses the file).
    const json& cameras = c.array(doc, "cameras", "");
    for (size_t i = 0; i < cameras.size(); ++i) {
        const json* type = cameras[i].is_object() ? Checker::member(cameras[i], "type") : nullptr;
        if (type && type->is_string() && (*type == "perspective" || *type == "orthographic")) continue;
        result.skippedCameras.push_back(i);
        result.warnings.push_back(file + ": " + Checker::indexed("cameras", i) +
                                  ".type: " + (type ? io::jsonExcerpt(*type) : std::string("missing")) +
                                  " is not perspective or orthographic; camera skipped");
    }
    const std::vector<uint64_t> viewLength = checkBufferViews(c, doc, bufferLength);
    checkAccessors(c, doc, viewLength);
    checkImagesAndTextures(c, doc, viewLength.size());
    checkMaterials(c, doc);
    checkMeshes(c, doc);
    // Index accessors without a bufferView hold zeros (valid glTF, but every triangle is
    // degenerate): the primitive is skipped, and its indices removed before tinygltf, which
    // refuses them, parses the file.
    const json& accessorList = c.array(doc, "accessors", "");
    const json& meshList = c.array(doc, "meshes", "");
    for (size_t m = 0; m < meshList.size(); ++m) {
        const json* primitives = Checker::member(meshList[m], "primitives");
        for (size_t p = 0; primitives && p < primitives->size(); ++p) {
            const json* indices = Checker::member((*primitives)[p], "indices");
            if (!indices || !indices->is_number_unsigned() || indices->get<uint64_t>() >= accessorList.size()) continue;
            const json& accessor = accessorList[indices->get<size_t>()];
            if (Checker::member(accessor, "bufferView") || Checker::member(accessor, "sparse")) continue;
            result.skippedPrimitives.emplace_back(m, p);
            result.warnings.push_back(file + ": " + Checker::indexed("meshes", m) + Checker::indexed(".primitives", p) +
                                      ".indices: accessors[" + std::to_string(indices->get<size_t>()) +
                                      "] has no bufferView: its indices are all 0 and draw nothing; primitive skipped");
        }
    }
    checkNodesAndScenes(c, doc);
    checkLights(c, doc);
    checkEnvironment(c, doc, result);
    checkSkinProfiles(c, doc, result);
    return result;
}

}  // namespace preskin::gltf
