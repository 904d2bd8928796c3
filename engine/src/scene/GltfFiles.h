// File access for the glTF loader: the size limits, reading whole regular files, the binary
// container (.glb) split into its JSON and BIN chunks, and the URI policy.
//
// URI policy: a buffer, image or environment URI is either a data URI of a media type tinygltf
// decodes, or a relative reference to a file in the scene's folder or below it. Refused before
// any file is touched: a scheme (file:, http:, C:), an absolute path, a ".." segment, an empty
// path or an embedded NUL, also when they only appear after percent-decoding. Symbolic links
// inside the folder are followed (the folder's owner placed them).
//
// GLB layout (glTF 2.0 spec, "Binary glTF Layout"): 12-byte header (magic "glTF", version 2,
// total length), then a JSON chunk and an optional BIN chunk, each an 8-byte header (length,
// type) and a payload padded to 4 bytes. Every length is checked against the file's size.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace preskin::gltf {

// Limits that keep hostile files from exhausting memory or time.
inline constexpr uint64_t kMaxFileBytes = 1ull << 30;        // scene, buffer and image files
inline constexpr uint64_t kMaxAccessorCount = 1ull << 25;    // elements in one accessor
inline constexpr uint64_t kMaxImagePixels = 1ull << 28;      // 16384 x 16384
inline constexpr uint32_t kMaxImageDimension = 32768;
inline constexpr int kMaxJsonDepth = 64;

// Joins the lines of a third-party message into one line.
std::string oneLine(const std::string& text);

// "<file>: <where>: <what>" as one preskin::Error (`what` joined into one line).
[[noreturn]] void fail(const std::string& file, const std::string& where, const std::string& what);

// Reads a whole regular file of at most kMaxFileBytes. `label` names it in the error message.
std::vector<uint8_t> readRegularFile(const std::filesystem::path& path, const std::string& label);

struct GlbChunks {
    std::span<const uint8_t> json;
    std::span<const uint8_t> bin;  // empty when the file has no BIN chunk
    bool hasBin = false;
};
// Splits a .glb; throws naming `file` and the header field on any inconsistency.
GlbChunks splitGlb(std::span<const uint8_t> bytes, const std::string& file);

// True for the data URIs tinygltf decodes (base64 with a known media type).
bool isDecodableDataUri(const std::string& uri);

// Percent-decodes as tinygltf does before it opens a file ('+' also becomes a space).
std::string decodeUriLikeTinygltf(const std::string& uri);

// Applies the URI policy to a non-data URI and returns the file's absolute path (lexically
// normal, inside `sceneFolder`). Throws "<file>: <where>: ..." when refused; touches no file.
std::filesystem::path resolveUri(const std::string& uri, const std::filesystem::path& sceneFolder,
                                 const std::string& file, const std::string& where);

// Lexical test: is `path` (absolute, normalised) `folder` or below it?
bool isInsideFolder(const std::filesystem::path& path, const std::filesystem::path& folder);

// Deepest nesting of arrays/objects in JSON text (strings skipped); stops counting past `limit`.
int jsonNestingDepth(std::span<const uint8_t> text, int limit);

}  // namespace preskin::gltf
