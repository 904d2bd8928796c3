// Checks on the glTF JSON document made before tinygltf reads it, so that tinygltf never opens a
// file the URI policy refuses, never reads outside a buffer, and so that each problem gets a
// message naming the file and the field:
//   asset.version / minVersion (2.x), extensionsRequired (only what preskin implements),
//   buffers (byteLength, URI policy, the file exists and has byteLength bytes, data URIs decode to
//   byteLength bytes, the GLB BIN chunk is large enough), bufferViews (inside their buffer, stride),
//   images (uri or bufferView, URI policy, the file exists), the accessor indices that primitives
//   reference, and the root PRESKIN_environment extension.
// Everything else (accessor ranges, index values, finiteness, node graph) is checked while the
// tinygltf model is converted, see GltfLoader.cpp.
#pragma once

#include "scene/GltfFiles.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace preskin::gltf {

// Extensions whose presence in extensionsRequired is accepted.
const std::vector<std::string>& supportedRequiredExtensions();

struct PrepassResult {
    std::optional<std::filesystem::path> environmentPath;
    float environmentIntensity = 1.0f;
    float environmentRotation = 0.0f;
    std::vector<std::string> warnings;
};

// `glb` is set for binary files; its BIN chunk size bounds buffer 0.
PrepassResult checkDocument(const nlohmann::json& doc, const std::string& file,
                            const std::filesystem::path& folder, const GlbChunks* glb);

}  // namespace preskin::gltf
