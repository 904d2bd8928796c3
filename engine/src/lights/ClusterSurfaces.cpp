// Where the frame's surfaces are in each froxel; the method is in ClusterSurfaces.h.
#include "lights/ClusterSurfaces.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>

namespace preskin {

namespace {

// The rasterizer snaps vertices to sub-pixels (8 bits or more) and the shader's tile lookup
// rounds: a fragment may lie this far (pixels) outside its triangle and its tile besides
// ClusterSurfaces::outsidePx.
constexpr double kSnapPx = 1.0 / 64.0;
// Without MSAA, an edge-on triangle's extents grow by this fraction of themselves.
constexpr double kEdgeOnGrowth = 0.05;
constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr float kFar = 3.0e38f;
constexpr uint32_t kNone = ~0u;                          // an empty span: (kNone, kNone)
constexpr size_t kBinChunk = 4096;                       // triangles binned by one task
const glm::vec4 kEmptyExtent(kFar, -kFar, kFar, -kFar);  // no surface: min > max

// One corner of a clipped triangle: view-space point and its cluster coordinates (clip x,
// clip y, view depth, clip w).
struct Corner {
    glm::dvec3 view;
    glm::dvec4 h;
};

glm::dvec4 clusterCoordinates(const glm::dmat4& clipFromView, const glm::dvec3& view) {
    const glm::dvec4 clip = clipFromView * glm::dvec4(view, 1.0);
    return {clip.x, clip.y, -view.z, clip.w};
}

// An affine function of the tile coordinates, value = x * g.x + y * g.y + g.z.
struct Affine {
    glm::dvec3 g{0.0};
    double at(const glm::dvec2& p) const { return g.x * p.x + g.y * p.y + g.z; }
};

// The convex polygon t[0..n) clipped to the strip lo <= p[axis] <= hi (Sutherland-Hodgman; a side
// that every corner is inside of is skipped): its corner count (0: nothing inside), corners in
// `out` (at most n + 2 of them; n <= 6).
int clipToStrip(const glm::dvec2* t, int n, int axis, double lo, double hi, std::array<glm::dvec2, 8>& out) {
    std::array<glm::dvec2, 8> other;
    const glm::dvec2* from = t;
    glm::dvec2* to = other.data();
    int count = n;
    for (int side = 0; side < 2 && count > 0; ++side) {
        const double bound = side == 0 ? lo : hi;
        const double sign = side == 0 ? 1.0 : -1.0;  // inside: sign * (p[axis] - bound) >= 0
        bool allInside = true;
        for (int i = 0; i < count && allInside; ++i) allInside = sign * (from[i][axis] - bound) >= 0.0;
        if (allInside) continue;
        int kept = 0;
        for (int i = 0; i < count; ++i) {
            const glm::dvec2& p = from[i];
            const glm::dvec2& q = from[i + 1 == count ? 0 : i + 1];
            const double dp = sign * (p[axis] - bound);
            const double dq = sign * (q[axis] - bound);
            if (dp >= 0.0 && kept < 8) to[kept++] = p;
            if ((dp >= 0.0) != (dq >= 0.0) && kept < 8) to[kept++] = p + (q - p) * (dp / (dp - dq));
        }
        count = kept;
        from = to;
        to = to == other.data() ? out.data() : other.data();
    }
    if (from != out.data()) std::copy(from, from + count, out.data());
    return count;
}

// One band of tile rows, one triangle at a time. Pass 0 sums area-weighted normals into the
// tiles' axes; pass 1 (after the axes are normalised) writes the froxels' extents.
class SurfaceWriter {
public:
    SurfaceWriter(const ClusterGridShape& shape, std::span<const float> sliceStarts, const Eye& eye, double outsidePx,
                  int pass, uint32_t rowBegin, uint32_t rowEnd, FroxelSurfaces& out)
        : shape_(shape),
          sliceStarts_(sliceStarts),
          rowBegin_(rowBegin),
          rowEnd_(rowEnd),
          clipFromView_(eye.clipFromView),
          orthographic_(eye.orthographic()),
          pass_(pass),
          out_(out) {
        tilesPerNdc_ = 0.5 * glm::dvec2(shape.extentPx) / double(shape.tileSizePx);
        outside_ = (std::max(outsidePx, 0.0) + kSnapPx) / double(shape.tileSizePx);
        edgeOnAnywhere_ = outsidePx > 0.0;
        clipDepth_ = 0.5 * double(shape.nearM);  // perspective fragments lie beyond the near plane
    }

    // One triangle from its corners (Corner: view-space point and cluster coordinates).
    void triangle(const Corner& a, const Corner& b, const Corner& c) {
        const std::array<const Corner*, 3> v{&a, &b, &c};
        const glm::dvec3 cross = glm::cross(b.view - a.view, c.view - a.view);
        const double twiceArea = glm::length(cross);
        if (!(twiceArea > 0.0)) return;  // no area: never rasterized
        normal_ = cross / twiceArea;
        // Towards the camera: surfaces seen from either side share a tile's axis.
        const double facing = orthographic_ ? normal_.z : -glm::dot(normal_, a.view);
        if (facing < 0.0) normal_ = -normal_;
        area_ = 0.5 * twiceArea;
        std::array<Corner, 4> clipped;
        int n = 0;
        for (int i = 0; i < 3; ++i) {
            const Corner& p = *v[size_t(i)];
            const Corner& q = *v[size_t((i + 1) % 3)];
            // Clip to view depth >= clipDepth_ (perspective; orthographic keeps every depth).
            const bool pIn = orthographic_ || -p.view.z >= clipDepth_;
            const bool qIn = orthographic_ || -q.view.z >= clipDepth_;
            if (pIn) clipped[size_t(n++)] = p;
            if (pIn != qIn)
                clipped[size_t(n++)] =
                    corner(p.view + (q.view - p.view) * ((-clipDepth_ - p.view.z) / (q.view.z - p.view.z)));
        }
        if (n >= 3) polygon(clipped.data(), n);
    }

    Corner corner(const glm::dvec3& view) const { return {view, clusterCoordinates(clipFromView_, view)}; }

private:
    // A convex planar polygon of n (3 or 4) corners, all with w > 0.
    void polygon(const Corner* v, int n) {
        std::array<glm::dvec2, 8> t;  // corners in tile units
        glm::dvec2 lo(kInfinity);
        glm::dvec2 hi(-kInfinity);
        for (int i = 0; i < n; ++i) {
            t[size_t(i)] = (glm::dvec2(v[i].h) / v[i].h.w + 1.0) * tilesPerNdc_;
            lo = glm::min(lo, t[size_t(i)]);
            hi = glm::max(hi, t[size_t(i)]);
        }
        lo -= 2.0 * outside_;
        hi += 2.0 * outside_;
        const glm::dvec2 dims(shape_.dims);
        if (!(hi.x >= 0.0 && hi.y >= 0.0 && lo.x <= dims.x && lo.y <= dims.y)) return;  // off the grid (or NaN)
        const auto tile = [](double x, double count) {
            return static_cast<uint32_t>(std::clamp(std::floor(x), 0.0, count - 1.0));
        };
        const uint32_t x0 = tile(lo.x, dims.x), x1 = tile(hi.x, dims.x);
        const uint32_t y0 = std::max(tile(lo.y, dims.y), rowBegin_);
        const uint32_t y1 = std::min(tile(hi.y, dims.y), rowEnd_ - 1);
        if (rowBegin_ >= rowEnd_ || y0 > y1) return;

        if (pass_ == 0) {  // the tiles' axes: every tile of the box
            const glm::vec4 weighted(glm::vec3(normal_ * area_), 0.0f);
            for (uint32_t ty = y0; ty <= y1; ++ty)
                for (uint32_t tx = x0; tx <= x1; ++tx)
                    out_.values[out_.froxels() + ty * shape_.dims.x + tx] += weighted;
            return;
        }

        // Over w: view x, y, z and 1 as affine functions of the tile coordinates, from three corners.
        const glm::dvec2 e1 = t[1] - t[0];
        const glm::dvec2 e2 = t[2] - t[0];
        const double det = e1.x * e2.y - e1.y * e2.x;
        const double size = std::max(glm::length(e1), glm::length(e2));
        bool exact = std::abs(det) > 1e-9 * std::max(size * size, 1e-30);
        std::array<Affine, 4> over;  // view x / w, y / w, z / w, 1 / w
        double widen = 0.0;          // how far (m) the plane's points move within outside_ of the polygon
        if (exact) {
            for (int k = 0; k < 4; ++k) {
                const auto value = [&](int i) { return (k < 3 ? v[i].view[k] : 1.0) / v[i].h.w; };
                const double f0 = value(0), f1 = value(1), f2 = value(2);
                const double gx = ((f1 - f0) * e2.y - (f2 - f0) * e1.y) / det;
                const double gy = ((f2 - f0) * e1.x - (f1 - f0) * e2.x) / det;
                over[size_t(k)].g = glm::dvec3(gx, gy, f0 - gx * t[0].x - gy * t[0].y);
            }
            // p = Q / B (Q = view point over w, B = 1 / w): dp/dx = (Q_x B - Q B_x) / B^2. The
            // numerator is affine, so its norm is largest at a corner of the polygon grown by
            // outside_ (at most a corner's plus outside_ times its own rate); B is smallest there.
            const glm::dvec3 qx(over[0].g.x, over[1].g.x, over[2].g.x);
            const glm::dvec3 qy(over[0].g.y, over[1].g.y, over[2].g.y);
            const double bx = over[3].g.x;
            const double by = over[3].g.y;
            const double bRate = std::sqrt(bx * bx + by * by);
            double numerator = 0.0;
            double bMin = kInfinity;
            for (int i = 0; i < n; ++i) {
                const glm::dvec2& p = t[size_t(i)];
                const double b = over[3].at(p);
                const glm::dvec3 q(over[0].at(p), over[1].at(p), over[2].at(p));
                numerator = std::max(
                    numerator,
                    std::sqrt(glm::dot(qx * b - q * bx, qx * b - q * bx) + glm::dot(qy * b - q * by, qy * b - q * by)));
                bMin = std::min(bMin, b);
            }
            // The numerator's own rate: d/dx of (Q_x B - Q B_x) is 0 and d/dy is Q_x B_y - Q_y B_x,
            // likewise for the other column, so its norm changes by at most
            // sqrt(2) (|Q_x| + |Q_y|) |grad B| per tile.
            const double numeratorRate = std::sqrt(2.0) * (glm::length(qx) + glm::length(qy)) * bRate;
            bMin -= bRate * outside_;
            exact = bMin > 0.0 && std::isfinite(numerator);
            if (exact) widen = (numerator + numeratorRate * outside_) / (bMin * bMin) * outside_;
            exact = exact && std::isfinite(widen);
        }
        std::array<glm::dvec3, 8> points;
        std::array<glm::dvec2, 8> row;   // the polygon's part within outside_ of a row of tiles
        std::array<glm::dvec2, 8> part;  // and of one tile of it
        for (uint32_t ty = y0; ty <= y1; ++ty) {
            const int rowCount = clipToStrip(t.data(), n, 1, double(ty) - outside_, double(ty + 1) + outside_, row);
            if (rowCount == 0) continue;
            double left = kInfinity, right = -kInfinity;
            for (int i = 0; i < rowCount; ++i) {
                left = std::min(left, row[size_t(i)].x);
                right = std::max(right, row[size_t(i)].x);
            }
            // Tiles whose grown columns [tx - outside_, tx + 1 + outside_] meet [left, right].
            const uint32_t first = std::max(x0, tile(left - 1.0 - outside_, dims.x));
            const uint32_t last = std::min(x1, tile(right + outside_, dims.x));
            for (uint32_t tx = first; tx <= last; ++tx) {
                const int m =
                    clipToStrip(row.data(), rowCount, 0, double(tx) - outside_, double(tx + 1) + outside_, part);
                if (m == 0) continue;
                if (exact) {
                    for (int i = 0; i < m; ++i) {
                        const glm::dvec2& q = part[size_t(i)];
                        points[size_t(i)] = glm::dvec3(over[0].at(q), over[1].at(q), over[2].at(q)) / over[3].at(q);
                    }
                    mark(tx, ty, std::span<const glm::dvec3>(points.data(), size_t(m)), widen, 0.0);
                } else if (!edgeOnAnywhere_) {
                    for (int i = 0; i < n; ++i) points[size_t(i)] = v[i].view;
                    mark(tx, ty, std::span<const glm::dvec3>(points.data(), size_t(n)), 0.0, kEdgeOnGrowth);
                } else {
                    mark(tx, ty, std::span<const glm::dvec3>(), 0.0, 0.0);
                }
            }
        }
    }

    // The plane's points over one tile (view space), or none for "anywhere"; the extents they span
    // grow by `widen` (m) and by `growth` times their size.
    void mark(uint32_t tx, uint32_t ty, std::span<const glm::dvec3> points, double widen, double growth) {
        const glm::vec4& axisValue = out_.values[out_.froxels() + ty * shape_.dims.x + tx];
        const bool slab = axisValue.w > 0.0f;
        const glm::dvec3 axis(axisValue);
        double dLo = 0.0, dHi = kInfinity, sLo = -kInfinity, sHi = kInfinity;
        if (!points.empty()) {
            dLo = sLo = kInfinity;
            dHi = sHi = -kInfinity;
            for (const glm::dvec3& p : points) {
                dLo = std::min(dLo, -p.z);
                dHi = std::max(dHi, -p.z);
                const double along = glm::dot(axis, p);
                sLo = std::min(sLo, along);
                sHi = std::max(sHi, along);
            }
            const double slack = 2.0 * double(kClusterDepthSlack) * std::max(std::abs(dLo), std::abs(dHi));
            const double dGrow = widen + growth * (dHi - dLo) + slack;
            const double sGrow = widen + growth * (sHi - sLo) + slack;
            dLo -= dGrow;
            dHi += dGrow;
            sLo -= sGrow;
            sHi += sGrow;
        }
        const auto lo = static_cast<float>(std::max(dLo, -double(kFar)));
        const auto hi = static_cast<float>(std::min(dHi, double(kFar)));
        const auto along0 = static_cast<float>(std::max(sLo, -double(kFar)));
        const auto along1 = static_cast<float>(std::min(sHi, double(kFar)));
        const uint32_t z0 = sliceOf(lo);
        const uint32_t z1 = sliceOf(hi);
        for (uint32_t z = z0; z <= z1; ++z) {
            // A row's froxels are written within its span only: those the span grows over start
            // empty here.
            glm::uvec2& span = out_.rowColumns[size_t(z) * shape_.dims.y + ty];
            const size_t row = shape_.froxelIndex(0, ty, z);
            glm::vec4* const first = out_.values.data() + row;
            if (span.x == kNone) {
                first[tx] = kEmptyExtent;
                span = glm::uvec2(tx);
            } else if (tx < span.x) {
                std::fill(first + tx, first + span.x, kEmptyExtent);
                span.x = tx;
            } else if (tx > span.y) {
                std::fill(first + span.y + 1, first + tx + 1, kEmptyExtent);
                span.y = tx;
            }
            out_.occupiedBits[(size_t(z) * shape_.dims.y + ty) * out_.wordsPerRow() + tx / 64] |= uint64_t(1)
                << (tx % 64);
            glm::vec4& e = first[tx];
            e = glm::vec4(std::min(e.x, lo), std::max(e.y, hi), slab ? std::min(e.z, along0) : -kFar,
                          slab ? std::max(e.w, along1) : kFar);
        }
    }

    // The slice of a view depth: the slice starts at or below it (shape_.sliceOf's, by counting
    // them without branches, which surfaces at any depth would mispredict; the extents' slack
    // covers the rounding).
    uint32_t sliceOf(float depth) const {
        uint32_t z = 0;
        for (const float start : sliceStarts_) z += depth < start ? 0u : 1u;
        return z;
    }

    const ClusterGridShape& shape_;
    std::span<const float> sliceStarts_;  // slices 1 to dims.z - 1
    uint32_t rowBegin_;
    uint32_t rowEnd_;
    glm::dmat4 clipFromView_;
    bool orthographic_;
    int pass_;
    FroxelSurfaces& out_;
    glm::dvec2 tilesPerNdc_{1.0};
    double outside_ = 0.0;  // tile units
    bool edgeOnAnywhere_ = false;
    double clipDepth_ = 0.0;
    glm::dvec3 normal_{0.0};
    double area_ = 0.0;
};

// Whether the triangle's front (counter-clockwise) side faces any of the viewpoints; a triangle
// seen edge-on within a relative 1e-4 counts as facing.
bool facesAnEye(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, std::span<const glm::vec4> viewpoints) {
    const glm::dvec3 pa(a);
    const glm::dvec3 n = glm::cross(glm::dvec3(b) - pa, glm::dvec3(c) - pa);
    for (const glm::vec4& e : viewpoints) {
        const glm::dvec3 toEye = glm::dvec3(e) - pa * double(e.w);
        if (glm::dot(n, toEye) >= -1e-4 * glm::length(n) * glm::length(toEye)) return true;
    }
    return false;
}

}  // namespace

glm::vec4 FroxelSurfaces::extent(size_t froxel) const {
    const size_t tiles = size_t(dims.x) * dims.y;
    const size_t tile = froxel % tiles;
    const glm::uvec2 span = rowColumns[froxel / tiles * dims.y + tile / dims.x];
    const size_t x = tile % dims.x;
    return x >= span.x && x <= span.y ? values[froxel] : kEmptyExtent;
}

void FroxelSurfaces::fillOutsideSpans() {
    if (filled || values.empty()) return;
    for (size_t row = 0; row < rowColumns.size(); ++row) {
        const glm::uvec2 span = rowColumns[row];
        glm::vec4* const first = values.data() + row * dims.x;
        if (span.x > span.y) {
            std::fill(first, first + dims.x, kEmptyExtent);
            continue;
        }
        std::fill(first, first + span.x, kEmptyExtent);
        std::fill(first + span.y + 1, first + dims.x, kEmptyExtent);
    }
    filled = true;
}

void froxelSurfaces(const ClusterGridShape& shape, const ClusterCamera& camera, const ClusterSurfaces& surfaces,
                    FroxelSurfaces& out) {
    const size_t tiles = size_t(shape.dims.x) * shape.dims.y;
    out.dims = shape.dims;
    out.filled = false;
    out.values.resize(out.froxels() + tiles);  // each band clears its own rows below
    out.rowColumns.resize(size_t(shape.dims.z) * shape.dims.y);
    out.occupiedBits.resize(out.rowColumns.size() * out.wordsPerRow());
    const size_t triangles = surfaces.indices.size() / 3;
    const size_t vertexCount = surfaces.positionsWs.size();
    const bool culling = surfaces.backFaceCulled.size() == triangles && !camera.viewpoints.empty();

    // Triangles binned by bands of tile rows (their corners' rows; every band for one crossing
    // the near clip); each band is written by one thread, so no value is shared.
    const uint32_t rowsPerBand = std::max<uint32_t>(1, (shape.dims.y + 15) / 16);
    const uint32_t bandCount = (shape.dims.y + rowsPerBand - 1) / rowsPerBand;
    // Every vertex in view space, once (kept between builds: 12 bytes per vertex).
    std::vector<glm::vec3>& views = out.viewScratch;
    std::vector<glm::dvec4>& clusters = out.clusterScratch;
    views.resize(vertexCount);
    clusters.resize(vertexCount);
    const glm::dmat4 viewFromWorld(camera.eye.viewFromWorld);
    const glm::dmat4 clipFromViewD(camera.eye.clipFromView);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, vertexCount, 4096), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i < r.end(); ++i) {
            views[i] = glm::vec3(viewFromWorld * glm::dvec4(glm::dvec3(surfaces.positionsWs[i]), 1.0));
            clusters[i] = clusterCoordinates(clipFromViewD, glm::dvec3(views[i]));
        }
    });
    const glm::mat4& clipFromView = camera.eye.clipFromView;
    const float tilesPerNdcY = 0.5f * float(shape.extentPx.y) / float(shape.tileSizePx);
    const float marginTiles = (std::max(surfaces.outsidePx, 0.0f) + 1.0f) / float(shape.tileSizePx);
    const bool orthographic = camera.eye.orthographic();
    // In fixed chunks of triangles, each chunk's bins kept apart so that a band reads its
    // triangles in order whatever thread binned which chunk.
    const size_t chunks = (triangles + kBinChunk - 1) / kBinChunk;
    std::vector<std::vector<uint32_t>>& banded = out.bandScratch;
    banded.resize(chunks * bandCount);
    tbb::parallel_for(size_t(0), chunks, [&](size_t chunk) {
        std::vector<uint32_t>* bins = banded.data() + chunk * bandCount;
        for (uint32_t k = 0; k < bandCount; ++k) bins[k].clear();
        const size_t end = std::min(triangles, (chunk + 1) * kBinChunk);
        for (size_t t = chunk * kBinChunk; t < end; ++t) {
            const uint32_t* i = surfaces.indices.data() + 3 * t;
            if (i[0] >= vertexCount || i[1] >= vertexCount || i[2] >= vertexCount) continue;
            const glm::vec3& a = surfaces.positionsWs[i[0]];
            const glm::vec3& b = surfaces.positionsWs[i[1]];
            const glm::vec3& c = surfaces.positionsWs[i[2]];
            if (!std::isfinite(a.x + a.y + a.z + b.x + b.y + b.z + c.x + c.y + c.z)) continue;
            if (culling && surfaces.backFaceCulled[t] != 0 && !facesAnEye(a, b, c, camera.viewpoints)) continue;
            float lo = std::numeric_limits<float>::infinity();
            float hi = -lo;
            bool ahead = true;  // every corner beyond the writer's near clip
            for (int k = 0; k < 3; ++k) {
                const glm::vec3& view = views[i[k]];
                const glm::vec4 clip = clipFromView * glm::vec4(view, 1.0f);
                ahead = ahead && (orthographic || -view.z >= 0.5f * shape.nearM);
                const float row = (clip.y / clip.w + 1.0f) * tilesPerNdcY;
                lo = std::min(lo, row);
                hi = std::max(hi, row);
            }
            uint32_t first = 0;
            uint32_t last = bandCount - 1;
            if (ahead) {
                if (!(hi + marginTiles >= 0.0f && lo - marginTiles <= float(shape.dims.y))) continue;
                const auto band = [&](float row) {
                    return static_cast<uint32_t>(std::clamp(std::floor(row), 0.0f, float(shape.dims.y - 1))) /
                        rowsPerBand;
                };
                first = band(lo - marginTiles);
                last = band(hi + marginTiles);
            }
            for (uint32_t k = first; k <= last; ++k) bins[k].push_back(static_cast<uint32_t>(t));
        }
    });
    std::vector<float> sliceStarts;
    for (uint32_t z = 1; z < shape.dims.z; ++z) sliceStarts.push_back(shape.sliceStartM(z));
    // Per band: its rows emptied, then its tiles' axes (pass 0: the triangles' normals summed; the
    // mean normal where they agree on one), then its froxels' extents (pass 1). A band's passes
    // read and write its own rows only.
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, bandCount, 1), [&](const tbb::blocked_range<uint32_t>& r) {
        for (uint32_t k = r.begin(); k < r.end(); ++k) {
            const uint32_t rowBegin = k * rowsPerBand;
            const uint32_t rowEnd = std::min((k + 1) * rowsPerBand, shape.dims.y);
            const size_t first = out.froxels() + size_t(rowBegin) * shape.dims.x;
            const size_t last = out.froxels() + size_t(rowEnd) * shape.dims.x;
            for (uint32_t z = 0; z < shape.dims.z; ++z) {
                std::fill(out.rowColumns.begin() + ptrdiff_t(size_t(z) * shape.dims.y + rowBegin),
                          out.rowColumns.begin() + ptrdiff_t(size_t(z) * shape.dims.y + rowEnd), glm::uvec2(kNone));
                std::fill(
                    out.occupiedBits.begin() + ptrdiff_t((size_t(z) * shape.dims.y + rowBegin) * out.wordsPerRow()),
                    out.occupiedBits.begin() + ptrdiff_t((size_t(z) * shape.dims.y + rowEnd) * out.wordsPerRow()),
                    uint64_t(0));
            }
            std::fill(out.values.begin() + ptrdiff_t(first), out.values.begin() + ptrdiff_t(last), glm::vec4(0.0f));
            const auto pass = [&](int which) {
                SurfaceWriter writer(shape, sliceStarts, camera.eye, double(surfaces.outsidePx), which, rowBegin,
                                     rowEnd, out);
                for (size_t chunk = 0; chunk < chunks; ++chunk)
                    for (const uint32_t t : banded[chunk * bandCount + k]) {
                        const uint32_t* i = surfaces.indices.data() + 3 * size_t(t);
                        const auto vertex = [&](uint32_t v) { return Corner{glm::dvec3(views[v]), clusters[v]}; };
                        writer.triangle(vertex(i[0]), vertex(i[1]), vertex(i[2]));
                    }
            };
            pass(0);
            for (size_t tile = first; tile < last; ++tile) {
                const glm::vec3 sum(out.values[tile]);
                const float length = glm::length(sum);
                out.values[tile] =
                    length > 0.0f && std::isfinite(length) ? glm::vec4(sum / length, 1.0f) : glm::vec4(0.0f);
            }
            pass(1);
        }
    });
    // Empty spans as lo > hi, and each slice's rows.
    out.sliceRows.assign(shape.dims.z, glm::uvec2(1u, 0u));
    for (uint32_t z = 0; z < shape.dims.z; ++z)
        for (uint32_t y = 0; y < shape.dims.y; ++y) {
            glm::uvec2& span = out.rowColumns[size_t(z) * shape.dims.y + y];
            if (span.x == kNone) {
                span = glm::uvec2(1u, 0u);
                continue;
            }
            glm::uvec2& rows = out.sliceRows[z];
            rows = rows.x > rows.y ? glm::uvec2(y) : glm::uvec2(rows.x, y);
        }
}

}  // namespace preskin
