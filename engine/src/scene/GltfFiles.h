// File access for the glTF loader: the binary container (.glb) split into its JSON and BIN
// chunks, and the URI policy. Files are read through io::readInputFile (regular files only,
// size limits of <preskin/Limits.h>).
//
// URI policy: a buffer, image or environment URI is either a data URI of a media type tinygltf
// decodes (strict base64: only its alphabet, padding only at the end, a length that is a
// multiple of 4), or a relative reference to a file in the scene's folder or below it. Refused
// before any file is touched: a scheme (file:, http:, C:), an absolute path, a ".." segment, an
// empty path or an embedded NUL, also when they only appear after percent-decoding. Symbolic
// links are followed only while they stay inside the scene's folder (io/FolderConfinement.h),
// unless the caller allows links that leave it; a refusal reveals nothing about the outside.
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

// "<file>: <where>: <what>" as one preskin::Error (`what` joined into one line, length-bounded).
[[noreturn]] void fail(const std::string& file, const std::string& where, const std::string& what);

struct GlbChunks {
    std::span<const uint8_t> json;
    std::span<const uint8_t> bin;  // empty when the file has no BIN chunk
    bool hasBin = false;
};
// Splits a .glb; throws naming `file` and the header field on any inconsistency.
GlbChunks splitGlb(std::span<const uint8_t> bytes, const std::string& file);

// True for the data URIs tinygltf decodes (base64 with a known media type).
// Extensions whose presence in extensionsRequired is accepted.
const std::vector<std::string>& supportedRequiredExtensions();

bool isDecodableDataUri(const std::string& uri);

// Why the base64 payload of a decodable data URI is not strict base64, or "" when it is.
std::string base64Problem(const std::string& uri);
// The bytes of a base64 data URI of any media type ("data:<type>;base64,<payload>"); fails naming
// `file` and `where` when it is not base64 or the payload is malformed.
std::vector<uint8_t> decodeBase64DataUri(const std::string& uri, const std::string& file, const std::string& where);

// Percent-decodes as tinygltf does before it opens a file ('+' also becomes a space).
std::string decodeUriLikeTinygltf(const std::string& uri);

// Applies the URI policy to a non-data URI and returns the file's absolute path (inside
// `sceneFolder`, its links resolved unless `allowOutsideLinks`). Throws "<file>: <where>: ..."
// when refused; examines nothing outside the folder.
std::filesystem::path resolveUri(const std::string& uri, const std::filesystem::path& sceneFolder,
                                 const std::string& file, const std::string& where, bool allowOutsideLinks);

// Lexical test: is `path` (absolute, normalised) `folder` or below it?
bool isInsideFolder(const std::filesystem::path& path, const std::filesystem::path& folder);

}  // namespace preskin::gltf
