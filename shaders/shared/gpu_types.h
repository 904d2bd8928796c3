// GPU-visible structs, binding numbers and specialization-constant ids of the renderer, read by
// C++ (engine/src/render) and GLSL (shaders/*). See common.h for the layout rules.
#ifndef PRESKIN_SHARED_GPU_TYPES_H
#define PRESKIN_SHARED_GPU_TYPES_H

#include "shared/common.h"
#include "shared/constants.h"
#include "shared/light.h"
#include "shared/lut_mapping.h"
#include "shared/skin_features.h"

PRESKIN_GPU_BEGIN

// ---- descriptor set 0: per frame -------------------------------------------------------------
PRESKIN_CONST(uint, kBindingFrame, 0)          // FrameUniforms (uniform buffer)
PRESKIN_CONST(uint, kBindingLights, 1)         // GpuLight[] (storage buffer)
PRESKIN_CONST(uint, kBindingInstances, 2)      // GpuInstance[] (storage buffer)
PRESKIN_CONST(uint, kBindingShadowMap, 3)      // depth, sampled with NEAREST taps (manual PCF)
// The LUTs are 2D array textures, one layer per diffusion profile (layer 0: the default set).
PRESKIN_CONST(uint, kBindingDiffuseLut, 4)     // D(NoL, curvature)
PRESKIN_CONST(uint, kBindingPenumbraLut, 5)    // P(penumbra position, width)
PRESKIN_CONST(uint, kBindingShTransferLut, 6)  // A_l(curvature), bands 0..2
PRESKIN_CONST(uint, kBindingTransmittanceLut, 7)  // T(thickness)
PRESKIN_CONST(uint, kBindingClusterRanges, 8)  // uvec2 (offset, count) per cluster
PRESKIN_CONST(uint, kBindingClusterIndices, 9) // uint light indices
PRESKIN_CONST(uint, kBindingWideShadowMap, 10)    // skin: the shadow map's nearest depth per block (R32F; shadow_reduce.comp)
// The environment (render/GpuEnvironment.cpp, preskin/ibl.glsl): its equirectangular image with
// mips (the background), the prefiltered specular cube and the split-sum DFG table.
PRESKIN_CONST(uint, kBindingEnvironmentImage, 11)
PRESKIN_CONST(uint, kBindingPrefilteredEnvironment, 12)
PRESKIN_CONST(uint, kBindingDfgTable, 13)

// ---- descriptor set 1: per material ----------------------------------------------------------
PRESKIN_CONST(uint, kBindingMaterial, 0)  // MaterialUniforms (uniform buffer)
PRESKIN_CONST(uint, kBindingBaseColorTexture, 1)
PRESKIN_CONST(uint, kBindingMetallicRoughnessTexture, 2)
PRESKIN_CONST(uint, kBindingNormalTexture, 3)
PRESKIN_CONST(uint, kBindingOcclusionTexture, 4)
PRESKIN_CONST(uint, kBindingEmissiveTexture, 5)
PRESKIN_CONST(uint, kBindingSpecularTexture, 6)      // skin: F0 scale (red)
PRESKIN_CONST(uint, kBindingDetailNormalTexture, 7)  // skin: detail normal map
PRESKIN_CONST(uint, kBindingCurvatureTexture, 8)     // skin: curvature (red)
PRESKIN_CONST(uint, kBindingProfileWeightTexture, 9) // skin: weights of the blended profiles (RGB)
PRESKIN_CONST(uint, kMaterialTextureCount, 9)

// ---- specialization constants of forward.frag ------------------------------------------------
PRESKIN_CONST(uint, kSpecMaterialModel, 0)  // kModelStandard or kModelSkin
PRESKIN_CONST(uint, kSpecOutputMode, 1)     // kOutputLinear or kOutputTonemapped
PRESKIN_CONST(uint, kSpecDebugView, 2)      // kDebug* (shared/constants.h)
PRESKIN_CONST(uint, kSpecAlphaMode, 3)      // kAlphaOpaque, kAlphaMask, kAlphaBlend (shared/constants.h)
PRESKIN_CONST(uint, kSpecSkinFeatures, 4)   // bit mask of kSkin* (shared/skin_features.h)
PRESKIN_CONST(uint, kSpecLightLoop, 5)      // kLightLoopClustered or kLightLoopAll
PRESKIN_CONST(uint, kSpecAlphaToCoverage, 6)  // 1: alpha-mask coverage from alpha (MSAA), 0: discard
PRESKIN_CONST(uint, kSpecSpecular, 7)       // kSpecular* below (RenderSettings::specular, specularIbl)
PRESKIN_CONST(uint, kSpecProfileMix, 8)     // entries of a skin material's profile mix: 1 (its own), 2..4 (blended)
PRESKIN_CONST(uint, kSpecSkinInputs, 9)     // a skin material's inputs and how to read them: kSkinInput* below
PRESKIN_CONST(uint, kSpecLutMapping, 10)    // 32 ids: a skin material's own profile's LutMapping, member by member (xyzw)
PRESKIN_CONST(uint, kSpecAreaLights, 42)   // the frame's area light types: bit (kLight* - kLightSphere) each, 0: none
PRESKIN_CONST(uint, kSpecCount, 43)
// kSpecAreaLights' bit for a shadow light with an angular radius (its penumbrae widen with the
// occluder's distance); a directional light with one also sets kLightSphere's bit (1).
PRESKIN_CONST(uint, kAreaLightSizedShadow, 16)

// Bits of kSpecSkinInputs.
PRESKIN_CONST(uint, kSkinInputDetailNormals, 1u)       // a detail normal map
PRESKIN_CONST(uint, kSkinInputCurvatureShift, 1u)      // bits 1-2: the curvature source, kCurvatureSource*
PRESKIN_CONST(uint, kSkinInputNormalLevelsShift, 3u)   // bits 3-7: the whole levels the biased normals blend
                                                       // (normalLevelCount, PreskinNormalMaps::levelCount)
PRESKIN_CONST(uint, kSkinInputSpecularMap, 256u)       // a specular map
PRESKIN_CONST(uint, kSkinInputDoubleSided, 512u)       // double-sided (the vertex stage cannot tell the facing)
PRESKIN_CONST(uint, kSkinInputTermsPerFragment, 1024u) // curvature-only terms per fragment (RenderSettings::skinTermsPerVertex off)
PRESKIN_CONST(uint, kSkinInputSpecularFromLevels, 2048u)  // the unbiased normal from the biased samples' levels
PRESKIN_CONST(uint, kSkinInputSpecularInBaseAlpha, 4096u)  // the specular map in the base colour's alpha (GpuScene packs it)

PRESKIN_CONST(uint, kModelStandard, 0)
PRESKIN_CONST(uint, kModelSkin, 1)
PRESKIN_CONST(uint, kModelBackground, 2)  // the renderer's backdrop pipeline (background.frag), not a material model
PRESKIN_CONST(uint, kOutputLinear, 0)
PRESKIN_CONST(uint, kOutputTonemapped, 1)
PRESKIN_CONST(uint, kLightLoopAll, 0)
PRESKIN_CONST(uint, kLightLoopClustered, 1)
PRESKIN_CONST(uint, kSpecularOff, 0)  // diffuse only, no Fresnel taken from it
PRESKIN_CONST(uint, kSpecularSh, 1)   // specular; the environment's from its L2 SH
PRESKIN_CONST(uint, kSpecularIbl, 2)  // specular; the environment's from the prefiltered cube (preskin/ibl.glsl)


struct GpuInstance {
    mat4 worldFromObject;
    mat4 normalWorldFromObject;  // inverse transpose of the upper 3x3
    vec4 params;                 // x: 1 / uniform scale (object curvature -> world curvature)
};
PRESKIN_CHECK_SIZE(GpuInstance, 144)

// The most eyes (multiview views) one frame draws; equals preskin::kMaxEyes (<preskin/View.h>).
PRESKIN_CONST(uint, kMaxEyes, 6)

struct EyeUniforms {
    mat4 clipFromWorld;
    vec4 positionWs;            // xyz camera position, w unused
    vec4 viewDepthFromWorld;    // view depth (m, along the view direction) = dot(this, vec4(p, 1))
};
PRESKIN_CHECK_SIZE(EyeUniforms, 96)

struct FrameUniforms {
    EyeUniforms eyes[kMaxEyes]; // indexed by gl_ViewIndex
    mat4 clusterFromWorld;      // light grid camera (ClusterCamera): rows clip x, clip y, view depth, clip w
    mat4 shadowClipFromWorld;   // directional shadow: orthographic, depth 0 (near) .. 1 (far)
    vec4 params;                // x: exposure, y: eye count
    vec4 viewport;              // per eye: width, height, 1/width, 1/height
    vec4 shadowParams;          // x texel size (m), y Gaussian sigma (texels), z depth range (m), w map size
    vec4 shadowDirectionWs;     // xyz direction the shadow light travels, w: 1 when a shadow map exists (its light is lights[0])
    vec4 shRadiance[9];         // L2 SH of environment radiance, RGB (environment intensity applied)
    uvec4 lightCounts;          // x: lights, y: directional lights (first y entries), z: cluster index capacity
    vec4 clusterScale;          // x,y: tiles per unit of cluster-camera NDC (tile = (ndc + 1) * xy),
                                // z,w: depth slice = log2(viewDepth) * z + w
    uvec4 clusterDims;          // x, y, z clusters; w: max lights per cluster
    vec4 wideShadow;            // skin's wide shadow map: x its uv per shadow-map uv, y its size (texels), z its
                                // texel size (m), w shadow-map texels per side of its texels
    vec4 environment;           // x, y: cos and sin of the environment's turn about +Y, z: the prefiltered cube's
                                // last mip level (roughness 1), w unused
    vec4 shadowIrradiance;      // rgb: the shadow light's irradiance (lights[0].colorIntensity.rgb), w unused
};
PRESKIN_CHECK_SIZE(FrameUniforms, 6 * 96 + 2 * 64 + 4 * 16 + 9 * 16 + 6 * 16)

// Per-texture transform rows (KHR_texture_transform): uv' = (dot(r0.xyz, (u,v,1)), dot(r1.xyz, (u,v,1))).
struct GpuUvTransform {
    vec4 row0;
    vec4 row1;
};

struct MaterialUniforms {
    vec4 baseColorFactor;
    vec4 emissiveAlphaCutoff;  // rgb emissive factor (strength applied), w alpha cutoff
    vec4 pbr;                  // x metallic, y roughness, z normal scale, w occlusion strength
    vec4 skinScatter;          // x scatter scale, y curvature texture bias (the curvature source is
                               // kSpecSkinInputs), z curvature texture scale (1/m), w transmission strength
    vec4 skinTransmission;     // rgb transmission colour, w thickness scale
    vec4 skinSpecular;         // x F0 scale, y lobe-0 roughness multiplier, z lobe-1 multiplier, w lobe-1 weight
    vec4 textureFlags;         // x detail normal scale, y detail uv scale, z unused (a detail map and a specular
                               // map are kSpecSkinInputs), w has normal map
    vec4 hasTextures;          // 1 where the texture exists: x base colour, y metallic-roughness, z occlusion, w emissive
    vec4 skinProfileLayers;    // LUT array layers: x the profile, y z w the blended ones (SkinMaterial::blendProfiles)
    vec4 skinProfileBlend;     // x: blended profiles (0..3), weighted by the profile-weight texture's r, g, b
    GpuUvTransform uv[5];      // base colour, metallic-roughness, normal, occlusion, emissive
    LutMapping skinLuts[4];    // the LutMapping of each skinProfileLayers entry; the forward pass takes entry 0
                               // from its pipeline's specialization (kSpecLutMapping) instead
    vec4 skinNormalLodBias[4];  // rgb: the normal maps' LOD bias per channel for each skinProfileLayers entry
    vec4 skinNormalBasis[12];  // the weights of the normal basis (normalBasisWeights of <preskin/NormalBasis.h>) at
                               // the material's scatter scale: red, green, blue of each skinProfileLayers entry
};
PRESKIN_CHECK_SIZE(MaterialUniforms, 10 * 16 + 5 * 32 + 4 * 128 + 4 * 16 + 12 * 16)

// ---- the screen-space baseline's passes (shaders/screen_diffusion.frag, render/ScreenDiffusion.h) ----
PRESKIN_CONST(uint, kBindingDiffusionInput, 0)    // skin's diffuse light (premultiplied by coverage), linear filter
PRESKIN_CONST(uint, kBindingDiffusionSurface, 1)  // RG32F: view depth (m), skin material index + 1 (times coverage)
PRESKIN_CONST(uint, kBindingDiffusionScene, 2)    // the rest of the frame, linear radiance (the vertical pass)
PRESKIN_CONST(uint, kBindingDiffusionKernels, 3)  // per material: 1 / 2v per channel (1/m^2), then per tap rgb weight, w offset (m)
PRESKIN_CONST(uint, kSpecDiffusionPass, 0)        // kDiffusionHorizontal or kDiffusionVertical
PRESKIN_CONST(uint, kSpecDiffusionTaps, 1)        // taps per kernel (odd)
PRESKIN_CONST(uint, kSpecDiffusionOutput, 2)      // the vertical pass's output: kOutputLinear or kOutputTonemapped
PRESKIN_CONST(uint, kDiffusionHorizontal, 0)      // the diffuse light along rows, to an intermediate target
PRESKIN_CONST(uint, kDiffusionVertical, 1)        // along columns, added to the rest of the frame, into the target

// The texture-space baseline (render/TextureDiffusion.h): its blurred irradiance in the forward
// pass (set 0), and its blur passes (shaders/texture_blur.frag, their own set).
PRESKIN_CONST(uint, kBindingDiffusionTexture, 14)  // sampler2DArray: one layer per skin draw (DrawPush.indices.z)
PRESKIN_CONST(uint, kBindingBlurInput, 0)          // the level blurred (irradiance premultiplied by coverage)
PRESKIN_CONST(uint, kBindingBlurStretch, 1)        // metres per texel along u, v
PRESKIN_CONST(uint, kSpecBlurAccumulate, 0)        // 1: the vertical pass, which also adds weight * level to the sum

struct BlurPush {
    vec4 direction;  // xy: the texel axis (1, 0) or (0, 1); z: the Gaussian's standard deviation (world m); w: layer
    vec4 weight;     // rgb: the Gaussian's weight per channel in the profile (the vertical pass adds weight * level);
                     // a: 1 for the first Gaussian (its pass adds the coverage to the sum's alpha), else 0
};
PRESKIN_CHECK_SIZE(BlurPush, 32)

struct DiffusionPush {
    vec4 eyeScale[kMaxEyes];  // per eye: x, y pixels per metre at view depth 1 (perspective) or at any depth
                              // (orthographic); z: 1 perspective, 0 orthographic
    uvec4 params;             // x: materials with kernels
};
PRESKIN_CHECK_SIZE(DiffusionPush, 6 * 16 + 16)

// Per draw.
struct DrawPush {
    uvec4 indices;  // x: instance index
};
PRESKIN_CHECK_SIZE(DrawPush, 16)

PRESKIN_GPU_END

#endif
