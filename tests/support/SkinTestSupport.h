// Helpers for the skin shading tests (tests/reference/test_skin_*.cpp): analytic sphere hits per pixel
// for CPU references, synthetic environments, procedural normal maps, and image comparisons in
// 8-bit sRGB steps.
#pragma once

#include <preskin/DiffusionReference.h>
#include <preskin/Environment.h>
#include <preskin/LutSet.h>
#include <preskin/Renderer.h>
#include <preskin/Scene.h>
#include <preskin/View.h>

#include <glm/glm.hpp>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace preskin::test {

// The first hit of a pixel's ray with a sphere. `interior`: the rays through every corner of the
// pixel and of its eight neighbours hit the sphere too, so the pixel is fully covered and far
// from the silhouette.
struct SphereHit {
    bool interior = false;
    glm::dvec3 positionWs{0.0};
};

// One entry per pixel (row-major, top row first, as RenderedImage) of a width x height image of
// `view` (perspective or orthographic, Vulkan clip conventions of View.h).
std::vector<SphereHit> traceSphere(const View& view, uint32_t width, uint32_t height, const glm::dvec3& centerWs,
                                   double radiusM);

// An equirectangular environment (convention of Environment.h) of width x width/2 texels whose
// texel centres hold radiance(direction); written as EXR into a temporary folder, loaded with
// Environment::load and the folder removed. The loaded image (half-float rounded) is what both
// the GPU and CPU references see.
Environment makeEnvironment(uint32_t width, const std::function<glm::vec3(const glm::vec3&)>& radiance);

// Appends a tangent-space normal map (glTF: RGB = n * 0.5 + 0.5, +Y up) of width x height texels
// holding normalAt(uv) (uv at texel centres, any non-zero vector; normalised here) to the
// scene's images and returns its index.
int addNormalMap(Scene& scene, uint32_t width, uint32_t height, const std::function<glm::vec3(glm::vec2)>& normalAt);

// The diffusion reference at coarse settings (larger irradiance pieces, a looser profile
// quadrature), for tests whose assertions hold with a wide margin, at a fraction of the time.
inline ReferenceSettings coarseReferenceSettings() {
    ReferenceSettings coarse;
    coarse.leafRatio = 1.0;
    coarse.finestLeafRatio = 4.0;
    coarse.momentTolerance = 1e-5;
    return coarse;
}

// Per-vertex curvature of a primitive recomputed from its positions and normals
// (computeVertexCurvature), replacing whatever it held.
void recomputeCurvature(Primitive& primitive);

// Linear RGB of one pixel of a LinearFloat image.
glm::dvec3 pixelLinear(const RenderedImage& image, uint32_t x, uint32_t y);

// Largest per-channel difference between two values after sRGB encoding, in 8-bit steps.
double srgbDifference(const glm::dvec3& a, const glm::dvec3& b);

// Pixels of two LinearFloat images of one size whose sRGB difference exceeds `steps`.
size_t countDifferingPixels(const RenderedImage& a, const RenderedImage& b, double steps);
// The largest sRGB difference over all pixels, in 8-bit steps.
double maxSrgbDifference(const RenderedImage& a, const RenderedImage& b);

// Per-pixel agreement of a rendered sphere (radius radiusM at the origin, one directional
// light, no shadows or environment) with the CPU evaluation of the skin model.
struct SphereAgreement {
    size_t interior = 0;       // pixels fully covered by the sphere
    size_t within = 0;         // of those, within 2/255 of the skin reference
    size_t lambertWithin = 0;  // within 2/255 of the reference with Lambert in place of D
    double worst = 0.0;        // largest difference from the skin reference, 1/255 steps
};

// The diffuse LUT D(NoL, curvature in profile 1/mm), per channel.
using DiffuseLookup = std::function<glm::dvec3(double NoL, double curvaturePerMm)>;
DiffuseLookup lutDiffuse(const LutSet& luts);

// A directional light whose terminator crosses sphereView's image.
Light sphereLight();
// A square view of a sphere of radius radiusM at the origin, filling about half the image.
View sphereView(double radiusM);

// `image` (LinearFloat) against (1 - F) albedo / pi D(NoL, curvature) E + dual-lobe GGX specular
// with the skin parameters `skin` (F0 = 0.028 specularIntensity), albedo and roughness, at the
// analytic curvature 1 / radiusM, for every interior pixel.
SphereAgreement compareWithSkinReference(const RenderedImage& image, const View& view, double radiusM,
                                         const Light& light, const SkinMaterial& skin, const glm::dvec3& albedo,
                                         double roughness, const DiffuseLookup& diffuse);

// The straight cast-shadow edge of the penumbra and diffusion-method tests: a skin plane `planeM`
// wide in z = 0 (albedo 0.8, 0.6, 0.5), a dark plate 30 mm above it over x' below its edge, the
// shadow light `lightElevationDeg` above the plane (default 63.4: tilted 26.6 degrees across the
// edge), its approach turned `lightAzimuthDeg` from across the edge towards along it; the edge
// falls at x' = 0, x' being x turned 25 degrees about the plane's normal (with the plate, the
// light and the view), so the edge runs across the shadow map's texel rows, as edges in scenes
// do. Seen from 80 mm above: 12 mm across the edge in width x height pixels. A plate
// `casterWidthM` wide (less than the view) is a bar: its shadow a strip from x' = 0 towards -x'.
struct StraightEdgeScene {
    Scene scene;
    View view;
    uint32_t width = 128;
    uint32_t height = 8;
};
StraightEdgeScene straightEdgeScene(float planeM, float lightElevationDeg = 63.434949f, float lightAzimuthDeg = 0.0f,
                                    float casterWidthM = 0.6f);

// A skin plate's underside 1 mm over a lit skin floor (x from -40 to 0 mm over a floor 80 mm
// wide, 1 mm cells), the plate's other faces casting its shadow, one shadowed directional light
// 30 degrees above the floor from +x: the underside sees the lit floor across the gap (the
// opposing neighbours' light). Seen from below (z < 0) it shows the underside.
Scene overhangScene();

// Per column (rows averaged), the largest |render - truth| over the truth's lit level (the mean
// of its four rightmost columns: the edge's lit side), per channel.
// Each column's mean (rows averaged) of a width x height RGBA float image's red, green and blue.
std::vector<glm::dvec3> columnMeans(const std::vector<float>& rgba, uint32_t width, uint32_t height);
glm::dvec3 largestColumnDifference(const RenderedImage& render, const ReferenceImage& truth);

// A 40 mm skin sphere under sphereLight() (casting the shadow) rendered with `settings` as a
// stereo pair 96x96 per eye from 0.25 m, and each eye again as a mono frame: per eye the largest
// sRGB difference (1/255 steps), and the stereo frame's statistics.
struct StereoAgainstMono {
    double worst[2] = {0.0, 0.0};
    FrameStats stereoStats;
};
StereoAgainstMono stereoAgainstMono(Context& context, const RenderSettings& settings);

}  // namespace preskin::test
