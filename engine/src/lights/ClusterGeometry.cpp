// The grid's shape (tiles, logarithmic slices fitted to the scene's depth range) and its view-space
// geometry; see ClusterGeometry.h and <preskin/ClusterGrid.h>.
#include "lights/ClusterGeometry.h"

#include "lights/ClusterAssign.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace preskin {

namespace {

// Normalised device depth of view depth d (> 0) for this projection.
double ndcDepth(const glm::dmat4& clipFromView, double viewDepthM) {
    const glm::dvec4 clip = clipFromView * glm::dvec4(0.0, 0.0, -viewDepthM, 1.0);
    return clip.z / clip.w;
}

struct Unprojector {
    glm::dmat4 clipFromView;
    glm::dmat4 viewFromClip;
    glm::dvec2 extent;

    // View-space point at pixel position (px, py) (pixel edges at integers) and view depth d.
    glm::dvec3 point(double px, double py, double viewDepthM) const {
        const glm::dvec4 ndc(px / extent.x * 2.0 - 1.0, py / extent.y * 2.0 - 1.0, ndcDepth(clipFromView, viewDepthM),
                             1.0);
        const glm::dvec4 p = viewFromClip * ndc;
        return glm::dvec3(p) / p.w;
    }
};

// Plane through a, b, c, oriented so that `higher` lies on its positive side.
glm::vec4 orientedPlane(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& higher) {
    glm::dvec3 n = glm::cross(b - a, c - a);
    const double len = glm::length(n);
    n = len > 0.0 ? n / len : glm::dvec3(1.0, 0.0, 0.0);
    double w = -glm::dot(n, a);
    if (glm::dot(n, higher) + w < 0.0) {
        n = -n;
        w = -w;
    }
    return glm::vec4(glm::vec3(n), float(w));
}

// The automatic tile (ClusterSettings::tileSizePx = 0): the largest of 16, 8 and 4 pixels that the
// median local light's bounding sphere spans kAutoTileRadiusTiles times in radius, projected at
// its view depth (clamped to the slices' fitted range, where the surfaces it lights are). A light
// is listed for every pixel of each tile it touches anywhere, so tiles small against the lights
// keep the lists near the exact count. At most kAutoTileSamples lights, evenly strided, are
// measured; lights whose sphere misses shape.lightBounds (listed nowhere) are not.
constexpr float kAutoTileRadiusTiles = 8.0f;
constexpr size_t kAutoTileSamples = 4096;
// Finer tiles than 16 px take at most kAutoFineSlices slices (the surfaces bound each froxel's
// depths, so slices matter less than tiles) and at most kAutoMaxFroxels froxels (the grid's memory
// and build time; a larger image gets larger tiles).
constexpr uint32_t kAutoFineSlices = 16;
constexpr uint64_t kAutoMaxFroxels = uint64_t(1) << 20;

uint32_t autoTileSizePx(const ClusterGridShape& s, const Eye& view, std::span<const ClusterLight> lights) {
    const float pixelsPerTangent = 0.5f * float(s.extentPx.y) * std::abs(view.clipFromView[1][1]);
    const bool perspective = view.clipFromView[2][3] != 0.0f;
    const size_t stride = std::max<size_t>(1, (lights.size() + kAutoTileSamples - 1) / kAutoTileSamples);
    std::vector<float> radiiPx;
    radiiPx.reserve(std::min(lights.size(), kAutoTileSamples));
    for (size_t i = 0; i < lights.size(); i += stride) {
        const glm::vec4 sphere = clusterLightSphereWs(lights[i]);
        const glm::vec3 center(sphere);
        const float radius = sphere.w;
        if (std::isinf(radius)) {
            radiiPx.push_back(radius);
            continue;
        }
        if (!s.lightBounds.empty() && !sphereReachesBox(s.lightBounds, center, radius)) continue;
        const float depth = std::clamp(-(view.viewFromWorld * glm::vec4(center, 1.0f)).z, s.logStartM, s.logEndM);
        const float radiusPx = radius * pixelsPerTangent / (perspective ? depth : 1.0f);
        if (!std::isnan(radiusPx)) radiiPx.push_back(radiusPx);  // a light at a NaN position lights nothing
    }
    uint32_t tile = 16;
    if (radiiPx.empty()) return tile;
    const auto median = radiiPx.begin() + std::ptrdiff_t(radiiPx.size() / 2);
    std::nth_element(radiiPx.begin(), median, radiiPx.end());
    while (tile > 4 && !(*median >= kAutoTileRadiusTiles * float(tile))) tile /= 2;
    return tile;
}

}  // namespace

ClusterGridShape clusterGridShape(const ClusterSettings& settings, const ClusterCamera& camera,
                                  const Bounds& sceneBounds, std::span<const Light> lights) {
    // The local lights as the grid bounds them (only the automatic tile reads them).
    std::vector<ClusterLight> local;
    if (settings.tileSizePx == 0)
        for (const Light& light : lights)
            if (light.type != LightType::Directional) local.push_back(clusterLight(light, 0));
    return clusterGridShape(settings, camera, sceneBounds, std::span<const ClusterLight>(local));
}

ClusterGridShape clusterGridShape(const ClusterSettings& settings, const ClusterCamera& camera,
                                  const Bounds& sceneBounds, std::span<const ClusterLight> lights) {
    const Eye& view = camera.eye;
    ClusterGridShape s;
    s.extentPx = glm::max(camera.extentPx, glm::uvec2(1u));
    s.dims.z = std::clamp<uint32_t>(settings.depthSlices, 2, 256);
    s.nearM = std::isfinite(view.nearM) && view.nearM > 0.0f ? view.nearM : 1e-3f;
    const float farM = std::isfinite(view.farM) ? std::max(view.farM, s.nearM * 4.0f) : s.nearM * 1e6f;
    float start = std::isfinite(settings.nearSliceM) ? settings.nearSliceM : 0.0f;
    start = std::max(start, s.nearM * 1.001f);
    float end = farM;
    if (settings.fitDepthToScene && !sceneBounds.empty()) {
        float minDepth = std::numeric_limits<float>::max();
        float maxDepth = -std::numeric_limits<float>::max();
        for (int i = 0; i < 8; ++i) {
            const glm::vec3 corner((i & 1) ? sceneBounds.max.x : sceneBounds.min.x,
                                   (i & 2) ? sceneBounds.max.y : sceneBounds.min.y,
                                   (i & 4) ? sceneBounds.max.z : sceneBounds.min.z);
            const float depth = -(view.viewFromWorld * glm::vec4(corner, 1.0f)).z;
            minDepth = std::min(minDepth, depth);
            maxDepth = std::max(maxDepth, depth);
        }
        start = std::max(start, minDepth);
        end = std::min(end, maxDepth);
        s.lightBounds = sceneBounds;
    }
    end = std::max(end, start * 1.01f);
    s.logStartM = start;
    s.logEndM = end;
    auto tiles = [&](uint32_t tile) {
        return glm::uvec2((s.extentPx.x + tile - 1) / tile, (s.extentPx.y + tile - 1) / tile);
    };
    s.tileSizePx = std::clamp<uint32_t>(settings.tileSizePx, 4, 256);
    if (settings.tileSizePx == 0) {
        const uint32_t fineSlices = std::min(s.dims.z, kAutoFineSlices);
        uint32_t tile = autoTileSizePx(s, view, lights);
        while (tile < 16 && uint64_t(tiles(tile).x) * tiles(tile).y * fineSlices > kAutoMaxFroxels) tile *= 2;
        s.tileSizePx = tile;
        if (tile < 16) s.dims.z = fineSlices;
    }
    s.dims.x = tiles(s.tileSizePx).x;
    s.dims.y = tiles(s.tileSizePx).y;
    s.sliceScale = float(s.dims.z - 1) / std::log2(end / start);
    s.sliceBias = 1.0f - std::log2(start) * s.sliceScale;
    return s;
}

bool ClusterGeometry::sphereTiles(int axis, const glm::vec3& center, float radius, uint32_t& lo, uint32_t& hi) const {
    const glm::dmat4& p = clipFromView;
    // The projection's terms for this axis: scale, the other axis's, depth's and the constant.
    const glm::dvec4 row =
        axis == 0 ? glm::dvec4(p[0][0], p[1][0], p[2][0], p[3][0]) : glm::dvec4(p[1][1], p[0][1], p[2][1], p[3][1]);
    // The usual form: no x-y mixing, w = -z (perspective) or 1.
    const bool perspective = p[2][3] == -1.0 && p[3][3] == 0.0;
    const bool orthographic = p[2][3] == 0.0 && p[3][3] == 1.0;
    if (row.y != 0.0 || p[0][3] != 0.0 || p[1][3] != 0.0 || !(perspective || orthographic) || !std::isfinite(radius))
        return false;
    const double c = axis == 0 ? double(center.x) : double(center.y);
    const double r = radius;
    double ndc0 = 0.0;
    double ndc1 = 0.0;
    if (orthographic) {
        ndc0 = row.x * (c - r) + row.z * double(center.z) + row.w;
        ndc1 = row.x * (c + r) + row.z * double(center.z) + row.w;
    } else {
        if (row.w != 0.0) return false;
        const double depth = -double(center.z);
        const double d2 = c * c + depth * depth;
        if (!(depth > r * 1.001) || !(d2 > r * r)) return false;  // reaches the eye's plane
        // Slopes a / depth of the two tangent lines from the eye in the (axis, depth) plane.
        const double root = r * std::sqrt(d2 - r * r);
        const double denominator = depth * depth - r * r;
        const double t0 = (c * depth - root) / denominator;
        const double t1 = (c * depth + root) / denominator;
        // ndc = (scale a + depth term z) / -z = scale t - depth term
        ndc0 = row.x * t0 - row.z;
        ndc1 = row.x * t1 - row.z;
    }
    const double tilesPerNdc = 0.5 * double(axis == 0 ? shape.extentPx.x : shape.extentPx.y) / double(shape.tileSizePx);
    const double count = double(axis == 0 ? shape.dims.x : shape.dims.y);
    const double a = (std::min(ndc0, ndc1) + 1.0) * tilesPerNdc - 1.0;
    const double b = (std::max(ndc0, ndc1) + 1.0) * tilesPerNdc + 1.0;
    if (!(a <= b) || b < 0.0 || a >= count) {  // NaN, or wholly outside: an empty range
        lo = 1;
        hi = 0;
        return std::isfinite(a) && std::isfinite(b);
    }
    lo = static_cast<uint32_t>(std::clamp(std::floor(a), 0.0, count - 1.0));
    hi = static_cast<uint32_t>(std::clamp(std::floor(b), 0.0, count - 1.0));
    return true;
}

ClusterGeometry clusterGeometry(const ClusterGridShape& shape, const Eye& view) {
    ClusterGeometry g;
    clusterGeometry(shape, view, g);
    return g;
}

void clusterGeometry(const ClusterGridShape& shape, const Eye& view, ClusterGeometry& g) {
    g.shape = shape;
    g.clipFromView = glm::dmat4(view.clipFromView);
    const glm::uvec3 dims = shape.dims;
    Unprojector u{glm::dmat4(view.clipFromView), glm::inverse(glm::dmat4(view.clipFromView)),
                  glm::dvec2(shape.extentPx)};
    const double d1 = shape.logStartM;
    const double d2 = shape.logEndM;
    const double width = shape.extentPx.x;
    const double height = shape.extentPx.y;
    auto edgeX = [&](uint32_t i) { return std::min(double(i) * shape.tileSizePx, width); };
    auto edgeY = [&](uint32_t j) { return std::min(double(j) * shape.tileSizePx, height); };

    g.xPlanes.resize(dims.x + 1);
    for (uint32_t i = 0; i <= dims.x; ++i) {
        const double x = edgeX(i);
        // A point of the neighbouring column on the higher side (or the lower side for the last).
        const double probe = i < dims.x ? x + 0.5 : x - 0.5;
        glm::vec4 plane = orientedPlane(u.point(x, 0.0, d1), u.point(x, 0.0, d2), u.point(x, height, d1),
                                        u.point(probe, 0.5 * height, d1));
        if (i == dims.x) plane = -plane;
        g.xPlanes[i] = plane;
    }
    g.yPlanes.resize(dims.y + 1);
    for (uint32_t j = 0; j <= dims.y; ++j) {
        const double y = edgeY(j);
        const double probe = j < dims.y ? y + 0.5 : y - 0.5;
        glm::vec4 plane = orientedPlane(u.point(0.0, y, d1), u.point(0.0, y, d2), u.point(width, y, d1),
                                        u.point(0.5 * width, probe, d1));
        if (j == dims.y) plane = -plane;
        g.yPlanes[j] = plane;
    }
    g.sliceStartM.resize(dims.z + 1);
    for (uint32_t z = 0; z <= dims.z; ++z) g.sliceStartM[z] = shape.sliceStartM(z);

    // Corner lines: the unprojection is linear in the corner's NDC x and y at a fixed depth, so
    // each column's and row's share of it is computed once.
    g.cornerOrigin.resize(size_t(dims.x + 1) * (dims.y + 1));
    g.cornerDir.resize(g.cornerOrigin.size());
    const glm::dmat4& m = u.viewFromClip;
    std::vector<glm::dvec4> columns(dims.x + 1);
    for (uint32_t i = 0; i <= dims.x; ++i) columns[i] = m[0] * (edgeX(i) / width * 2.0 - 1.0);
    const glm::dvec4 near = m[2] * ndcDepth(u.clipFromView, d1) + m[3];
    const glm::dvec4 far = m[2] * ndcDepth(u.clipFromView, d2) + m[3];
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, dims.y + 1, 16), [&](const tbb::blocked_range<uint32_t>& r) {
        for (uint32_t j = r.begin(); j < r.end(); ++j) {
            const glm::dvec4 row = m[1] * (edgeY(j) / height * 2.0 - 1.0);
            for (uint32_t i = 0; i <= dims.x; ++i) {
                const glm::dvec4 pa = columns[i] + row + near;
                const glm::dvec4 pb = columns[i] + row + far;
                const glm::dvec3 a = glm::dvec3(pa) / pa.w;
                const glm::dvec3 dir = (glm::dvec3(pb) / pb.w - a) / (d2 - d1);
                g.cornerOrigin[g.cornerIndex(i, j)] = glm::vec4(glm::vec3(a - dir * d1), 0.0f);
                g.cornerDir[g.cornerIndex(i, j)] = glm::vec4(glm::vec3(dir), 0.0f);
            }
        }
    });
}

}  // namespace preskin
