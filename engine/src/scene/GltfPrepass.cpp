// JSON-level checks before tinygltf parses the document (see GltfPrepass.h).
#include "scene/GltfPrepass.h"
#include "scene/TinyGltf.h"

#include <algorithm>
#include <cmath>
#include <system_error>

namespace preskin::gltf {

namespace fs = std::filesystem;
using nlohmann::json;

const std::vector<std::string>& supportedRequiredExtensions() {
    static const std::vector<std::string> names = {
        "KHR_lights_punctual",        "KHR_materials_diffuse_transmission",
        "KHR_materials_emissive_strength", "KHR_materials_volume",
        "KHR_mesh_quantization",      "KHR_texture_transform",
        "PRESKIN_environment",        "PRESKIN_materials_skin",
    };
    return names;
}

namespace {

struct Checker {
    const std::string& file;
    const fs::path& folder;

    [[noreturn]] void error(const std::string& where, const std::string& what) const { fail(file, where, what); }

    const json* member(const json& object, const char* key) const {
        auto it = object.find(key);
        return it == object.end() ? nullptr : &*it;
    }

    const json& array(const json& doc, const char* key) const {
        static const json empty = json::array();
        const json* v = member(doc, key);
        if (!v) return empty;
        if (!v->is_array()) error(key, "not an array");
        return *v;
    }

    const json& object(const json& array, size_t i, const std::string& name) const {
        const json& v = array[i];
        if (!v.is_object()) error(indexed(name, i), "not an object");
        return v;
    }

    static std::string indexed(const std::string& name, size_t i) { return name + "[" + std::to_string(i) + "]"; }

    // A non-negative integer field; nullopt when absent.
    std::optional<uint64_t> unsignedField(const json& object, const char* key, const std::string& where) const {
        const json* v = member(object, key);
        if (!v) return std::nullopt;
        if (v->is_number_unsigned()) return v->get<uint64_t>();
        if (v->is_number_integer()) error(where + "." + key, std::to_string(v->get<int64_t>()) + " is negative");
        if (v->is_number_float()) {
            const double d = v->get<double>();
            if (std::isfinite(d) && d >= 0.0 && d == std::floor(d) && d < 9007199254740992.0) {
                return static_cast<uint64_t>(d);
            }
        }
        error(where + "." + key, "not a non-negative integer");
    }

    uint64_t requiredUnsigned(const json& object, const char* key, const std::string& where) const {
        auto v = unsignedField(object, key, where);
        if (!v) error(where + "." + key, "missing");
        return *v;
    }

    void checkIndex(uint64_t index, size_t count, const std::string& where, const char* what) const {
        if (index >= count) {
            error(where, std::to_string(index) + " is out of range: the file has " + std::to_string(count) + " " + what);
        }
    }

    fs::path existingFile(const std::string& uri, const std::string& where) const {
        const fs::path path = resolveUri(uri, folder, file, where);
        std::error_code ec;
        const auto status = fs::status(path, ec);
        if (ec || !fs::exists(status)) error(where, "file '" + uri + "' not found next to the scene");
        if (!fs::is_regular_file(status)) error(where, "'" + uri + "' is not a regular file");
        return path;
    }
};

}  // namespace

PrepassResult checkDocument(const json& doc, const std::string& file, const fs::path& folder, const GlbChunks* glb) {
    const Checker c{file, folder};
    PrepassResult result;
    if (!doc.is_object()) c.error("JSON", "the root is not an object");

    // asset
    const json* asset = c.member(doc, "asset");
    if (!asset || !asset->is_object()) c.error("asset", "missing (every glTF file has asset.version)");
    const json* version = c.member(*asset, "version");
    if (!version || !version->is_string()) c.error("asset.version", "missing or not a string");
    const std::string versionText = version->get<std::string>();
    if (versionText.rfind("2.", 0) != 0) c.error("asset.version", "'" + versionText + "', only glTF 2.x is supported");
    if (const json* minVersion = c.member(*asset, "minVersion")) {
        if (!minVersion->is_string() || minVersion->get<std::string>() != "2.0") {
            c.error("asset.minVersion", "'" + minVersion->dump() + "', only 2.0 is supported");
        }
    }

    // extensions
    const auto& supported = supportedRequiredExtensions();
    const json& required = c.array(doc, "extensionsRequired");
    for (size_t i = 0; i < required.size(); ++i) {
        if (!required[i].is_string()) c.error(Checker::indexed("extensionsRequired", i), "not a string");
        const std::string name = required[i].get<std::string>();
        if (std::find(supported.begin(), supported.end(), name) == supported.end()) {
            std::string list;
            for (const auto& s : supported) list += (list.empty() ? "" : ", ") + s;
            c.error(Checker::indexed("extensionsRequired", i), "'" + name + "' is not supported (supported: " + list + ")");
        }
    }
    const json& used = c.array(doc, "extensionsUsed");
    for (size_t i = 0; i < used.size(); ++i) {
        if (!used[i].is_string()) c.error(Checker::indexed("extensionsUsed", i), "not a string");
        const std::string name = used[i].get<std::string>();
        if (std::find(supported.begin(), supported.end(), name) == supported.end()) {
            result.warnings.push_back(file + ": " + Checker::indexed("extensionsUsed", i) + ": '" + name +
                                      "' is not implemented; ignored");
        }
    }

    // buffers
    const json& buffers = c.array(doc, "buffers");
    std::vector<uint64_t> bufferLength(buffers.size());
    for (size_t i = 0; i < buffers.size(); ++i) {
        const std::string where = Checker::indexed("buffers", i);
        const json& buffer = c.object(buffers, i, "buffers");
        const uint64_t byteLength = c.requiredUnsigned(buffer, "byteLength", where);
        if (byteLength == 0) c.error(where + ".byteLength", "0 (must be at least 1)");
        if (byteLength > kMaxFileBytes) {
            c.error(where + ".byteLength", std::to_string(byteLength) + " bytes exceeds the limit of " +
                                               std::to_string(kMaxFileBytes));
        }
        bufferLength[i] = byteLength;
        const json* uri = c.member(buffer, "uri");
        if (!uri) {
            if (!glb || i != 0) c.error(where + ".uri", "missing (only the first buffer of a .glb may omit it)");
            if (!glb->hasBin) c.error(where, "refers to the GLB BIN chunk, but the file has none");
            if (byteLength > glb->bin.size()) {
                c.error(where + ".byteLength", std::to_string(byteLength) + " exceeds the GLB BIN chunk (" +
                                                   std::to_string(glb->bin.size()) + " bytes)");
            }
            continue;
        }
        if (!uri->is_string()) c.error(where + ".uri", "not a string");
        const std::string text = uri->get<std::string>();
        if (isDecodableDataUri(text)) {
            std::vector<unsigned char> decoded;
            std::string mime;
            if (!tinygltf::DecodeDataURI(&decoded, mime, text, 0, false)) c.error(where + ".uri", "data URI does not decode");
            if (decoded.size() != byteLength) {
                c.error(where + ".uri", "data URI holds " + std::to_string(decoded.size()) + " bytes, byteLength says " +
                                            std::to_string(byteLength));
            }
            continue;
        }
        const fs::path path = c.existingFile(text, where + ".uri");
        std::error_code ec;
        const uintmax_t size = fs::file_size(path, ec);
        if (ec) c.error(where + ".uri", "cannot read the size of '" + text + "'");
        if (size != byteLength) {
            c.error(where + ".uri", "'" + text + "' has " + std::to_string(size) + " bytes, byteLength says " +
                                        std::to_string(byteLength) + (size < byteLength ? " (truncated)" : ""));
        }
    }

    // bufferViews
    const json& views = c.array(doc, "bufferViews");
    for (size_t i = 0; i < views.size(); ++i) {
        const std::string where = Checker::indexed("bufferViews", i);
        const json& view = c.object(views, i, "bufferViews");
        const uint64_t buffer = c.requiredUnsigned(view, "buffer", where);
        c.checkIndex(buffer, buffers.size(), where + ".buffer", "buffers");
        const uint64_t offset = c.unsignedField(view, "byteOffset", where).value_or(0);
        const uint64_t length = c.requiredUnsigned(view, "byteLength", where);
        if (length == 0) c.error(where + ".byteLength", "0 (must be at least 1)");
        if (offset > bufferLength[buffer] || length > bufferLength[buffer] - offset) {
            c.error(where, "byteOffset " + std::to_string(offset) + " + byteLength " + std::to_string(length) +
                               " exceeds buffers[" + std::to_string(buffer) + "] (" +
                               std::to_string(bufferLength[buffer]) + " bytes)");
        }
        if (auto stride = c.unsignedField(view, "byteStride", where)) {
            if (*stride < 4 || *stride > 252 || *stride % 4 != 0) {
                c.error(where + ".byteStride", std::to_string(*stride) + " (must be a multiple of 4 in 4..252)");
            }
        }
    }

    // images
    const json& images = c.array(doc, "images");
    for (size_t i = 0; i < images.size(); ++i) {
        const std::string where = Checker::indexed("images", i);
        const json& image = c.object(images, i, "images");
        const json* uri = c.member(image, "uri");
        const bool hasView = c.member(image, "bufferView") != nullptr;
        if (uri && hasView) c.error(where, "has both uri and bufferView");
        if (!uri && !hasView) c.error(where, "has neither uri nor bufferView");
        if (hasView) {
            c.checkIndex(c.requiredUnsigned(image, "bufferView", where), views.size(), where + ".bufferView",
                         "bufferViews");
            continue;
        }
        if (!uri->is_string()) c.error(where + ".uri", "not a string");
        const std::string text = uri->get<std::string>();
        if (isDecodableDataUri(text)) continue;
        c.existingFile(text, where + ".uri");
    }

    // accessors and the accessors primitives use (tinygltf dereferences these while parsing)
    const json& accessors = c.array(doc, "accessors");
    for (size_t i = 0; i < accessors.size(); ++i) {
        const std::string where = Checker::indexed("accessors", i);
        const json& accessor = c.object(accessors, i, "accessors");
        if (auto view = c.unsignedField(accessor, "bufferView", where)) {
            c.checkIndex(*view, views.size(), where + ".bufferView", "bufferViews");
        }
    }
    const json& meshes = c.array(doc, "meshes");
    for (size_t m = 0; m < meshes.size(); ++m) {
        const json& mesh = c.object(meshes, m, "meshes");
        const json* primitives = c.member(mesh, "primitives");
        if (!primitives || !primitives->is_array()) c.error(Checker::indexed("meshes", m) + ".primitives", "missing or not an array");
        for (size_t p = 0; p < primitives->size(); ++p) {
            const std::string where = Checker::indexed("meshes", m) + Checker::indexed(".primitives", p);
            const json& primitive = c.object(*primitives, p, Checker::indexed("meshes", m) + ".primitives");
            if (auto indices = c.unsignedField(primitive, "indices", where)) {
                c.checkIndex(*indices, accessors.size(), where + ".indices", "accessors");
                if (!c.unsignedField(accessors[*indices], "bufferView", "accessors[" + std::to_string(*indices) + "]")) {
                    c.error(where + ".indices", "accessors[" + std::to_string(*indices) + "] has no bufferView");
                }
            }
            const json* attributes = c.member(primitive, "attributes");
            if (!attributes || !attributes->is_object()) c.error(where + ".attributes", "missing or not an object");
            for (auto it = attributes->begin(); it != attributes->end(); ++it) {
                const std::string at = where + ".attributes." + it.key();
                if (!it->is_number_unsigned()) c.error(at, "not an accessor index");
                c.checkIndex(it->get<uint64_t>(), accessors.size(), at, "accessors");
            }
        }
    }

    // skins (tinygltf refuses a skin without joints without naming it)
    const json& skins = c.array(doc, "skins");
    for (size_t i = 0; i < skins.size(); ++i) {
        const json* joints = c.member(c.object(skins, i, "skins"), "joints");
        if (!joints || !joints->is_array()) {
            c.error(Checker::indexed("skins", i) + ".joints", "missing or not an array (a skin needs at least one joint)");
        }
    }

    // PRESKIN_environment
    if (const json* extensions = c.member(doc, "extensions")) {
        if (!extensions->is_object()) c.error("extensions", "not an object");
        if (const json* env = c.member(*extensions, "PRESKIN_environment")) {
            const std::string where = "extensions.PRESKIN_environment";
            if (!env->is_object()) c.error(where, "not an object");
            const json* uri = c.member(*env, "uri");
            if (!uri || !uri->is_string()) c.error(where + ".uri", "missing or not a string");
            result.environmentPath = c.existingFile(uri->get<std::string>(), where + ".uri");
            if (const json* intensity = c.member(*env, "intensity")) {
                if (!intensity->is_number()) c.error(where + ".intensity", "not a number");
                const double value = intensity->get<double>();
                if (!std::isfinite(value) || value < 0.0) {
                    c.error(where + ".intensity", std::to_string(value) + " (must be finite and >= 0)");
                }
                result.environmentIntensity = static_cast<float>(value);
            }
            if (const json* rotation = c.member(*env, "rotation")) {
                if (!rotation->is_number()) c.error(where + ".rotation", "not a number");
                const double value = rotation->get<double>();
                if (!std::isfinite(value)) c.error(where + ".rotation", "not a finite number of radians");
                result.environmentRotation = static_cast<float>(value);
            }
        }
    }
    return result;
}

}  // namespace preskin::gltf
