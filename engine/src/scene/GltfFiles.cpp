// File access for the glTF loader: limits, whole-file reads, .glb chunks, the URI policy.
// See GltfFiles.h for the policy and its limits.
#include "scene/GltfFiles.h"
#include "io/FolderConfinement.h"
#include "io/MessageText.h"
#include "scene/TinyGltf.h"

#include <preskin/Error.h>

#include <cctype>
#include <cstring>
#include <system_error>

namespace preskin::gltf {

namespace fs = std::filesystem;

void fail(const std::string& file, const std::string& where, const std::string& what) {
    const std::string text = io::messageText(what, 4 * io::kMessageExcerptChars);
    throw Error(where.empty() ? file + ": " + text : file + ": " + where + ": " + text);
}

namespace {

uint32_t readU32(std::span<const uint8_t> bytes, size_t offset) {
    uint32_t v = 0;
    std::memcpy(&v, bytes.data() + offset, 4);  // little endian on every supported platform
    return v;
}

constexpr uint32_t kGlbMagic = 0x46546C67;   // "glTF"
constexpr uint32_t kChunkJson = 0x4E4F534A;  // "JSON"
constexpr uint32_t kChunkBin = 0x004E4942;   // "BIN\0"

}  // namespace

GlbChunks splitGlb(std::span<const uint8_t> bytes, const std::string& file) {
    if (bytes.size() < 12) {
        fail(file, "GLB header", "truncated: " + std::to_string(bytes.size()) + " bytes, the header needs 12");
    }
    if (readU32(bytes, 0) != kGlbMagic) fail(file, "GLB header magic", "not 'glTF' (not a binary glTF file)");
    const uint32_t version = readU32(bytes, 4);
    if (version != 2) fail(file, "GLB header version", std::to_string(version) + ", only 2 is supported");
    const uint32_t length = readU32(bytes, 8);
    if (length != bytes.size()) {
        fail(file, "GLB header length",
             std::to_string(length) + " bytes, but the file has " + std::to_string(bytes.size()) +
                 (length > bytes.size() ? " (truncated)" : ""));
    }
    GlbChunks chunks;
    uint64_t offset = 12;
    int chunkIndex = 0;
    bool haveJson = false;
    while (offset < length) {
        const std::string where = "GLB chunk " + std::to_string(chunkIndex);
        if (offset + 8 > length) fail(file, where, "truncated chunk header");
        const uint32_t chunkLength = readU32(bytes, static_cast<size_t>(offset));
        const uint32_t chunkType = readU32(bytes, static_cast<size_t>(offset + 4));
        const uint64_t payload = offset + 8;
        if (payload + chunkLength > length) {
            fail(file, where + " length",
                 std::to_string(chunkLength) + " bytes runs past the end of the file (" +
                     std::to_string(length - payload) + " bytes left)");
        }
        if (chunkLength % 4 != 0)
            fail(file, where + " length", std::to_string(chunkLength) + " is not a multiple of 4");
        const auto data = bytes.subspan(static_cast<size_t>(payload), chunkLength);
        if (chunkIndex == 0) {
            if (chunkType != kChunkJson) fail(file, where + " type", "the first chunk must be JSON");
            if (chunkLength == 0) fail(file, where + " length", "empty JSON chunk");
            chunks.json = data;
            haveJson = true;
        } else if (chunkType == kChunkBin) {
            if (chunkIndex != 1)
                fail(file, where + " type", "a BIN chunk that does not directly follow the JSON chunk");
            chunks.bin = data;
            chunks.hasBin = true;
        } else if (chunkType == kChunkJson) {
            fail(file, where + " type", "a second JSON chunk");
        }
        // Chunks of other types are skipped, as the specification asks.
        offset = payload + chunkLength;
        ++chunkIndex;
    }
    if (!haveJson) fail(file, "GLB", "no JSON chunk");
    return chunks;
}

bool isDecodableDataUri(const std::string& uri) { return tinygltf::IsDataURI(uri); }

std::string base64Problem(const std::string& uri) {
    const size_t comma = uri.find(";base64,");
    if (comma == std::string::npos) return "not base64";
    const std::string_view payload = std::string_view(uri).substr(comma + 8);
    if (payload.size() % 4 != 0) {
        return "base64 length " + std::to_string(payload.size()) + " is not a multiple of 4";
    }
    size_t padding = 0;
    for (size_t i = 0; i < payload.size(); ++i) {
        const auto c = static_cast<unsigned char>(payload[i]);
        if (c == '=') {
            ++padding;
            continue;
        }
        if (padding > 0) return "base64 padding '=' before the end, at character " + std::to_string(i - padding);
        if (!std::isalnum(c) && c != '+' && c != '/') return "character " + std::to_string(i) + " is not base64";
    }
    if (padding > 2) return "base64 ends in " + std::to_string(padding) + " padding characters (at most 2)";
    return "";
}

std::string decodeUriLikeTinygltf(const std::string& uri) {
    auto hex = [](char c) -> unsigned {
        if (c >= '0' && c <= '9') return static_cast<unsigned>(c - '0');
        if (c >= 'a' && c <= 'f') return static_cast<unsigned>(c - 'a' + 10);
        if (c >= 'A' && c <= 'F') return static_cast<unsigned>(c - 'A' + 10);
        return 0;
    };
    std::string out;
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '+') {
            out += ' ';
        } else if (uri[i] == '%' && uri.size() > i + 2) {
            out += static_cast<char>((hex(uri[i + 1]) << 4) | hex(uri[i + 2]));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

bool isInsideFolder(const fs::path& path, const fs::path& folder) {
    const fs::path rel = path.lexically_normal().lexically_relative(folder.lexically_normal());
    if (rel.empty()) return false;
    const auto first = *rel.begin();
    return first != ".." && !rel.is_absolute();
}

namespace {

bool hasScheme(const std::string& uri) {
    // RFC 3986: scheme = ALPHA *( ALPHA / DIGIT / "+" / "-" / "." ) ":"
    if (uri.empty() || !std::isalpha(static_cast<unsigned char>(uri[0]))) return false;
    for (size_t i = 1; i < uri.size(); ++i) {
        const auto c = static_cast<unsigned char>(uri[i]);
        if (c == ':') return true;
        if (!std::isalnum(c) && c != '+' && c != '-' && c != '.') return false;
    }
    return false;
}

void checkRelativePath(const std::string& path, const std::string& raw, const std::string& file,
                       const std::string& where, const char* form) {
    const std::string quoted = "'" + raw + "'";
    if (path.empty()) fail(file, where, std::string("empty URI") + form);
    if (path.find('\0') != std::string::npos) fail(file, where, quoted + " contains a NUL character" + form);
    if (hasScheme(path)) {
        fail(file, where,
             quoted + " has a scheme or drive" + std::string(form) +
                 "; only relative paths inside the scene's folder are allowed");
    }
    if (path[0] == '/' || path[0] == '\\') {
        fail(file, where,
             quoted + " is an absolute path" + std::string(form) +
                 "; only relative paths inside the scene's folder are allowed");
    }
    size_t start = 0;
    while (start <= path.size()) {
        size_t end = path.find_first_of("/\\", start);
        if (end == std::string::npos) end = path.size();
        if (path.compare(start, end - start, "..") == 0) {
            fail(file, where, quoted + " leaves the scene's folder ('..')" + std::string(form));
        }
        start = end + 1;
    }
}

}  // namespace

const std::vector<std::string>& supportedRequiredExtensions() {
    static const std::vector<std::string> names = {"KHR_lights_punctual",
                                                   "KHR_materials_diffuse_transmission",
                                                   "KHR_materials_emissive_strength",
                                                   "KHR_materials_scatter",
                                                   "KHR_materials_volume",
                                                   "KHR_materials_volume_scatter",
                                                   "KHR_mesh_quantization",
                                                   "KHR_texture_transform",
                                                   "PRESKIN_environment",
                                                   "PRESKIN_lights_area",
                                                   "PRESKIN_materials_skin"};
    return names;
}

std::vector<uint8_t> decodeBase64DataUri(const std::string& uri, const std::string& file, const std::string& where) {
    if (const std::string problem = base64Problem(uri); !problem.empty()) fail(file, where, "data URI: " + problem);
    const std::string bytes = tinygltf::base64_decode(uri.substr(uri.find(";base64,") + 8));
    return std::vector<uint8_t>(bytes.begin(), bytes.end());
}

fs::path resolveUri(const std::string& uri, const fs::path& sceneFolder, const std::string& file,
                    const std::string& where, bool allowOutsideLinks) {
    if (uri.rfind("data:", 0) == 0) {
        fail(file, where, "unsupported data URI (only base64 with a media type tinygltf knows)");
    }
    checkRelativePath(uri, uri, file, where, "");
    const std::string decoded = decodeUriLikeTinygltf(uri);
    checkRelativePath(decoded, uri, file, where, " after percent-decoding");
    const fs::path resolved = (sceneFolder / fs::path(decoded)).lexically_normal();
    if (!isInsideFolder(resolved, sceneFolder)) fail(file, where, "'" + uri + "' leaves the scene's folder");
    if (allowOutsideLinks) return resolved;
    const io::ConfinedPath confined = io::resolveInsideFolder(sceneFolder, fs::path(decoded));
    if (!confined.inside) {
        fail(file, where,
             "'" + uri +
                 "' leads out of the scene's folder through a symbolic link (refused unless "
                 "links out of the folder are allowed)");
    }
    return confined.path;
}

}  // namespace preskin::gltf
