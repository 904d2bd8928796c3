// Curvature maps (see <preskin/CurvatureBake.h>).
#include <preskin/CurvatureBake.h>

#include <preskin/Error.h>
#include <preskin/OutputFile.h>
#include <preskin/Scene.h>
#include <preskin/SkinParameters.h>

#include <fmt/core.h>
#include <nlohmann/json.hpp>
#include "image/PngFile.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace preskin {
namespace {

uint32_t mapSize(const Scene& scene, const Material& material, uint32_t requested) {
    if (requested != 0) return requested;
    uint32_t size = 0;
    auto consider = [&](int image) {
        if (image >= 0 && size_t(image) < scene.images.size())
            size = std::max({size, scene.images[size_t(image)].width, scene.images[size_t(image)].height});
    };
    for (const TextureRef* t :
         {&material.baseColor, &material.metallicRoughness, &material.normal, &material.occlusion, &material.emissive})
        consider(t->image);
    if (material.skin) {
        consider(material.skin->specularTexture.image);
        consider(material.skin->detailNormalTexture.image);
    }
    return size == 0 ? 1024u : std::min(size, 4096u);
}

// Accumulates one triangle's interpolated curvature into the texels whose centres it covers and
// adds the texels of its bounding box to `visited`. The layout repeats (UVs outside [0, 1) wrap):
// the triangle is placed by the tile of its lowest corner and each covered texel centre wrapped
// into the map, so a triangle reaching exactly 1.0 or crossing a tile's edge is baked whole.
// False (nothing done) for a triangle wider than the texture in UV: a layout that wraps within a
// triangle, or broken UVs.
bool rasterise(const glm::vec2 uv[3], const float value[3], uint32_t width, uint32_t height, std::vector<double>& sum,
               std::vector<uint32_t>& count, uint64_t& visited) {
    const glm::vec2 tile = glm::floor(glm::min(uv[0], glm::min(uv[1], uv[2])));
    glm::vec2 p[3];
    for (int i = 0; i < 3; ++i) p[i] = (uv[i] - tile) * glm::vec2(float(width), float(height));
    const float area = (p[1].x - p[0].x) * (p[2].y - p[0].y) - (p[2].x - p[0].x) * (p[1].y - p[0].y);
    const glm::vec2 lo = glm::min(p[0], glm::min(p[1], p[2])), hi = glm::max(p[0], glm::max(p[1], p[2]));
    if (!(hi.x - lo.x <= float(width)) || !(hi.y - lo.y <= float(height))) return false;
    if (!(std::abs(area) > 1e-12f)) return true;
    // Texel centres x + 0.5 in [lo, hi]: at most two tiles' worth, wrapped when written.
    const int x0 = int(std::floor(lo.x)), x1 = int(std::ceil(hi.x)) - 1;
    const int y0 = int(std::floor(lo.y)), y1 = int(std::ceil(hi.y)) - 1;
    if (x1 >= x0 && y1 >= y0) visited += uint64_t(x1 - x0 + 1) * uint64_t(y1 - y0 + 1);
    for (int y = y0; y <= y1; ++y) {
        for (int x = x0; x <= x1; ++x) {
            const glm::vec2 c(float(x) + 0.5f, float(y) + 0.5f);
            float w[3];
            for (int i = 0; i < 3; ++i) {
                const glm::vec2 a = p[(i + 1) % 3], b = p[(i + 2) % 3];
                w[i] = ((b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y)) / area;
            }
            if (w[0] < 0.0f || w[1] < 0.0f || w[2] < 0.0f) continue;
            const size_t i = size_t(y % int(height)) * width + size_t(x % int(width));
            sum[i] += double(w[0] * value[0] + w[1] * value[1] + w[2] * value[2]);
            ++count[i];
        }
    }
    return true;
}

// What the material's triangles hold in UV, over the meshes its instances draw (once each): the
// UV and surface areas of all of them (accumulateTexelDensity: the rule texture-space diffusion
// shares, hasUvLayout) and the UV area of those the bake rasterises (no wider than the map).
struct MaterialAreas {
    double uv = 0.0, surface = 0.0, bakeableUv = 0.0;
};

MaterialAreas materialAreas(const Scene& scene, int material) {
    MaterialAreas areas;
    std::vector<bool> meshDone(scene.meshes.size(), false);
    for (const MeshInstance& instance : scene.instances) {
        if (instance.mesh < 0 || size_t(instance.mesh) >= scene.meshes.size() || meshDone[size_t(instance.mesh)])
            continue;
        meshDone[size_t(instance.mesh)] = true;
        for (const Primitive& p : scene.meshes[size_t(instance.mesh)].primitives) {
            if (p.material != material) continue;
            accumulateTexelDensity(p, glm::mat4(1.0f), areas.uv, areas.surface);
            for (size_t t = 0; t + 2 < p.indices.size(); t += 3) {
                const glm::vec2 a = p.vertices[p.indices[t]].uv0, b = p.vertices[p.indices[t + 1]].uv0,
                                c = p.vertices[p.indices[t + 2]].uv0;
                const glm::vec2 extent = glm::max(a, glm::max(b, c)) - glm::min(a, glm::min(b, c));
                if (extent.x <= 1.0f && extent.y <= 1.0f)
                    areas.bakeableUv += 0.5 * std::abs(double((b - a).x * (c - a).y - (b - a).y * (c - a).x));
            }
        }
    }
    return areas;
}

}  // namespace

std::vector<uint16_t> CurvatureMap::encoded() const {
    std::vector<uint16_t> out(curvaturePerM.size(), 0);
    for (size_t i = 0; i < out.size(); ++i) {
        const float k = curvaturePerM[i];
        const float v = std::isnan(k) || !(scalePerM > 0.0f) ? bias : std::clamp(bias + k / scalePerM, 0.0f, 1.0f);
        out[i] = uint16_t(std::lround(v * 65535.0f));
    }
    return out;
}

std::vector<CurvatureMap> bakeCurvatureMaps(const Scene& scene, const CurvatureBakeSettings& settings) {
    if (settings.size != 0 && (settings.size < 16 || settings.size > 8192))
        throw Error(fmt::format("bake-curvature: size: must be in [16, 8192], got {}", settings.size));
    if (!(settings.rangeQuantile >= 0.5 && settings.rangeQuantile <= 1.0))
        throw Error(fmt::format("bake-curvature: range quantile: must be in [0.5, 1], got {}", settings.rangeQuantile));
    if (settings.dilationTexels < 0 || settings.dilationTexels > 1024)
        throw Error(fmt::format("bake-curvature: dilation: must be in [0, 1024], got {}", settings.dilationTexels));
    std::vector<CurvatureMap> maps;
    for (size_t m = 0; m < scene.materials.size(); ++m) {
        const Material& material = scene.materials[m];
        if (!material.skin) continue;
        // The layout, before any work: none at all, or charts stacked more than 64 deep.
        const MaterialAreas areas = materialAreas(scene, int(m));
        const std::string label = fmt::format("bake-curvature: materials[{}] ('{}')", m, material.name);
        if (areas.surface > 0.0 && !hasUvLayout(areas.uv))  // drawn, but flat in UV
            throw Error(label +
                        ": its triangles have no UV layout (no TEXCOORD_0, or every UV the same); "
                        "nothing baked");
        if (areas.bakeableUv > 64.0)
            throw Error(
                fmt::format("{}: its triangles cover the map {:.0f} times over in UV (more than 64: "
                            "charts stacked beyond any real layout); nothing baked",
                            label, areas.bakeableUv));
        CurvatureMap map;
        map.material = int(m);
        map.materialName = material.name;
        map.width = map.height = mapSize(scene, material, settings.size);
        const size_t texels = size_t(map.width) * map.height;
        std::vector<double> sum(texels, 0.0);
        std::vector<uint32_t> count(texels, 0);
        float firstScale = 0.0f;
        uint64_t visited = 0;
        const uint64_t budget = 64 * uint64_t(texels) + 100'000'000;
        std::vector<bool> meshDone(scene.meshes.size(), false);
        for (const MeshInstance& instance : scene.instances) {
            if (instance.mesh < 0 || size_t(instance.mesh) >= scene.meshes.size()) continue;
            const Mesh& mesh = scene.meshes[size_t(instance.mesh)];
            bool uses = false;
            for (const Primitive& p : mesh.primitives) uses = uses || p.material == int(m);
            if (!uses) continue;
            const float scale = instance.curvatureScale();
            if (firstScale == 0.0f) firstScale = scale;
            if (std::abs(scale - firstScale) > 1e-4f * firstScale) ++map.warnedInstances;
            if (meshDone[size_t(instance.mesh)]) continue;
            meshDone[size_t(instance.mesh)] = true;
            for (const Primitive& p : mesh.primitives) {
                if (p.material != int(m)) continue;
                for (size_t t = 0; t + 2 < p.indices.size(); t += 3) {
                    glm::vec2 uv[3];
                    float value[3];
                    for (int c = 0; c < 3; ++c) {
                        const Vertex& v = p.vertices[p.indices[t + size_t(c)]];
                        uv[c] = v.uv0;
                        value[c] = v.curvaturePerM / std::max(firstScale, 1e-12f);
                    }
                    if (!rasterise(uv, value, map.width, map.height, sum, count, visited)) ++map.skippedTriangles;
                    // Long thin triangles whose bounding boxes sweep the map over and over (the
                    // work would not end in time).
                    if (visited > budget)
                        throw Error(
                            fmt::format("{}: its triangles' bounds in UV sweep the {}x{} map more than 64 "
                                        "times over; nothing baked",
                                        label, map.width, map.height));
                }
            }
        }
        if (firstScale == 0.0f) continue;  // no instance draws the material
        map.curvaturePerM.assign(texels, std::numeric_limits<float>::quiet_NaN());
        map.covered.assign(texels, 0);
        std::vector<float> magnitudes;
        for (size_t i = 0; i < texels; ++i) {
            if (count[i] == 0) continue;
            map.curvaturePerM[i] = float(sum[i] / count[i]);
            map.covered[i] = 1;
            magnitudes.push_back(std::abs(map.curvaturePerM[i]));
        }
        if (magnitudes.empty())
            throw Error(
                fmt::format("{}: its triangles cover no texel centre of the {}x{} map ({} wider than the map "
                            "in UV); nothing baked",
                            label, map.width, map.height, map.skippedTriangles));
        // Dilation: ring by ring, each empty texel next to filled ones takes their mean.
        const int w = int(map.width), h = int(map.height);
        for (int pass = 0; pass < settings.dilationTexels; ++pass) {
            std::vector<std::pair<size_t, float>> fills;
            for (int y = 0; y < h; ++y) {
                for (int x = 0; x < w; ++x) {
                    const size_t i = size_t(y) * size_t(w) + size_t(x);
                    if (map.covered[i] != 0) continue;
                    double s = 0.0;
                    int n = 0;
                    for (int dy = -1; dy <= 1; ++dy)
                        for (int dx = -1; dx <= 1; ++dx) {
                            const int nx = x + dx, ny = y + dy;
                            if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
                            const size_t j = size_t(ny) * size_t(w) + size_t(nx);
                            if (map.covered[j] == 0) continue;
                            s += double(map.curvaturePerM[j]);
                            ++n;
                        }
                    if (n > 0) fills.emplace_back(i, float(s / n));
                }
            }
            if (fills.empty()) break;
            for (const auto& [i, value] : fills) {
                map.curvaturePerM[i] = value;
                map.covered[i] = 2;
            }
        }
        float largest = 0.0f;
        if (!magnitudes.empty()) {
            const size_t k =
                std::min(magnitudes.size() - 1, size_t(double(magnitudes.size()) * settings.rangeQuantile));
            std::nth_element(magnitudes.begin(), magnitudes.begin() + std::ptrdiff_t(k), magnitudes.end());
            largest = magnitudes[k];
        }
        map.scalePerM = largest > 0.0f ? 2.0f * largest : 1.0f;
        maps.push_back(std::move(map));
    }
    return maps;
}

void writeCurvatureMap(const CurvatureMap& map, const std::filesystem::path& png) {
    std::filesystem::path jsonPath = png;
    jsonPath.replace_extension(".json");
    checkOutputFile(png);
    checkOutputFile(jsonPath);
    PixelImage image;
    image.width = map.width;
    image.height = map.height;
    image.channels = 1;
    image.texels = map.encoded();
    writeOutputFile(png, [&](const std::filesystem::path& temporary) {
        try {
            image::encodePng(temporary, image);
        } catch (const std::exception& e) {
            throw Error(fmt::format("{}: cannot write: {}", png.string(), e.what()));
        }
    });
    size_t covered = 0;
    for (uint8_t c : map.covered) covered += c == 1;
    nlohmann::ordered_json j;
    j["material"] = map.materialName;
    j["materialIndex"] = map.material;
    j["image"] = png.filename().string();
    j["width"] = map.width;
    j["height"] = map.height;
    j["coveredFraction"] = map.covered.empty() ? 0.0 : double(covered) / double(map.covered.size());
    j["PRESKIN_materials_skin"] = {{"curvatureSource", "texture"},
                                   {"curvatureTextureScalePerM", map.scalePerM},
                                   {"curvatureTextureBias", map.bias}};
    writeTextFile(jsonPath, j.dump(2) + "\n");
}

}  // namespace preskin
