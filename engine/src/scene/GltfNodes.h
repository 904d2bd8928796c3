// The node hierarchy as the file has it (glTF 2.0, "Nodes and Hierarchy"): Scene::nodes holds
// every node of the file at its glTF index, with its parent, children, rest transform (TRS; a
// matrix is kept in Node::matrix and decomposed into Node::transform), mesh, skin and morph
// weights. The loader then flattens the default scene into world-space instances, lights and
// cameras (GltfLoader.cpp, with the hierarchy's world transforms of anim/NodeHierarchy.h, as
// posing does), linking each instance to its node and skin.
// Errors: a node with two parents or in a cycle, a zero-length rotation, a skin without a mesh
// on the node, node weights whose count differs from the mesh's morph target count.
#pragma once

#include "scene/GltfContext.h"

#include <glm/glm.hpp>

namespace preskin::gltf {

// Fills Scene::nodes and checks that they form a forest; runs after the meshes are converted
// (their target counts) and before the default scene is flattened.
void convertNodeHierarchy(const LoadContext& ctx);

// Translation, rotation and scale of a matrix without shear or projection, as glTF requires of
// node matrices; a negative determinant goes into the x scale. m = T * R * S up to rounding.
NodeTransform decomposeMatrix(const glm::mat4& m);

}  // namespace preskin::gltf
