// glTF 2.0 (.gltf and .glb) to preskin::Scene, through Debian's tinygltf 2.7.
//
// Order: read the file (a regular file within the limits of <preskin/Limits.h>) -> split the .glb
// container -> parse the JSON (depth- and size-limited, io/JsonDocument.h) and check it
// (GltfPrepass: versions, required extensions, object counts, URIs and links, buffer, view and
// accessor ranges, every index, lights) -> tinygltf
// parses the model, reading files only through callbacks that refuse anything outside the scene's
// folder, and decoding images through a callback: the host's decoder (SceneLoadOptions::decodeImage),
// then the registered codecs (<preskin/ImageCodec.h>) -> conversion: samplers,
// images, materials (GltfMaterials), meshes, the node hierarchy of the default scene (or scene 0,
// or all root nodes when the file has no scenes) flattened into world-space instances, lights and
// cameras.
//
// Meshes: GltfMeshes.h (per-mesh curvature included).
// Animation data (<preskin/Animation.h>): morph targets (GltfMorphTargets), joint influences and
// skins (GltfSkins), the node hierarchy (GltfNodes) and animations (GltfAnimations); instances
// keep the rest pose in MeshInstance::worldFromObject and name their node and skin.
//
// Lights: KHR_lights_punctual; a light's extras.castsShadow (boolean) marks shadow casters; when
// no light of the file has that key, the first directional light casts shadows.
// Cameras: scale is removed from the camera's node transform.
//
// Limits (<preskin/Limits.h>): vertices, indices, primitives, draws (primitives times instances)
// and drawn triangles per scene, pixels per image and per scene, all checked before the memory
// they guard is allocated; every number read passes the input-number rule (io/NumberRule.h).
// The node graph must be a forest (one parent per node, no cycles), with or without scenes.
//
// Bad input of any kind throws one preskin::Error "<file>: <field>: <problem>"; non-fatal
// issues are collected in Scene::warnings.
#pragma once

#include <preskin/Scene.h>

#include <cstdint>
#include <filesystem>
#include <vector>

namespace preskin::gltf {

Scene loadScene(const std::filesystem::path& path, const SceneLoadOptions& options);

// The same from the file's bytes already in memory (for fuzzing); `path` names the file in
// messages, gives the format by its extension and the folder that URIs are relative to.
Scene loadSceneBytes(std::vector<uint8_t> bytes, const std::filesystem::path& path, const SceneLoadOptions& options);

}  // namespace preskin::gltf
