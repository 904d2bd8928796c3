// Renderer::Impl: the state of the sample renderer (<preskin/Renderer.h>) and the steps of a
// frame, split along the frame's seams: the frame orchestration and per-frame data
// (Renderer.cpp), the shadow pass (ShadowPass.cpp), the forward pass (ForwardPass.cpp) and the
// diffusion baselines' parts (DiffusionPasses.cpp).
#pragma once

#include <preskin/Renderer.h>

#include "lights/ClusterBuilder.h"
#include "render/GpuDeformer.h"
#include "render/GpuEnvironment.h"
#include "render/GpuLuts.h"
#include "render/GpuScene.h"
#include "render/PoseBounds.h"
#include "render/PoseSurfaces.h"
#include "render/ScreenDiffusion.h"
#include "render/TextureDiffusion.h"
#include "vk/Pipeline.h"
#include "vk/Resources.h"

#include <array>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <tuple>
#include <vector>

namespace preskin {

inline constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
inline constexpr uint32_t kSlotCount = 2;
// start, after deformation, after curvature, after shadow, after clustering, after forward, and
// with screen-space diffusion after its horizontal and vertical passes
inline constexpr uint32_t kQueryCount = 9;

// The technique mask a quality tier compiles in (shared/skin_features.h's kSkinQuality*).
uint32_t skinQualityMask(SkinQuality quality);
// The widest environment image the renderer keeps (the backdrop's; the lights' search and the
// specular map read narrower copies): an 8192-wide image would hold 400 MB.
inline constexpr uint32_t kEnvironmentKeptWidth = 2048;

// What makes one forward pipeline differ from another.
// The area light types among `lights` as kSpecAreaLights holds them (render/ForwardPass.cpp).
uint32_t areaLightTypes(const std::vector<Light>& lights);

// PipelineKey::split: which pass of which diffusion method a pipeline draws.
inline constexpr uint32_t kForwardPlain = 0;       // preskin's forward pass (forward.frag)
inline constexpr uint32_t kForwardSplit = 1;       // screen-space: skin's diffuse light apart (forward_split.frag)
inline constexpr uint32_t kForwardTexture = 2;     // texture-space: skin's diffuse light read (forward_texture.frag)
inline constexpr uint32_t kTextureIrradiance = 3;  // texture-space: the irradiance pass (texture_irradiance.*)

struct PipelineKey {
    uint32_t model, alphaMode, doubleSided, format, depthFormat, debugView, skinMask, lightLoop, specular, eyes,
        samples, layered, profileMix, skinInputs, areaLights,
        split;  // a baseline's pass: kForwardPlain, kForwardSplit, kForwardTexture, kTextureIrradiance
    std::array<uint32_t, 32> lutMapping;  // skin: the material's own LutMapping, as bits (kSpecLutMapping)
    uint32_t depthOnly = 0;
    auto tie() const {
        return std::tie(model, alphaMode, doubleSided, format, depthFormat, debugView, skinMask, lightLoop, specular,
                        eyes, samples, layered, profileMix, skinInputs, areaLights, split, lutMapping, depthOnly);
    }
    bool operator<(const PipelineKey& o) const { return tie() < o.tie(); }
};

struct Renderer::Impl {
    struct Slot {
        vk::Buffer frameUniforms;
        vk::Buffer lights;
        vk::Buffer instances;            // GpuInstance per scene instance, from the pose
        uint64_t instancesPose = ~0ull;  // the pose version they hold
        VkDescriptorSet set = VK_NULL_HANDLE;
        VkDescriptorSet reduceSet = VK_NULL_HANDLE;  // the wide shadow map's reduction: shadow map in, wide map out
        VkQueryPool queries = VK_NULL_HANDLE;
        bool recorded = false;  // a frame was recorded into this slot (it may still be in flight)
        bool shadowRecorded = false;
        double wallMs = 0.0;
        double recordMs = 0.0;  // CPU time of record(), light-grid build included
        uint32_t eyes = 0;
        uint32_t lightCount = 0;
        bool split = false;    // the frame drew the screen-space baseline
        bool texture = false;  // the frame drew the texture-space baseline
    };

    Context& context;
    const vk::Device& dev;
    RenderSettings settings;
    EyeDrawing resolvedEyeDrawing = EyeDrawing::Multiview;
    std::vector<Light> lights;  // the scene's or the host's (setLights)
    Environment environment;    // its image at most kEnvironmentKeptWidth wide: all the renderer reads
    // The environment's dominant lights for settings.environmentLights (-1: resolved), and the
    // lights a frame shades: lights, then the extracted ones.
    int extractedCount = -2;
    EnvironmentLights extracted;
    std::vector<Light> extractedLights;
    std::vector<Light> frameLights;
    uint32_t frameAreaLightTypes = 0;  // areaLightTypes(frameLights), kept with them (pipeline keys read it per draw)
    int frameShadowLight = -1;         // shadowLightIndex(frameLights), likewise (skinMask)
    // The light this frame's shadow map is drawn for: frameShadowLight, -1 with shadows off.
    int shadowMapLight() const { return settings.shadows ? frameShadowLight : -1; }
    std::vector<gpu::GpuLight> gpuLights;             // this frame's light array, as the shaders read it
    std::vector<ClusterLight> gridLights;             // its point and spot lights as the light grid bounds them
    std::unique_ptr<GpuEnvironment> environmentMaps;  // the backdrop, the prefiltered cube, the DFG table
    Bounds bounds;                                    // of the scene in the current pose
    Bounds receivers;       // of the skin in the current pose: what the shadow map is fitted to (render/ShadowFit.h)
    std::string sceneName;  // for messages
    std::unique_ptr<GpuScene> scene;
    ScenePose pose;
    uint64_t poseVersion = 0;
    std::unique_ptr<PoseBounds> poseBounds;
    std::unique_ptr<PoseBounds> receiverPoseBounds;  // the skin's
    std::unique_ptr<PoseSurfaces> poseSurfaces;      // the drawn triangles, for the light grid
    uint64_t surfacesPose = UINT64_MAX;              // poseVersion of `surfaces`
    ClusterSurfaces surfaces;                        // poseSurfaces' triangles in that pose
    std::unique_ptr<GpuDeformer> deformer;
    std::unique_ptr<GpuLuts> luts;
    std::unique_ptr<ClusterBuilder> clusters;
    // RenderSettings::diffusion ScreenSpace: its passes and targets, made when a frame first uses them.
    std::unique_ptr<ScreenDiffusion> screenDiffusion;
    bool diffusionKernelsStale = true;  // the profiles or materials changed since its kernels were made
    // RenderSettings::diffusion TextureSpace: its textures and blur, made when a frame first uses
    // them; per scene draw its layer (UINT32_MAX: not skin), and the skin draws' (layer, material).
    std::unique_ptr<TextureDiffusion> textureDiffusion;
    bool textureKernelsStale = true;
    std::vector<uint32_t> drawLayers;
    std::vector<std::pair<uint32_t, uint32_t>> layerMaterials;

    VkDescriptorSetLayout frameLayout = VK_NULL_HANDLE;
    VkPipelineLayout forwardLayout = VK_NULL_HANDLE;
    VkPipelineLayout shadowLayout = VK_NULL_HANDLE;
    VkDescriptorPool framePool = VK_NULL_HANDLE;
    VkSampler shadowSampler = VK_NULL_HANDLE;
    std::array<Slot, kSlotCount> slots;
    // Attachments replaced while recording, kept until no slot's frame in flight can use them.
    struct Retired {
        vk::Image image;
        uint32_t slotsInFlight = 0;  // bit s: slot s's last frame was recorded before the replacement
    };
    std::vector<Retired> retired;
    vk::Image shadowMap;
    vk::Image wideShadowMap;   // skin's: the shadow map's nearest depth per block of wideFactor^2 texels
    uint32_t wideFactor = 8;   // this frame's (prepareFrame): the wide filter's footprint covers skinReachMm
    double skinReachMm = 0.0;  // world mm the widest skin profile scatters far enough to show (2 RMS widths)
    VkDescriptorSetLayout reduceSetLayout = VK_NULL_HANDLE;
    VkPipelineLayout reduceLayout = VK_NULL_HANDLE;
    VkPipeline reducePipeline = VK_NULL_HANDLE;
    bool sceneHasSkin = false;
    vk::Image depth;      // one layer per eye, msaaSamples samples
    vk::Image msaaColor;  // MSAA only: one layer per eye, resolved into the target
    std::map<PipelineKey, VkPipeline> pipelines;
    VkPipeline shadowPipeline = VK_NULL_HANDLE;      // depth only
    VkPipeline shadowMaskPipeline = VK_NULL_HANDLE;  // alpha-masked materials
    std::map<std::string, std::vector<uint32_t>> shaderOverrides;
    // Headless render target and readback.
    vk::Image colorTarget;
    vk::Buffer readback;

    // lutLayers: the LUT array layers (<preskin/ProfileLibrary.h>); empty: no LUTs.
    Impl(Context& ctx, const Scene& s, const Environment& env, const std::vector<const LutSet*>& lutLayers,
         const RenderSettings& rs);

    ~Impl();

    void createLayouts();

    // Extracts the environment's lights again when their count or the environment changed, and
    // makes frameLights; the strongest extracted light casts the shadow when no light does.
    void updateEnvironmentLights(bool environmentChanged);

    // Every skin material's profiles must have a layer (when there are LUTs at all).
    void checkProfileLayers(size_t layerCount) const;
    // Replaces the LUT arrays (after checking the materials against them).
    void setLutLayers(const std::vector<const LutSet*>& layers);
    // skinReachMm from the skin materials and their LUT layers' profiles.
    void updateSkinReach();
    // Destroys the skin pipelines (specialised to LUT mappings that may have changed); the GPU
    // must be idle. They are made again when drawn.
    void dropSkinPipelines();

    // Replaces an attachment without waiting: the old image lives on until every other slot
    // whose last frame was recorded with it has been recorded again (the host's slot contract).
    void retire(vk::Image& image, uint32_t slotIndex);

    // Recording into `slotIndex` means its previous frame finished: nothing retired waits on it.
    void releaseRetired(uint32_t slotIndex);

    // The shadow map at the settings' size, and skin's wide map for this frame's factor; new ones
    // start in the read layout (sampled even when no light casts a shadow), transitioned in `cmd`.
    void createShadowMap(VkCommandBuffer cmd, uint32_t slotIndex);
    void createWideShadowMap(VkCommandBuffer cmd, uint32_t slotIndex);
    uint32_t wideShadowSize() const;
    // The wide map's reduction of the shadow map (after the shadow pass, for scenes with skin).
    void recordWideShadow(VkCommandBuffer cmd, Slot& slot);

    std::span<const uint32_t> shader(const char* name) const;

    VkSampleCountFlagBits samples() const { return static_cast<VkSampleCountFlagBits>(settings.msaaSamples); }

    PipelineKey pipelineKey(const GpuMaterial& m, VkFormat format, VkFormat depthFormat, uint32_t eyes) const;
    // The skin techniques a skin material's pipelines compile in: the settings' switches, its
    // tier (or the settings' override), and what the diffusion baselines keep.
    uint32_t skinMask(const GpuMaterial& m) const;
    // Whether a skin pipeline of this frame reads the wide shadow map (penumbra scattering on for
    // its material's tier and the settings); else its reduction is not recorded.
    bool wideShadowRead() const;

    // The settings' EyeDrawing resolved for this device (see <preskin/Renderer.h>); resolved
    // when settings are set, since the probe submits work of its own.
    EyeDrawing eyeDrawing() const { return resolvedEyeDrawing; }

    void resolveEyeDrawing();

    // The forward pass's pipeline for a key, made when first drawn (kept in `pipelines`).
    VkPipeline pipeline(const PipelineKey& key);
    VkPipeline createPipeline(const PipelineKey& key) const;
    vk::GraphicsPipelineDesc forwardPassDesc(const PipelineKey& key) const;
    VkPipeline createForwardPipeline(const PipelineKey& key) const;
    // The backdrop's key (background*.vert, background.frag) for a target, eye count, samples and
    // eye drawing: model kModelBackground.
    PipelineKey backgroundKey(VkFormat format, VkFormat depthFormat, uint32_t eyes) const;
    PipelineKey depthPrepassKey(const PipelineKey& shading) const;
    VkPipeline createBackgroundPipeline(const PipelineKey& key) const;

    VkPipeline createShadowPipeline(bool masked) const;

    void setShaderOverrides(const std::map<std::string, std::vector<uint32_t>>& spirv);

    void setPose(ScenePose p);

    VkPipeline depthOnlyPipeline(bool masked);

    // The forward pass's own attachments: depth (unless the host's is used), and with MSAA the
    // multisampled colour (unless the screen-space baseline's is used). Replaced ones are
    // retired, never waited for.
    void ensureAttachments(VkExtent2D extent, uint32_t eyes, VkFormat colorFormat, bool ownDepth, bool ownMsaaColor,
                           uint32_t slotIndex);

    // Fills the slot's uniforms and light list; returns whether a shadow map is rendered.
    bool prepareFrame(Slot& slot, uint32_t slotIndex, const View& view, VkExtent2D extent,
                      glm::mat4& shadowClipFromWorld);

    void updateFrameSet(Slot& slot, uint32_t slotIndex);

    // Binds the index buffer; vertex buffers are bound per draw (bindDrawVertices).
    void bindGeometry(VkCommandBuffer cmd, VkBuffer& boundVertices);

    // Binds the vertices a draw reads (the scene's rest vertices, or this frame's deformed ones of
    // its instance) and returns its vertex offset.
    int32_t bindDrawVertices(VkCommandBuffer cmd, uint32_t slotIndex, const DrawItem& d, VkBuffer& bound);

    void recordShadowPass(VkCommandBuffer cmd, Slot& slot, uint32_t slotIndex);

    // `split`: the screen-space baseline's attachments after the target's (its diffuse and surface
    // targets), transitioned from undefined and left for sampling; empty otherwise.
    // `splitTonemapped`: its last pass tone-maps into a display target (the clear colour is
    // cleared to what maps to it).
    void recordForwardPass(VkCommandBuffer cmd, Slot& slot, uint32_t slotIndex, const RenderTarget& target,
                           const View& view, std::span<const ScreenDiffusion::Attachment> split = {},
                           bool splitTonemapped = false);

    // Whether this frame draws the screen-space baseline: Diffusion::ScreenSpace, skin with LUTs
    // in the scene (the baseline replaces skin's diffusion; without skin the frame is the same),
    // no debug view (which shows the forward pass's own values).
    bool splitDiffusion() const {
        return settings.diffusion == Diffusion::ScreenSpace && settings.debugView == DebugView::None && sceneHasSkin &&
            luts->valid();
    }
    // The baseline's passes, targets and kernels, ready for a frame of this target and view.
    ScreenDiffusion& prepareScreenDiffusion(const RenderTarget& target, uint32_t eyes, uint32_t slotIndex);
    // The same for the texture-space baseline.
    bool textureDiffusionFrame() const {
        return settings.diffusion == Diffusion::TextureSpace && settings.debugView == DebugView::None && sceneHasSkin &&
            luts->valid();
    }
    // Throws preskin::Error when its textures for this scene would exceed kMaxTextureDiffusionBytes.
    void checkTextureDiffusion() const;
    // Its textures, kernels and the skin draws' layers, ready for this frame.
    void prepareTextureDiffusion();
    // The irradiance pass of every skin draw and their blur (before the forward pass).
    void recordTextureDiffusion(VkCommandBuffer cmd, Slot& slot, uint32_t slotIndex);

    // Throws preskin::Error unless the view and settings can be drawn on this device.
    void checkFrame(const View& view) const;

    // Throws preskin::Error unless `record` can draw into the host's target as described.
    void checkTarget(const RenderTarget& target) const;

    uint32_t maxEyes() const { return std::min(kMaxEyes, dev.maxMultiviewViews()); }

    std::vector<uint32_t> msaaSampleCounts() const;

    void timestamp(VkCommandBuffer cmd, Slot& slot, uint32_t query);

    void record(VkCommandBuffer cmd, const RenderTarget& target, const View& view, uint32_t slotIndex);

    FrameStats stats(uint32_t slotIndex) const;
};

}  // namespace preskin
