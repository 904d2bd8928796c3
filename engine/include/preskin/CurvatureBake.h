// Curvature maps: the signed mean curvature of each skin material's surface baked into its UV
// space, for CurvatureSource::Texture (`preskin bake-curvature`). Pre-integrated skin read from a
// texture sees curvature at the texture's resolution, independent of the mesh it is drawn with
// (levels of detail, decimated meshes) and smooth across triangles.
//
// Method: every triangle of the material's primitives is rasterised in TEXCOORD_0 space (texel
// centres inside the triangle, texels where UV charts overlap averaged), the mesh's per-vertex
// signed mean curvature (<preskin/Curvature.h>, from the smooth vertex normals) interpolated
// barycentrically and converted to world units with the first instance's scale. Texels no
// triangle covers are then filled outwards from the charts for `dilationTexels` rings (each empty
// texel takes the mean of its filled 8-neighbours), so bilinear filtering and mip levels near UV
// seams read the chart's own values, not the background.
// Encoding: value = bias + curvature / scale with bias 0.5 (signed) and scale twice the largest
// |curvature| of the covered texels (or a quantile of it: rangeQuantile; beyond it values clamp),
// stored in 16 bits; the renderer decodes (value - bias) * scale
// (SkinMaterial::curvatureTextureBias, curvatureTextureScalePerM).
// Limits: the normal map's detail is not included (the map is the smooth surface's curvature);
// UVs outside [0, 1) are wrapped; a mesh drawn at several scales gets the first instance's; the
// map holds the rest pose, so on skinned or morphed meshes it does not follow the deformation
// (per-vertex curvature, recomputed every frame, does).
#pragma once

#include <preskin/Export.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace preskin {

struct Scene;

struct CurvatureMap {
    int material = -1;  // Scene::materials index
    std::string materialName;
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<float> curvaturePerM;  // width * height, rows top (v = 0) down; NaN where nothing was covered
    std::vector<uint8_t> covered;      // 1 where a triangle covered the texel, 2 where dilation filled it
    float scalePerM = 0.0f;            // the encoding's scale (curvatureTextureScalePerM)
    float bias = 0.5f;                 // the encoding's zero (curvatureTextureBias)
    int warnedInstances = 0;           // instances of another scale than the first (their curvature differs)
    int skippedTriangles = 0;          // triangles wider than the texture in UV (not baked)

    // The 16-bit texel values of the encoding; texels nothing covered or filled read as flat (the bias),
    // so coarse mip levels that reach them see no false curvature.
    std::vector<uint16_t> encoded() const;
};

struct CurvatureBakeSettings {
    uint32_t size = 0;  // width and height; 0: the largest texture the material has (1024 without any), at most 4096
    int dilationTexels = 16;  // rings filled around the charts
    // The quantile of |curvature| over the covered texels that the encoding's range reaches
    // (scale = twice it); texels beyond clamp. 1 (the default): the largest, nothing clamps;
    // scenes load 16-bit PNGs at 16 bits, so the range costs no precision that matters (the
    // head's full range, 6456 / m, steps by 0.1 / m). Smaller values suit maps that will be
    // stored at 8 bits.
    double rangeQuantile = 1.0;
};

// One map per skin material that some mesh instance draws. Throws preskin::Error, baking nothing,
// for a size out of [16, 8192] (0: the default above), and for a material whose triangles have no
// UV layout (no TEXCOORD_0, or every UV the same: the rule texture-space diffusion shares,
// hasUvLayout in <preskin/SkinParameters.h>), cover the map more than 64 times over (their summed
// UV area; no real layout does), or cover no texel centre at all.
PRESKIN_API std::vector<CurvatureMap> bakeCurvatureMaps(const Scene& scene, const CurvatureBakeSettings& settings = {});

// Writes the map as a one-channel 16-bit PNG at `png` and, beside it with the extension .json,
// its encoding and the PRESKIN_materials_skin fields that read it:
//   {"material": ..., "image": "<file name>", "width": w, "height": h, "coveredFraction": f,
//    "PRESKIN_materials_skin": {"curvatureSource": "texture", "curvatureTextureScalePerM": s,
//                               "curvatureTextureBias": 0.5}}
// (the curvatureTexture's index is the glTF texture the image becomes). Each file is written under
// the rule of <preskin/OutputFile.h>. (Scenes load 16-bit PNGs at 16 bits: a step of scale / 65535;
// a copy converted to 8 bits steps by scale / 255.)
PRESKIN_API void writeCurvatureMap(const CurvatureMap& map, const std::filesystem::path& png);

}  // namespace preskin
