// Skins (glTF 2.0, "Skins"): per primitive the joint influences JOINTS_0/WEIGHTS_0 and
// JOINTS_1/WEIGHTS_1 (joints unsigned byte or short; weights float or normalized unsigned byte or
// short), normalised to sum 1 with one warning per primitive whose sums are off; per skin the
// joints, inverse bind matrices (float MAT4, identity when absent) and skeleton.
// Errors: influences missing on a primitive of a skinned mesh, a joint index out of range of a
// skin the mesh is drawn with, negative weights or a vertex without weight, a skin without joints,
// a joint or skeleton out of range, an inverseBindMatrices count other than the joint count.
#pragma once

#include "scene/GltfContext.h"

#include <string>

namespace preskin::gltf {

// Fills `out.influences` from the primitive's JOINTS_n/WEIGHTS_n; `where` is
// "meshes[m].primitives[p]". The nodes that draw meshes[meshIndex] with a skin bound the indices.
void readJointInfluences(const LoadContext& ctx, size_t meshIndex, const tinygltf::Primitive& in,
                         const std::string& where, size_t vertexCount, Primitive& out);

// Fills Scene::skins.
void convertSkins(const LoadContext& ctx);

}  // namespace preskin::gltf
