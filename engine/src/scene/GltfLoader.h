// glTF 2.0 (.gltf and .glb) to preskin::Scene, through Debian's tinygltf 2.7 and OpenImageIO.
//
// Order: read the file (regular files up to 1 GiB) -> split the .glb container -> parse and check
// the JSON (GltfPrepass: versions, required extensions, URIs, buffer and view ranges) -> tinygltf
// parses the model, reading files only through callbacks that refuse anything outside the scene's
// folder, and decoding images through a callback that uses OpenImageIO -> conversion: samplers,
// images, materials (GltfMaterials), meshes, the node hierarchy of the default scene (or scene 0,
// or all root nodes when the file has no scenes) flattened into world-space instances, lights and
// cameras.
//
// Meshes: POSITION (required), NORMAL (flat normals when missing, as the spec asks), TEXCOORD_0,
// TANGENT (generated when missing, TangentFrames.h); all index widths and non-indexed primitives;
// normalized integer attributes; sparse accessors. Triangle strips and fans become lists; points
// and lines are skipped with a warning. Curvature is computed per mesh (Curvature.h).
// Animation data (<preskin/Animation.h>): morph targets (GltfMorphTargets), joint influences and
// skins (GltfSkins), the node hierarchy (GltfNodes) and animations (GltfAnimations); instances
// keep the rest pose in MeshInstance::worldFromObject and name their node and skin.
//
// Lights: KHR_lights_punctual; a light's extras.castsShadow (boolean) marks shadow casters; when
// no light of the file has that key, the first directional light casts shadows.
// Cameras: scale is removed from the camera's node transform.
//
// Bad input of any kind throws one preskin::Error "<file>: <field>: <problem>"; non-fatal
// issues are collected in Scene::warnings.
#pragma once

#include <preskin/Scene.h>

#include <filesystem>

namespace preskin::gltf {

Scene loadScene(const std::filesystem::path& path);

}  // namespace preskin::gltf
