// Checks on the glTF JSON document made before tinygltf reads it, so that tinygltf never opens a
// file the URI policy refuses, never reads outside a buffer, never sees a value it would
// silently turn into a default (a negative index becomes "absent" there, a 64-bit offset is
// truncated), and so that each problem gets a message naming the file and the field. What the
// glTF 2.0 schema and the Khronos glTF-Validator call an error is refused here:
//   asset.version / minVersion (2.x), extensionsRequired (only what preskin implements), the
//   object counts of <preskin/Limits.h>, every "extensions" value an object;
//   buffers (byteLength, URI policy, the file exists and has byteLength bytes, data URIs are
//   strict base64 and decode to byteLength bytes, the GLB BIN chunk is large enough), bufferViews
//   (inside their buffer, stride), accessors (byteOffset, count, componentType, type, sparse
//   counts, offsets and types), images (uri or bufferView, URI policy, the file exists);
//   every index into another array (glTFid: an integer >= 0 below that array's length) in
//   scenes, nodes, meshes (at least one primitive each), materials' textureInfo, textures,
//   skins and animations; KHR_lights_punctual lights (type, colour in [0, 1], intensity >= 0,
//   range > 0, spot cone angles); the root PRESKIN_environment extension; and the root
//   PRESKIN_materials_skin extension's diffusion profiles (every field, LUT folders exist).
// What needs the model (accessor ranges against views, index values, finiteness of data, the
// node graph) is checked while the tinygltf model is converted, see GltfLoader.cpp.
#pragma once

#include "scene/GltfFiles.h"

#include <preskin/SkinProfile.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace preskin::gltf {

struct PrepassResult {
    std::optional<std::filesystem::path> environmentPath;
    std::vector<uint8_t> environmentData;  // a data URI's bytes (environmentPath then unset)
    float environmentIntensity = 1.0f;
    float environmentRotation = 0.0f;
    std::vector<SkinProfile> profiles;  // the root PRESKIN_materials_skin extension's
    std::vector<std::string> warnings;
    std::vector<size_t> skippedCameras;                        // cameras of no glTF type: the loader leaves them out
    std::vector<std::pair<size_t, size_t>> skippedPrimitives;  // (mesh, primitive) that draw nothing
};

// `glb` is set for binary files; its BIN chunk size bounds buffer 0.
PrepassResult checkDocument(const nlohmann::json& doc, const std::string& file, const std::filesystem::path& folder,
                            const GlbChunks* glb, bool allowOutsideLinks);

}  // namespace preskin::gltf
