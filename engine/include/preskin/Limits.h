// Resource limits: what preskin accepts from files and the command line, so that no input can
// exhaust memory, time or the stack. docs/limits.md lists them with their reasons. Every limit is
// checked before the memory it guards is allocated, and a refusal names the file, the field and
// the limit ("scene.gltf: accessors[0].count: 33554432 exceeds the limit of 8388608 vertices").
//
// The one rule for numbers (kMaxInputMagnitude): every number that enters the engine (glTF
// values, profile and manifest fields, environment pixels, command-line options, the public
// setters) must be finite and at most 1e6 in magnitude, unless its field has a narrower range.
// Bounding every factor keeps the products the shaders form (intensity x colour x exposure x a
// specular peak over a squared distance, both floored in the shaders) inside the float range;
// as a last guard, an image that still holds a non-finite value is refused, never written.
#pragma once

#include <cstdint>

namespace preskin::limits {

// Files. Every file preskin opens must be a regular file (never a FIFO, device or folder).
inline constexpr uint64_t kMaxSceneFileBytes = 1ull << 30;   // .glb, .bin buffers, image files
inline constexpr uint64_t kMaxGltfJsonBytes = 128ull << 20;  // a .gltf file, a .glb's JSON chunk
inline constexpr uint64_t kMaxProfileBytes = 1ull << 20;     // a diffusion profile JSON file
inline constexpr uint64_t kMaxManifestBytes = 1ull << 20;    // a LUT folder's manifest.json
inline constexpr uint64_t kMaxImageFileBytes = 1ull << 30;   // environment and LUT images

// JSON (glTF, profiles, manifests).
inline constexpr int kMaxJsonDepth = 64;                     // nesting of arrays and objects
inline constexpr uint64_t kMaxJsonValues = 1ull << 24;       // values in one document
inline constexpr uint64_t kMaxGltfExtraValues = 1ull << 20;  // values inside a glTF's extras and extensions

// glTF objects: in all top-level arrays together, and per array for the large kinds.
inline constexpr uint64_t kMaxGltfObjects = 1ull << 20;
inline constexpr uint64_t kMaxGltfLargeObjects = 1ull << 16;  // materials, textures, images, samplers, cameras, lights

// Scene geometry, summed over the whole scene.
inline constexpr uint64_t kMaxSceneVertices = 1ull << 23;    // 8,388,608
inline constexpr uint64_t kMaxSceneIndices = 1ull << 25;     // triangle-list indices after strips and fans
inline constexpr uint64_t kMaxScenePrimitives = 1ull << 18;  // 262,144 mesh primitives
inline constexpr uint64_t kMaxSceneDraws = 1ull << 18;       // primitives times the instances drawing them
inline constexpr uint64_t kMaxDrawnTriangles = 1ull << 26;   // triangles times instances, per frame

// Images.
inline constexpr uint64_t kMaxImagePixels = 1ull << 26;  // one texture: 8192 x 8192
inline constexpr uint32_t kMaxImageSide = 16384;
inline constexpr uint64_t kMaxSceneImagePixels = 1ull << 27;  // all textures of a scene
inline constexpr uint32_t kMaxEnvironmentWidth = 8192;        // equirectangular: 8192 x 4096
inline constexpr uint32_t kMaxEnvironmentHeight = 4096;

// Diffusion profiles of one scene (LUT array layers: every Vulkan 1.3 device has at least 256,
// one of them is the default set's).
inline constexpr uint64_t kMaxSkinProfiles = 255;

// Numbers.
inline constexpr double kMaxInputMagnitude = 1e6;

// Area-light sizes (PRESKIN_lights_area radius, length, width, height) are (0, 1e6] metres; a
// size below this floor is taken as the floor (a size of 1e-300 would otherwise become 0 in
// single precision). A light that small renders as a point light of the same power: the shaders
// compute any size below a thousandth of the distance at that size (preskin/lights.glsl).
inline constexpr double kMinAreaLightSizeM = 1e-9;

}  // namespace preskin::limits
