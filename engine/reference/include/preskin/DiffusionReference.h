// DiffusionReference: ground-truth diffuse radiance of a scene under the diffusion model that
// every skin LUT approximates, computed on the CPU with ray-traced visibility (Embree 3) on all
// cores (TBB). It is the yardstick `preskin reference` writes and `preskin compare` measures the
// skin and Lambert renders against.
//
// Model, per shaded point x (the first surface along a pixel's ray, as the rasterizer sees it):
//   L(x) = albedo(x) / pi * int_S Rn(|x - y|) E(y) dA(y)      (skin materials)
//   L(x) = albedo(x) / pi * E(x)                              (other materials: Lambert)
// with Rn the diffusion profile divided by its own albedo (the LUTs' normalisation; the colour
// comes from the material), distances in profile millimetres (world millimetres times the
// material's scatter scale), S every skin surface of the scene (the triangles, with the vertex
// normals interpolated, i.e. the surface the rasterizer shades), and E(y) the irradiance at y
// from the renderer's own light definitions: every punctual light with its KHR_lights_punctual
// falloff, the shadow-casting directional light visible only along an unoccluded ray (Embree;
// the ray starts from the point lifted onto the surface the vertex normals imply, Hanika,
// "Hacking the Shadow Terminator", Ray Tracing Gems II, 2021), the other lights unshadowed as
// in the renderer, plus the environment's L2 SH irradiance (Lambert's zonal coefficients,
// unshadowed as in the renderer) times the material's occlusion texture. The albedo is the base
// colour factor times the texture (sRGB, mipmapped and filtered trilinearly at the pixel's
// footprint, like the GPU); emissive is added. Specular is not part of the model.
//
// Method (docs/reference.md has the derivation, the error bounds and the convergence figures):
// the surface integral is a graded quadrature around x. Every skin triangle within the
// profile's reach (the radius holding all but `tailFraction` of its energy) is split 4-way until
// each piece is smaller than `leafRatio` times its distance to x (and no smaller than
// `finestLeafRatio` times the profile's narrowest scale); E is evaluated at the pieces' corners
// (cached per thread), taken as linear over each piece, and integrated against the profile with
// an adaptive degree-5 triangle rule (Dunavant 1985) refined until the profile's moments over the
// piece change by less than `momentTolerance`. Results do not depend on the thread count:
// every pixel is computed alone, in a fixed order.
//
// Limits: distances are straight lines (light crosses air gaps within the reach as if it were
// tissue: lips, eyelids); the profile is the one of `profile` for every skin material, scaled by
// the shaded point's scatter scale; normal maps are not applied (the smooth surface only; the
// skin path's normal prefiltering is therefore not measured); alpha-blended materials are
// treated as opaque; the shadow light's visibility is sharp (a point light source).
#pragma once

#include <preskin/DiffusionProfile.h>
#include <preskin/Environment.h>
#include <preskin/Export.h>
#include <preskin/Scene.h>
#include <preskin/View.h>

#include <glm/glm.hpp>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace preskin {

struct ReferenceSettings {
    double tailFraction = 1e-4;     // profile energy left out beyond the reach, per channel
    double leafRatio = 0.5;         // irradiance piece size / its distance from x
    double finestLeafRatio = 1.0;   // smallest piece / the profile's narrowest scale
    double momentTolerance = 1e-7;  // adaptive profile quadrature, per piece (the profile integrates to 1)
    bool shadows = true;            // false: the shadow light is unshadowed too (RenderSettings::shadows)
    // The environment's light: 0 takes the renderer's L2 SH irradiance (unshadowed, times the
    // occlusion texture, as the renderer does); N > 0 traces the environment image with N rays
    // per vertex (importance-sampled, occluded by the scene), the truth the SH ambient stands for.
    // Tracing needs the constructor that takes the Environment.
    uint32_t environmentSamples = 0;
    // A pixel is "near a cast-shadow edge" when visible points that face the shadow light, some
    // lit and some in a cast shadow, lie within this many times the profile's widest channel
    // width (profile mm, so divided by the scatter scale in world units) of its point.
    double shadowEdgeWidths = 2.0;
    // A skin pixel is in the "terminator band" when the interpolated normal's cosine to the shadow
    // light lies within [kTerminatorBandNoL] and no visible point in a cast shadow of that light
    // lies within this distance of its point (profile mm, divided by the scatter scale as above):
    // where the shadow map shadows the surface itself, away from any occluder's shadow.
    double terminatorClearanceMm = 12.0;
};

// The cosines to the shadow light that bound the terminator band (ReferenceSettings).
inline constexpr double kTerminatorBandNoL[2] = {-0.1, 0.2};

// What the reference knows about one shaded point.
struct ReferenceSample {
    glm::dvec3 positionWs{0.0};
    glm::dvec3 normalWs{0.0};              // interpolated vertex normal, facing the viewer
    glm::dvec3 radiance{0.0};              // linear, before exposure
    bool skin = false;                     // the visible material is skin
    double curvaturePerMm = 0.0;           // signed mean curvature in profile 1/mm (> 0 convex), skin only
    bool facesShadowLight = false;         // N.L > 0 for the shadow-casting light
    bool inCastShadow = false;             // ... and the point is occluded from it
    std::optional<double> shadowLightNoL;  // the normal's cosine to the shadow light; none without one
    uint32_t irradianceSamples = 0;        // E evaluations the integral used (a cost figure)
};

struct ReferenceImage {
    uint32_t width = 0;
    uint32_t height = 0;
    // Linear radiance times exposure, RGBA, top row first; alpha 1 where a surface is visible,
    // 0 on the background (which holds the renderer's clear colour).
    std::vector<float> rgba32f;
    std::vector<uint8_t> skin;            // 1 where the visible surface is skin
    std::vector<float> curvaturePerMm;    // signed, profile 1/mm; 0 off skin
    std::vector<uint8_t> nearShadowEdge;  // 1 near a cast-shadow edge (ReferenceSettings::shadowEdgeWidths)
    std::vector<uint8_t> terminatorBand;  // 1 in the terminator band (ReferenceSettings::terminatorClearanceMm)
    uint64_t irradianceSamples = 0;       // sum over pixels
};

// What a reference image was made of, as (name, value) pairs in a fixed order: the scene, view,
// size, lights and settings a reader checks before it reuses the image.
using ReferenceKey = std::vector<std::pair<std::string, std::string>>;

// A reference image with everything `preskin compare` measures by (radiance and alpha, the skin
// mask, the signed curvature, the shadow-edge mask) as a 32-bit float OpenEXR file: channels R,
// G, B, A, skin, curvaturePerMm, nearShadowEdge, terminatorBand; the key as string attributes
// "preskin:NAME".
// Written into a temporary file renamed into place. Throws preskin::Error naming the file.
PRESKIN_API void writeReferenceImage(const std::filesystem::path& path, const ReferenceImage& image,
                                     const ReferenceKey& key);
// Reads such a file back with its key (every "preskin:" attribute, in the file's order). Throws
// preskin::Error naming the file and the missing or malformed channel.
PRESKIN_API ReferenceImage readReferenceImage(const std::filesystem::path& path, ReferenceKey& key);

// Fraction done in [0, 1]; calls are serialised and non-decreasing, the last one is 1.
using ReferenceProgress = std::function<void(double fraction)>;

class PRESKIN_API DiffusionReference {
public:
    // `lights` as given to the renderer (Renderer::setLights); the shadow light is the first
    // directional light flagged castsShadow, as in the renderer. Throws preskin::Error on bad
    // settings or scene data.
    DiffusionReference(const Scene& scene, const std::vector<Light>& lights, const ShRgb& radianceSh,
                       const DiffusionProfile& profile, const ReferenceSettings& settings = {});
    // The same with the environment itself, which settings.environmentSamples > 0 traces (the
    // environment must outlive the reference).
    DiffusionReference(const Scene& scene, const std::vector<Light>& lights, const Environment& environment,
                       const DiffusionProfile& profile, const ReferenceSettings& settings = {});
    ~DiffusionReference();
    DiffusionReference(const DiffusionReference&) = delete;
    DiffusionReference& operator=(const DiffusionReference&) = delete;

    // Every pixel of one eye's image (pixel centres, like the rasterizer), times `exposure`.
    ReferenceImage render(const Eye& eye, uint32_t width, uint32_t height, float exposure = 1.0f,
                          const ReferenceProgress& progress = {}) const;
    // The first visible surface along a ray and its radiance towards the ray's origin (textures
    // at their finest level). Empty when the ray leaves the scene.
    std::optional<ReferenceSample> trace(const glm::dvec3& originWs, const glm::dvec3& directionWs) const;
    // The reach of the profile in profile mm (DiffusionProfile::reachMm of tailFraction).
    double reachMm() const;

    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

}  // namespace preskin
