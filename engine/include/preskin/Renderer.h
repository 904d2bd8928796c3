// The sample renderer around the skin module: uploads a Scene, and renders frames of
//   shadow pass (one directional light) -> light clustering (compute) -> one forward pass
// either headless into an image it reads back, or into a host's command buffer and target.
// Skin adds no pass: all skin work happens in the forward pass's fragment shader.
// A frame draws every eye of its View (<preskin/View.h>): one shadow pass and one light grid
// serve all eyes, and the forward pass draws them all with multiview (each draw recorded once),
// optionally with MSAA resolved into the target.
#pragma once

#include <preskin/Animation.h>
#include <preskin/ClusterGrid.h>  // ClusterSettings: the light grid
#include <preskin/Context.h>
#include <preskin/Environment.h>
#include <preskin/Export.h>
#include <preskin/Scene.h>
#include <preskin/View.h>

#include <vulkan/vulkan_core.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace preskin {

class LutSet;
class ProfileLibrary;

// Each technique of the skin path on or off; off falls back to its standard equivalent
// (Lambert NoL, one normal, plain PCF shadow, Lambert SH, no transmission, one GGX lobe).
struct SkinFeatures {
    bool lutDiffuse = true;
    bool normalPrefilter = true;
    bool penumbra = true;
    bool shAmbient = true;
    bool transmission = true;
    bool dualSpecular = true;
    // The light of neighbours that face the point across a gap, a contact or a thin part (the
    // lips' line, the ear's folds; <preskin/NormalBasis.h>), from the shadow-casting light.
    bool opposingLight = true;
    // With normalPrefilter: the normal map read at each channel's level of detail (red blurred
    // most); off, read once, each channel's geometric normal carrying that one sample.
    bool normalMapLevels = true;
    // With penumbra: skin's wide shadow map, which carries red's scattering past the shadow
    // filter's reach (a reduction pass, nine more gathers per fragment); off, the penumbra LUT
    // acts within the shadow filter's reach only.
    bool widePenumbra = true;
    // With lutDiffuse: the diffuse LUT read for the shadow light; off, it is shaded by the
    // fragment's LUT row as a smoothed ramp, fitted per vertex (no fetch), as the other lights are.
    bool lutShadowLight = true;
    // The shadow filter over 8 x 8 texels of the shadow map (16 gathers); off, 6 x 6 (9 gathers),
    // the same Gaussian windowed at 3 texels, for a parallel shadow light (one with a size keeps
    // 8 x 8: its penumbra is the filter's width).
    bool fullShadowFilter = true;
    // With lutDiffuse: the diffuse LUT read for the lights other than the shadow light too (three
    // gathers per light and fragment) instead of the row's fit. An addition to the tiers that
    // read it for the shadow light (high, medium; kSkinAll in shared/skin_features.h), off by
    // default: the fit is what those lights get in every tier. A frame without a shadow map has
    // no shadow light: there every light reads the table where the shadow light would.
    bool lutOtherLights = false;
    // With lutDiffuse: each light that reads the diffuse LUT reads the row of convex skin's
    // curvature along that light near the terminator (from the principal curvatures of the
    // normal's screen derivatives) instead of the mean curvature's: a cylinder, an ear's rim, a
    // nose's bridge lit across them scatter past the terminator as a sphere of their curvature
    // across. ALU per such light, no fetch.
    bool lightCurvature = true;

    // Every technique off: the standard shading, with the standard material's 8 x 8 shadow filter.
    static SkinFeatures none() {
        return {false, false, false, false, false, false, false, false, false, false, true, false, false};
    }
    PRESKIN_API uint32_t mask() const;
    bool operator==(const SkinFeatures&) const = default;
};

// The techniques a quality tier compiles in, as SkinFeatures (shared/skin_features.h's kSkinQuality*).
PRESKIN_API SkinFeatures skinQualityFeatures(SkinQuality quality);

// The lights a frame is lit by: `lights`, then the environment's extracted lights
// (extractEnvironmentLights) as directional lights named "environment light N", with their
// angular radius where `lightSizes` (RenderSettings::environmentLightSizes), the first casting
// the shadow when none of `lights` does. The renderer lights every frame so, with the ambient SH
// the extraction leaves (EnvironmentLights::residualSh); the diffusion reference with an SH
// ambient takes the same lights and ambient.
PRESKIN_API std::vector<Light> withEnvironmentLights(const std::vector<Light>& lights,
                                                     const EnvironmentLights& extracted, bool lightSizes);

enum class DebugView { None, Curvature, Normals, Shadow, Penumbra, LightCount, ShAmbient, Transmission };

// How the one forward pass draws several eyes; either way each draw is recorded once.
//  - Multiview: the pass has one view per eye (viewMask), the vertex stage reads gl_ViewIndex.
//  - InstancedLayers: one instance per eye, the vertex stage writes gl_Layer (needs the Vulkan
//    1.2 shaderOutputLayer feature).
//  - Auto: Multiview, unless the device fails the multiview clipping probe (Mesa lavapipe 22.3
//    loses clipped triangles in the second view; render/MultiviewProbe.h) and offers
//    shaderOutputLayer.
enum class EyeDrawing { Auto, Multiview, InstancedLayers };

// What the forward pass shows where no surface is drawn.
//  - Color: the colour (linear; an 8-bit sRGB target encodes it), not exposed or tone-mapped;
//  - Environment: the environment's radiance in each pixel's direction (its image, turned by its
//    rotation), exposed and tone-mapped like surfaces, drawn in the forward pass as one triangle
//    at the far plane after the opaque draws (no extra pass), in every eye, with MSAA;
//  - Transparent: RGBA 0 (alpha 0), for compositing.
// A host that keeps its own colour (RenderTarget::loadColor) gets no clear; Environment still draws.
enum class BackgroundMode { Color, Environment, Transparent };
struct Background {
    BackgroundMode mode = BackgroundMode::Color;
    glm::vec3 color{0.045f, 0.045f, 0.05f};
};

// How the forward pass finds the local (point and spot) lights of a fragment.
enum class LightLoop { Clustered, All };

// How skin's diffuse light is scattered (docs/baselines.md).
//  - PreIntegrated: preskin's own, inside the one forward pass (curvature LUTs, per-channel
//    normals, penumbra LUT, SH transfer; RenderSettings::skin).
//  - ScreenSpace: the screen-space separable baseline it replaces (Jimenez et al., "Separable
//    Subsurface Scattering", CGF 2015): skin shades as Lambert (with the skin's specular and
//    transmission) and its diffuse light, written to a target of its own, is blurred along rows and
//    columns by each skin material's profile, depth-aware, then added to the frame: 2 more passes
//    and 4 more targets (3 more with MSAA), resolved before the blur, one blur per eye. The kernel
//    is the profile's line profile (exact for straight edges of light; skin/SeparableKernel.h);
//    the albedo is blurred with the light (pre-scatter texturing, as published). Limits: blended
//    materials over skin do not hide its blurred light; a host's loadColor is refused.
//  - TextureSpace: the texture-space baseline (d'Eon, Luebke, Enderton, "Efficient Rendering of
//    Human Skin", EGSR 2007): each skin draw's diffuse light (Lambert, white albedo) rendered
//    into a texture in its mesh's UV layout, blurred there by each Gaussian of the profile (a
//    sum of Gaussians, or a fit of one) with stretch correction, read back by the forward pass
//    times the albedo: per skin draw 1 + 2 x Gaussians more passes and 5 textures. Limits: skin
//    meshes need TEXCOORD_0 laid out without overlaps in [0, 1]; light does not cross UV seams.
enum class Diffusion { PreIntegrated, ScreenSpace, TextureSpace };

struct RenderSettings {
    SkinFeatures skin;
    // Every skin material at this quality tier instead of its own (SkinMaterial::quality).
    std::optional<SkinQuality> skinQuality;
    DebugView debugView = DebugView::None;
    LightLoop lightLoop = LightLoop::Clustered;
    ClusterSettings clusters;
    float exposure = 1.0f;
    uint32_t shadowMapSize = 2048;
    float shadowSoftnessTexels = 1.5f;  // Gaussian sigma of the PCF kernel, in shadow-map texels
    bool shadows = true;
    // true: the shadow map covers the skin in view (small texels where skin receives shadows);
    // false: the whole scene's bounding sphere. Without skin in view both cover the scene.
    bool fitShadowToSkin = true;
    // How far (world mm) skin's wide shadow map (the shadow map's nearest depths per block, which
    // carries red's scattering into cast shadows past the shadow map's filter) must reach: its
    // blocks are sized for it each frame. 0: two RMS widths of the widest profile any skin
    // material uses (3.3 mm for d'Eon's skin at scatter scale 1). Set it to give materials the
    // same wide map whatever other profiles the scene holds.
    float skinShadowReachMm = 0.0f;
    // false: no specular reflection for any material, and diffuse without the Fresnel factors
    // (1 - F) that specular takes from it: pure diffuse, what DiffusionReference models.
    bool specular = true;
    // true: the environment's specular reflection from its GGX-prefiltered cube and the split-sum
    // DFG table (preskin/ibl.glsl); false: from the cosine-convolved L2 SH in the reflection
    // direction (exact for rough surfaces, too blurry for glossy ones; no cube lookups).
    bool specularIbl = true;
    // Samples per pixel of the forward pass (any count of Renderer::msaaSampleCounts()), resolved
    // into the target by averaging. Shading stays per pixel; alpha-mask materials use
    // alpha-to-coverage when this is above 1.
    uint32_t msaaSamples = 1;
    // true: the forward pass draws the opaque meshes' depth first (their vertex stage alone), so
    // that their shading runs only where they are seen; the image is the same either way.
    bool depthPrepass = true;
    EyeDrawing eyeDrawing = EyeDrawing::Auto;
    // true: where a skin material's curvature is per vertex, what depends on curvature alone (the
    // SH transfer, the shadow lookup's lift, the transmittance the diffuse LUT already holds:
    // preskin/skin_vertex.glsl) is found per vertex and interpolated; false: per fragment.
    bool skinTermsPerVertex = true;
    // Directional lights extracted from the environment (extractEnvironmentLights in
    // <preskin/Environment.h>), shaded like any directional light (skin's LUT diffuse, penumbra
    // and transmission); the ambient SH is the environment's less their radiance. The strongest
    // casts the shadow when no light of the scene does. -1: one when the renderer has no lights
    // of its own, none otherwise; 0 .. kMaxEnvironmentLights: that many at most.
    int environmentLights = -1;
    // Those lights keep their spread as an angular radius (EnvironmentLight::angularRadius): a
    // terminator softened by it, and the shadow's penumbra widening with the occluder's distance
    // (docs/area-lights.md, suns); off, they are parallel lights with sharp shadows, cheaper on a
    // CPU driver.
    bool environmentLightSizes = false;
    Background background;
    Diffusion diffusion = Diffusion::PreIntegrated;
    // Diffusion::ScreenSpace: taps of each direction's kernel (odd, 3 to 63; Jimenez et al. ship
    // 7 to 25).
    uint32_t screenDiffusionTaps = 17;
    // Diffusion::TextureSpace: texels per side of each skin draw's irradiance texture (16 to 8192;
    // changing it waits for the device).
    uint32_t textureDiffusionSize = 1024;
};

enum class OutputEncoding {
    DisplaySrgb8,  // tone-mapped, sRGB-encoded 8-bit (PNG)
    LinearFloat,   // scene-referred linear radiance times exposure (EXR)
};

// One image per eye, eye after eye (eye e's rows start at pixel e * width * height).
struct RenderedImage {
    uint32_t width = 0;   // per eye
    uint32_t height = 0;  // per eye
    uint32_t eyes = 1;
    OutputEncoding encoding = OutputEncoding::DisplaySrgb8;
    std::vector<uint8_t> rgba8;  // DisplaySrgb8
    std::vector<float> rgba32f;  // LinearFloat
};

// Eye `eye` of an image, as a one-eye image.
PRESKIN_API RenderedImage eyeImage(const RenderedImage& image, uint32_t eye);
// Every eye side by side in one image, eye 0 (left) on the left.
PRESKIN_API RenderedImage sideBySide(const RenderedImage& image);

struct PassTime {
    std::string name;
    double gpuMs = 0.0;
};

struct FrameStats {
    std::vector<PassTime> passes;  // GPU timestamps per pass (empty when unsupported)
    double gpuMs = 0.0;            // first to last timestamp
    double wallMs = 0.0;           // CPU wall clock of record + submit + wait (headless only)
    uint32_t lightCount = 0;
    uint32_t clusterOverflows = 0;   // clusters whose list was truncated (<preskin/ClusterGrid.h>)
    double clusterBuildCpuMs = 0.0;  // CPU time of the light-list build or its compute setup (part of wallMs)
    double recordCpuMs = 0.0;        // CPU time of Renderer::record without the light-list build
    uint32_t eyes = 0;               // eyes drawn
    EyeDrawing eyeDrawing = EyeDrawing::Multiview;  // how (never Auto)
    bool clusterBuildGpu = false;    // the light lists came from the compute pass (ClusterSettings::build)
    uint64_t clusterGridBytes = 0;   // the light grid's buffers as allocated (ranges, indices, headroom included)
    glm::uvec3 clusterDims{0u};      // the light grid's tiles across, down and depth slices
    uint32_t clusterTileSizePx = 0;  // its tile edge (ClusterSettings::tileSizePx, or the one chosen)
    // What the diffusion method adds to the one forward pass (RenderSettings::diffusion): passes,
    // render targets and their bytes (0 for PreIntegrated).
    uint32_t diffusionPasses = 0;
    uint32_t diffusionTargets = 0;
    uint64_t diffusionTargetBytes = 0;
};

// The host's depth attachment, when `record` should test against and write the host's depth
// (RenderTarget::depth). It must follow preskin's conventions: reversed Z (1 at the near plane, 0
// at infinity, compare GREATER_OR_EQUAL) with the view's projections (<preskin/View.h>), one
// layer per eye, and RenderSettings::msaaSamples samples. Any depth or depth-stencil format the
// device can render; the stencil is neither read nor written.
struct DepthTarget {
    VkImage image = VK_NULL_HANDLE;  // VK_NULL_HANDLE: preskin uses its own depth (cleared each frame)
    VkImageView view = VK_NULL_HANDLE;
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkImageLayout layoutBefore = VK_IMAGE_LAYOUT_UNDEFINED;
    VkImageLayout layoutAfter = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    bool load = true;  // keep the host's depth (it drew first); false: clear to the far plane (0)
};

// Where `record` draws: the host's colour image, in `layoutBefore` on entry and left in
// `layoutAfter`. An 8-bit UNORM/SRGB format gets tone-mapped output, a float one linear.
// Eye e of the view lands in array layer e: the image has at least as many layers as the view
// has eyes and `view` covers layers 0 .. eyes - 1 (a 2D_ARRAY view; a 2D view for one eye), as
// an OpenXR multiview swapchain image does. With MSAA, preskin renders into its own
// multisampled image and resolves into this one.
// Inside a host's frame: `loadColor` keeps what the host drew (preskin draws over it instead of
// clearing; needs msaaSamples 1 and a defined layoutBefore), and `depth` makes preskin's draws
// test against the host's depth and write it.
struct RenderTarget {
    VkImage image = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkExtent2D extent{};
    VkImageLayout layoutBefore = VK_IMAGE_LAYOUT_UNDEFINED;
    VkImageLayout layoutAfter = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    bool loadColor = false;
    DepthTarget depth;
};

class PRESKIN_API Renderer {
public:
    // luts may be null: skin materials then render with the standard model. With one LUT set,
    // every skin material must use the default profile (SkinMaterial::profile -1).
    Renderer(Context& context, const Scene& scene, const Environment& environment, const LutSet* luts,
             const RenderSettings& settings = {});
    // Several diffusion profiles: the library's layers become the layers of the LUT arrays
    // (<preskin/ProfileLibrary.h>). Throws preskin::Error when a skin material names a profile
    // the library has no layer for.
    Renderer(Context& context, const Scene& scene, const Environment& environment, const ProfileLibrary& profiles,
             const RenderSettings& settings = {});
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    const RenderSettings& settings() const;
    void setSettings(const RenderSettings& settings);
    // The pose drawn from the next frame on (<preskin/Animation.h>): per mesh instance its
    // transform, morph weights and joint matrices, from an animation (animationNodePose +
    // posedScene) or a host's own animation system. Skinned and morphed instances are deformed on
    // the GPU every frame (compute pass "deform"); nothing is rebuilt. The initial pose is
    // restPose(scene). Throws preskin::Error when the pose does not fit the scene (counts,
    // non-finite values); the previous pose is kept then.
    void setPose(const ScenePose& pose);
    const ScenePose& pose() const;
    // Replaces the lights (the scene's lights are the initial set).
    void setLights(const std::vector<Light>& lights);
    const std::vector<Light>& lights() const;
    // Replaces the environment: its SH ambient, its dominant lights (RenderSettings::
    // environmentLights) and its maps for specular reflection and the background, prefiltered
    // on the device at once (waits for the device: call it between frames, not per frame).
    void setEnvironment(const Environment& environment);
    // The lights extracted from the environment that frames add to lights() (directional,
    // strongest first; see RenderSettings::environmentLights).
    const std::vector<Light>& environmentLights() const;
    void setLuts(const LutSet* luts);
    void setProfiles(const ProfileLibrary& profiles);
    // Replaces the tables of one layer (a re-baked profile: layer p + 1 for Scene::profiles[p])
    // and uploads only that layer. Throws preskin::Error when the layer does not exist or a table
    // is larger than the arrays' (setProfiles rebuilds them).
    void setProfileLayer(size_t layer, const LutSet& luts);
    // Replaces the SPIR-V of built-in shader stages by file name ("forward.vert", "forward_layers.vert", "forward.frag",
    // "shadow.vert", "background.vert", "background_layers.vert", "background.frag"); stages missing from the map use the code built into the library. Every
    // pipeline in use is rebuilt at once; when that fails, throws preskin::Error and keeps the
    // previous code and pipelines (so a host can hot-reload shaders and survive bad edits).
    void setShaderOverrides(const std::map<std::string, std::vector<uint32_t>>& spirvByFile);

    // The most eyes a view may have on this device (kMaxEyes or the device's multiview limit).
    uint32_t maxEyes() const;
    // The MSAA sample counts this device offers for the forward pass, ascending (1 first).
    std::vector<uint32_t> msaaSampleCounts() const;

    // Headless: renders one frame of every eye (width x height each) and reads it back.
    RenderedImage render(const View& view, uint32_t width, uint32_t height, OutputEncoding encoding);
    // Embedded: records one frame into the host's command buffer. `frameSlot` (0 or 1) selects
    // the per-frame buffers; the host must not reuse a slot before its previous frame finished.
    // Recording never waits for the device: attachments that change size (target extent, eye
    // count, MSAA, shadow-map size) are replaced, and the old ones are destroyed once every slot
    // that may still use them has been recorded again. Throws preskin::Error on a target it
    // cannot draw (see RenderTarget) before recording anything.
    void record(VkCommandBuffer cmd, const RenderTarget& target, const View& view, uint32_t frameSlot = 0);
    // Timings of the last finished frame of a slot (reads its timestamp queries).
    FrameStats frameStats(uint32_t frameSlot = 0) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// Writes an image atomically (a temporary file renamed into place): .png for DisplaySrgb8,
// .exr (half float) for LinearFloat, where radiance above the half range saturates at 65504;
// several eyes side by side (sideBySide). Throws preskin::Error naming the path on failure, and
// refuses (writes nothing) an image that holds a non-finite value.
PRESKIN_API void writeImage(const std::filesystem::path& path, const RenderedImage& image);
// Throws preskin::Error unless `path` has a supported extension for the encoding and can be
// written under the output rule of <preskin/OutputFile.h> (missing folders are made when the
// image is written; an existing file that is read-only or not a regular file is never
// replaced); call before expensive work.
PRESKIN_API void checkOutputPath(const std::filesystem::path& path, OutputEncoding encoding);

}  // namespace preskin
