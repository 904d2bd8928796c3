// A scene on the CPU, as loaded from glTF 2.0: meshes with a full tangent frame and per-vertex
// curvature, PBR materials (plus the optional skin parameters), decoded images, punctual lights
// and cameras. The node hierarchy is flattened into world-space mesh instances, lights and cameras.
// Units: metres, radians; light intensities as in KHR_lights_punctual (lux for directional,
// candela for point and spot).
//
// What the loader reads and how it treats bad input is described in engine/src/scene/GltfLoader.h
// and docs/gltf-extensions.md. In short: triangle lists, strips and fans (points and lines are
// skipped with a warning), TEXCOORD_0 only. Every primitive gets an index list (generated for
// non-indexed ones). Skins, morph targets, animations and the node hierarchy are loaded too
// (<preskin/Animation.h>, docs/animation.md); MeshInstance::worldFromObject is the rest pose.
#pragma once

#include <preskin/Animation.h>
#include <preskin/Export.h>
#include <preskin/ImageCodec.h>
#include <preskin/SkinMaterial.h>
#include <preskin/SkinProfile.h>

#include <preskin/Glm.h>
#include <preskin/KhronosScatter.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace preskin {

struct Bounds {
    glm::vec3 min{std::numeric_limits<float>::max()};
    glm::vec3 max{-std::numeric_limits<float>::max()};

    bool empty() const { return min.x > max.x; }
    void extend(const glm::vec3& p) {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }
    void extend(const Bounds& b) {
        if (!b.empty()) {
            extend(b.min);
            extend(b.max);
        }
    }
    glm::vec3 center() const { return 0.5f * (min + max); }
    glm::vec3 extent() const { return max - min; }
};

// One interleaved vertex, the layout the GPU reads (see shaders/shared/gpu_types.h).
struct Vertex {
    glm::vec3 positionOs{0.0f};
    glm::vec3 normalOs{0.0f, 0.0f, 1.0f};
    glm::vec4 tangentOs{1.0f, 0.0f, 0.0f, 1.0f};  // xyz tangent, w = bitangent sign
    glm::vec2 uv0{0.0f};
    float curvaturePerM = 0.0f;  // signed mean curvature in object-space units (> 0 convex; Curvature.h)
};

// One morph target of a primitive: per-vertex deltas, each either empty (the target does not
// move that attribute) or one per vertex. Tangent deltas move the tangent's xyz only.
struct MorphTarget {
    std::vector<glm::vec3> positionDeltas;
    std::vector<glm::vec3> normalDeltas;
    std::vector<glm::vec3> tangentDeltas;
};

// The joints a skinned vertex follows (JOINTS_0/WEIGHTS_0 and JOINTS_1/WEIGHTS_1): indices into
// the skin's joint list and weights summing to 1 (unused slots: weight 0).
struct JointInfluences {
    glm::uvec4 joints[2]{glm::uvec4(0u), glm::uvec4(0u)};
    glm::vec4 weights[2]{glm::vec4(0.0f), glm::vec4(0.0f)};
};

struct Primitive {
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;  // triangle list
    int material = -1;              // -1: the default material
    Bounds boundsOs;
    std::vector<MorphTarget> targets;         // morph targets (Mesh::weights are their defaults)
    std::vector<JointInfluences> influences;  // empty, or one per vertex for a skinned primitive
};

struct Mesh {
    std::string name;
    std::vector<Primitive> primitives;
    std::vector<float> weights;            // default morph weights, one per target (0 when absent)
    std::vector<std::string> targetNames;  // from the mesh's extras.targetNames, when given
};

struct MeshInstance {
    int mesh = 0;
    glm::mat4 worldFromObject{1.0f};  // in the rest pose
    std::string nodeName;
    int node = -1;  // Scene::nodes index (-1 for scenes built in code without nodes)
    int skin = -1;  // Scene::skins index when the instance is skinned

    // Object-to-world length scale (cube root of |det| of the 3x3 part): world-space curvature is
    // Vertex::curvaturePerM / curvatureScale() (exact for uniform scale, a mean otherwise).
    float curvatureScale() const { return std::cbrt(std::abs(glm::determinant(glm::mat3(worldFromObject)))); }
};

enum class Filter { Nearest, Linear };
enum class Wrap { Repeat, ClampToEdge, MirroredRepeat };

struct Sampler {
    Filter magFilter = Filter::Linear;
    Filter minFilter = Filter::Linear;
    Filter mipFilter = Filter::Linear;
    bool mipmaps = true;
    Wrap wrapU = Wrap::Repeat;
    Wrap wrapV = Wrap::Repeat;
};

// Decoded image, 8 bits per channel RGBA, top row first. The colour space is chosen per use
// (base colour and emissive are sRGB, everything else linear), so one image can serve both.
// 16-bit sources (PNG) also keep their full precision in rgba16, which linear uses (normal,
// curvature, thickness, weight maps, ...) upload as 16-bit textures; sRGB uses read rgba8.
struct Image {
    std::string name;  // the URI or "images[i]"
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<uint8_t> rgba8;
    std::vector<uint16_t> rgba16;  // empty, or the same texels at 16 bits (rgba8 is their rounding)
};

// A material's reference to a texture: glTF textureInfo plus KHR_texture_transform.
struct TextureRef {
    int image = -1;      // index into Scene::images, -1: none
    int sampler = -1;    // index into Scene::samplers, -1: default sampler
    float scale = 1.0f;  // normalTexture.scale or occlusionTexture.strength
    glm::vec2 uvOffset{0.0f};
    float uvRotation = 0.0f;  // radians, counter-clockwise as in KHR_texture_transform
    glm::vec2 uvScale{1.0f};

    bool valid() const { return image >= 0; }
    // The KHR_texture_transform matrix T(offset) * R(rotation) * S(scale), as a glm (column-major)
    // 3x3 whose last row is (0, 0, 1): uv' = (uvTransform() * vec3(uv, 1)).xy.
    PRESKIN_API glm::mat3 uvTransform() const;
};

enum class AlphaMode { Opaque, Mask, Blend };

struct Material {
    std::string name;
    glm::vec4 baseColorFactor{1.0f};
    float metallicFactor = 1.0f;
    float roughnessFactor = 1.0f;
    glm::vec3 emissiveFactor{0.0f};  // includes KHR_materials_emissive_strength
    TextureRef baseColor;
    TextureRef metallicRoughness;
    TextureRef normal;
    TextureRef occlusion;
    TextureRef emissive;
    AlphaMode alphaMode = AlphaMode::Opaque;
    float alphaCutoff = 0.5f;
    bool doubleSided = false;
    // Present when the material is shaded as skin (the PRESKIN_materials_skin extension,
    // or forced with Scene::makeSkin).
    std::optional<SkinMaterial> skin;
    // Values of KHR_materials_diffuse_transmission and KHR_materials_volume, when the material
    // has them. They seed SkinMaterial::transmission, transmissionColor and thicknessScale (at
    // load, and in makeSkin); PRESKIN_materials_skin's own fields win over them.
    std::optional<float> diffuseTransmissionFactor;
    std::optional<glm::vec3> diffuseTransmissionColor;
    std::optional<float> volumeThicknessFactor;  // mesh units; only values > 0 are kept
    // Scattering from KHR_materials_volume_scatter or KHR_materials_scatter (with
    // KHR_materials_volume's attenuation), when the material has it: a skin material that names
    // no profile gets profileFromKhronosScatter's profile (<preskin/KhronosScatter.h>), at load
    // and in makeSkin; a profile it names wins.
    std::optional<KhronosScatter> khronosScatter;
};

// Directional, point and spot lights are KHR_lights_punctual's. Sphere, tube, rectangle and disc
// lights have a size (PRESKIN_lights_area, docs/gltf-extensions.md); their intensity is in candela
// like a point light's: a sphere's in every direction, a tube's broadside, a rectangle's and a
// disc's along their normal (one-sided, with a cosine falloff), so a renderer that knows only
// points sees the same light from afar. docs/area-lights.md has the shading model.
enum class LightType { Directional, Point, Spot, Sphere, Tube, Rectangle, Disc };

struct Light {
    std::string name;
    LightType type = LightType::Directional;
    glm::vec3 color{1.0f};
    float intensity = 1.0f;  // lux (directional) or candela (point, spot)
    float range = 0.0f;      // metres, 0 = unlimited
    float innerConeAngle = 0.0f;
    float outerConeAngle = 0.7853982f;
    glm::vec3 positionWs{0.0f};
    glm::vec3 directionWs{0.0f, 0.0f, -1.0f};  // direction the light travels (rectangle, disc: their normal)
    // Area lights: sphere, tube and disc radius; tube length along axisWs; rectangle width along
    // axisWs and height along cross(axisWs, directionWs). Metres, > 0 for the types that use them.
    float radius = 0.0f;
    float length = 0.0f;
    float width = 0.0f;
    float height = 0.0f;
    glm::vec3 axisWs{1.0f, 0.0f, 0.0f};  // the node's +X
    // Directional lights: the angular radius of the disc they come from (radians, 0 = a parallel
    // light; the sun's is about 0.0047, at most pi / 4): a sphere light at infinity, which softens the
    // terminator and, for the shadow light, widens shadow penumbrae with the occluder's distance.
    float angularRadius = 0.0f;
    // From the light's extras.castsShadow (docs/gltf-extensions.md); when no light in the file
    // says either way, the first directional light casts shadows.
    bool castsShadow = false;
};

struct Camera {
    std::string name;
    std::string source;             // "<file>: cameras[i]", for messages about it
    glm::mat4 worldFromView{1.0f};  // rigid (node scale removed); view looks down -Z, +Y up
    bool orthographic = false;
    float yfov = 0.6f;         // radians (perspective)
    float aspectRatio = 0.0f;  // 0: use the viewport's
    float xmag = 1.0f;         // orthographic half extents
    float ymag = 1.0f;
    float znear = 0.01f;
    float zfar = 0.0f;  // 0: infinite (perspective only)
};

// How Scene::load treats the files a scene refers to.
struct SceneLoadOptions {
    // Buffers, images and the environment must lie in the scene file's folder or below it. A
    // symbolic link there that leads out of the folder is refused unless this is set (a scene
    // unpacked from an archive can carry such links).
    bool allowLinksOutsideFolder = false;
    // Images the host decodes itself (as Filament's gltfio TextureProvider): called for every image
    // of the scene with its encoded bytes, its URI (empty for images in buffer views) and its
    // media type (empty when the file states none); returns the decoded image (8- or 16-bit, or
    // float clamped to [0, 1]; 1 to 4 channels), or nothing to let preskin decode it with the
    // registered codecs (<preskin/ImageCodec.h>). Its exceptions refuse the scene, naming the image.
    std::function<std::optional<PixelImage>(std::span<const uint8_t> bytes, const std::string& uri,
                                            const std::string& mimeType)>
        decodeImage;
};

struct Scene {
    std::filesystem::path sourcePath;
    std::vector<Mesh> meshes;
    std::vector<MeshInstance> instances;
    std::vector<Material> materials;
    // Diffusion profiles the skin materials name (SkinMaterial::profile); empty: every skin
    // material uses the renderer's default set.
    std::vector<SkinProfile> profiles;
    std::vector<Image> images;
    std::vector<Sampler> samplers;
    std::vector<Light> lights;
    std::vector<Camera> cameras;
    std::vector<Node> nodes;  // the hierarchy (<preskin/Animation.h>)
    std::vector<Skin> skins;
    std::vector<Animation> animations;
    // Scene-level environment from the PRESKIN_environment extension (a file next to the scene).
    std::optional<std::filesystem::path> environmentPath;  // absolute; the file exists at load
    std::vector<uint8_t> environmentData;  // the environment's file content when the scene embeds it (a data URI)
    bool hasEnvironmentImage() const { return environmentPath.has_value() || !environmentData.empty(); }
    float environmentIntensity = 1.0f;
    float environmentRotation = 0.0f;  // radians about +Y, right-handed (+Z turns towards +X)
    // Non-fatal problems found while loading ("file: field: what was ignored"), for the host to show.
    std::vector<std::string> warnings;

    // Loads .gltf or .glb. Throws preskin::Error naming the file and the field on bad input,
    // including input beyond the limits of <preskin/Limits.h>.
    PRESKIN_API static Scene load(const std::filesystem::path& path, const SceneLoadOptions& options = {});

    PRESKIN_API Bounds worldBounds() const;
    // Marks materials as skin: every material for "all", else the materials with that name
    // (throws preskin::Error when no material has it). Existing skin parameters are kept.
    // "all" covers primitives without a material too: they get glTF's default material first
    // (addDefaultMaterial). A material made skin here gets `defaults`, then the material's KHR
    // transmission / volume values.
    PRESKIN_API void makeSkin(const std::string& materialName, const SkinMaterial& defaults = {});
    // Gives every primitive without a material (Primitive::material == -1, or an index past
    // `materials`) an explicit copy of glTF's default material (base colour 1, metallic 1,
    // roughness 1, opaque, single-sided), named kDefaultMaterialName and appended once to
    // `materials`. Returns its index, or -1 when every primitive already has a material.
    PRESKIN_API int addDefaultMaterial();
    // Gives the materials named `materialName` ("all": every material, as makeSkin) the
    // diffusion profile Scene::profiles[profile] (-1: the default set), making them skin first
    // where they are not. Throws preskin::Error when no material has the name or the profile
    // index is out of range.
    PRESKIN_API void setSkinProfile(const std::string& materialName, int profile);
    static constexpr const char* kDefaultMaterialName = "(default)";
};

}  // namespace preskin
