// Morph targets (glTF 2.0, "Morph Targets"): per primitive the POSITION, NORMAL and TANGENT deltas
// of each target (any accessor type the accessor reader takes: float, normalized integers as
// KHR_mesh_quantization allows, sparse); per mesh the default weights and the target names from
// extras.targetNames. Other target attributes (TEXCOORD_n, COLOR_n) are ignored with a warning.
// Errors: a delta accessor whose count differs from POSITION's, primitives of one mesh with
// different target counts, mesh weights whose count differs from the target count.
#pragma once

#include "scene/GltfContext.h"

#include <string>

namespace preskin::gltf {

// Fills `out.targets` from `in.targets`; `where` is "meshes[m].primitives[p]".
void readMorphTargets(const LoadContext& ctx, const tinygltf::Primitive& in, const std::string& where,
                      size_t vertexCount, Primitive& out);

// Checks that every primitive of meshes[meshIndex] has the same number of targets and fills
// Mesh::weights (the file's, else zeros) and Mesh::targetNames.
void convertMorphWeights(const LoadContext& ctx, size_t meshIndex, Mesh& mesh);

}  // namespace preskin::gltf
