// glTF meshes to preskin meshes (glTF 2.0, "Meshes"): POSITION (required), NORMAL (flat normals
// when missing, as the spec asks, and repaired where degenerate), TEXCOORD_0, TANGENT (generated
// when missing, TangentFrames.h); all index widths and non-indexed primitives; normalized integer
// attributes; sparse accessors. Triangle strips and fans become lists; points and lines are
// skipped with a warning; a primitive repeated verbatim is converted once. Morph targets and joint
// influences (GltfMorphTargets, GltfSkins) and per-vertex curvature (<preskin/Curvature.h>) are
// attached here. Limits: vertices and indices per scene (<preskin/Limits.h>), checked before
// allocating.
#pragma once

#include "scene/GltfContext.h"

namespace preskin::gltf {

// Fills Scene::meshes; runs after the materials are converted.
void convertMeshes(const LoadContext& ctx);

}  // namespace preskin::gltf
