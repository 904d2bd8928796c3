// Per-material parameters of the pre-integrated skin path. Read from the glTF material extension
// PRESKIN_materials_skin (every field, its JSON name, default and units: docs/gltf-extensions.md)
// or set by the host / CLI (--skin). Skin textures use TEXCOORD_0 without KHR_texture_transform.
#pragma once

#include <preskin/Glm.h>

#include <optional>
#include <string>
#include <vector>

namespace preskin {

enum class CurvatureSource {
    Vertex,       // per-vertex curvature computed from the mesh at load (default)
    Texture,      // a curvature texture (red channel, scaled by curvatureTextureScalePerM)
    Derivatives,  // screen-space derivatives length(fwidth(N)) / length(fwidth(P)) (Penner)
};

// Which skin techniques a material's shading compiles in: High all of them (the default), Medium
// and Low fewer, for skin that is small on screen (a crowd, a distant character). The tiers'
// techniques: shared/skin_features.h (kSkinQuality*); their cost and fidelity: docs/skin-cost.md.
enum class SkinQuality { Low, Medium, High };

// Per-vertex curvature of an animated (skinned or morphed) mesh.
enum class DeformedCurvature {
    Recomputed,  // from the deformed mesh every frame on the GPU, with computeVertexCurvature's estimator (default)
    BindPose,    // the rest pose's, as computed at load (what shipped pre-integrated skin does)
};

struct SkinTextureRef {
    int image = -1;    // index into Scene::images
    int sampler = -1;  // index into Scene::samplers, -1: default sampler
    bool valid() const { return image >= 0; }
};

// At most this many profiles blend on one material: the base profile plus one per RGB channel
// of the profile-weight texture.
inline constexpr int kMaxBlendedProfiles = 4;

struct SkinMaterial {
    // The diffusion profile: an index into Scene::profiles, -1 for the renderer's default set
    // (the bundled skin). Its LUTs are layer profile + 1 of the renderer's LUT arrays.
    int profile = -1;
    SkinQuality quality = SkinQuality::High;
    // Spatially varying profiles: up to three more profiles (indices as `profile`) weighted per
    // texel by the red, green and blue channels of profileWeightTexture (linear, TEXCOORD_0);
    // `profile` gets 1 - (r + g + b), and weights summing above 1 are scaled to sum to 1. Each
    // LUT lookup is the weighted sum of the profiles' lookups.
    std::vector<int> blendProfiles;
    SkinTextureRef profileWeightTexture;
    // How many profile millimetres one world millimetre is: curvature, penumbra width and
    // thickness are converted to profile units with it. 1 for a life-size head in metres.
    float scatterScale = 1.0f;
    CurvatureSource curvatureSource = CurvatureSource::Vertex;
    SkinTextureRef curvatureTexture;
    float curvatureTextureScalePerM = 100.0f;  // texture value 1.0 means this many 1/m
    // The texture value of zero curvature: curvature = (value - bias) * scale. 0 for maps of
    // convex curvature only, 0.5 for signed maps (bakeCurvatureMaps, `preskin bake-curvature`).
    float curvatureTextureBias = 0.0f;
    DeformedCurvature deformedCurvature = DeformedCurvature::Recomputed;  // with CurvatureSource::Vertex
    // Per-channel mip LOD bias of the normal map (R, G, B). Unset: derived from the profile's
    // per-channel scattering width and the mesh's texel density.
    std::optional<glm::vec3> normalLodBias;
    SkinTextureRef detailNormalTexture;
    float detailNormalScale = 1.0f;
    float detailUvScale = 8.0f;  // detail map tiling relative to TEXCOORD_0
    // Transmission through thin parts (ears, nostrils). 0 disables it for this material.
    float transmission = 1.0f;
    glm::vec3 transmissionColor{1.0f};
    float thicknessScale = 1.0f;  // scales the shadow-map thickness (KHR_materials_volume thicknessFactor)
    // Specular: dual-lobe GGX with F0 = 0.028 * specularIntensity * specular map.
    float specularIntensity = 1.0f;
    SkinTextureRef specularTexture;  // red channel scales F0
    float lobeRoughness0 = 0.75f;    // multipliers of the material roughness, lobe 0
    float lobeRoughness1 = 1.30f;    // lobe 1
    float lobeMix = 0.15f;           // weight of lobe 1
};

}  // namespace preskin
