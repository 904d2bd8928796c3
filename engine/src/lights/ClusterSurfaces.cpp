// Per-froxel depth intervals of the frame's surfaces; the method is in ClusterSurfaces.h.
#include "lights/ClusterSurfaces.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace preskin {

namespace {

// How far (pixels) a fragment's position may lie outside its triangle's projection: with MSAA a
// pixel whose samples the triangle covers in part is shaded at its centre, up to 0.71 pixels away
// (in the plane's extrapolation); an eye of a stereo view has pixels of about the cluster
// camera's size; and the rasterizer snaps vertices to sub-pixels.
constexpr double kMarginPx = 1.0;

// One triangle at a time into a band array.
class BandWriter {
public:
    BandWriter(const ClusterGridShape& shape, const glm::dmat4& clusterFromWorld, bool orthographic,
               std::vector<glm::vec2>& bands)
        : shape_(shape), clusterFromWorld_(clusterFromWorld), orthographic_(orthographic), bands_(bands) {
        tilesPerNdc_ = 0.5 * glm::dvec2(shape.extentPx) / double(shape.tileSizePx);
        margin_ = kMarginPx / double(shape.tileSizePx);
        // Perspective fragments lie beyond the near plane; clipping a little nearer keeps w > 0.
        clipDepth_ = 0.5 * double(shape.nearM);
    }

    void triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
        // (clip x, clip y, view depth, clip w) of the cluster camera.
        const std::array<glm::dvec4, 3> h{clusterFromWorld_ * glm::dvec4(glm::dvec3(a), 1.0),
                                          clusterFromWorld_ * glm::dvec4(glm::dvec3(b), 1.0),
                                          clusterFromWorld_ * glm::dvec4(glm::dvec3(c), 1.0)};
        if (orthographic_) {
            polygon(h.data(), 3);
            return;
        }
        // Clip to depth >= clipDepth_ (Sutherland-Hodgman against one plane: at most 4 corners).
        std::array<glm::dvec4, 4> clipped;
        int n = 0;
        for (int i = 0; i < 3; ++i) {
            const glm::dvec4& p = h[size_t(i)];
            const glm::dvec4& q = h[size_t((i + 1) % 3)];
            const bool pIn = p.z >= clipDepth_;
            const bool qIn = q.z >= clipDepth_;
            if (pIn) clipped[size_t(n++)] = p;
            if (pIn != qIn) clipped[size_t(n++)] = p + (q - p) * ((clipDepth_ - p.z) / (q.z - p.z));
        }
        if (n >= 3) polygon(clipped.data(), n);
    }

private:
    // A convex planar polygon of n (3 or 4) clip-space corners, all with w > 0.
    void polygon(const glm::dvec4* v, int n) {
        std::array<glm::dvec2, 4> t;  // corners in tile units
        glm::dvec2 lo(1e300);
        glm::dvec2 hi(-1e300);
        for (int i = 0; i < n; ++i) {
            t[size_t(i)] = (glm::dvec2(v[i]) / v[i].w + 1.0) * tilesPerNdc_;
            lo = glm::min(lo, t[size_t(i)]);
            hi = glm::max(hi, t[size_t(i)]);
        }
        lo -= margin_;
        hi += margin_;
        const glm::dvec2 dims(shape_.dims);
        if (!(hi.x >= 0.0 && hi.y >= 0.0 && lo.x <= dims.x && lo.y <= dims.y)) return;  // off the grid (or NaN)
        const auto tile = [](double x, double count) {
            return static_cast<uint32_t>(std::clamp(std::floor(x), 0.0, count - 1.0));
        };
        const uint32_t x0 = tile(lo.x, dims.x), x1 = tile(hi.x, dims.x);
        const uint32_t y0 = tile(lo.y, dims.y), y1 = tile(hi.y, dims.y);

        // depth / w and 1 / w as affine functions of the tile coordinates, from three corners.
        const glm::dvec2 e1 = t[1] - t[0];
        const glm::dvec2 e2 = t[2] - t[0];
        const double det = e1.x * e2.y - e1.y * e2.x;
        const double size = std::max(glm::length(e1), glm::length(e2));
        const bool planar = std::abs(det) > 1e-9 * std::max(size * size, 1e-30);
        glm::dvec3 A(0.0);
        glm::dvec3 B(0.0);  // value = x * gx + y * gy + c: (gx, gy, c)
        if (planar) {
            const auto fit = [&](double f0, double f1, double f2) {
                const double gx = ((f1 - f0) * e2.y - (f2 - f0) * e1.y) / det;
                const double gy = ((f2 - f0) * e1.x - (f1 - f0) * e2.x) / det;
                return glm::dvec3(gx, gy, f0 - gx * t[0].x - gy * t[0].y);
            };
            A = fit(v[0].z / v[0].w, v[1].z / v[1].w, v[2].z / v[2].w);
            B = fit(1.0 / v[0].w, 1.0 / v[1].w, 1.0 / v[2].w);
        }
        const double orientation = det < 0.0 ? -1.0 : 1.0;
        for (uint32_t ty = y0; ty <= y1; ++ty)
            for (uint32_t tx = x0; tx <= x1; ++tx) {
                // The tile's rectangle (grown by the margin) within the polygon's box.
                const glm::dvec2 r0 = glm::max(glm::dvec2(tx, ty) - margin_, lo);
                const glm::dvec2 r1 = glm::min(glm::dvec2(tx + 1, ty + 1) + margin_, hi);
                const std::array<glm::dvec2, 4> corners{r0, glm::dvec2(r1.x, r0.y), r1, glm::dvec2(r0.x, r1.y)};
                if (planar && separated(t.data(), n, orientation, corners)) continue;
                // The plane's depths over the rectangle (past the corners by the margin too); a
                // plane seen edge-on, or passing the eye there, gets the tile's whole depth.
                double rectMin = 0.0;
                double rectMax = std::numeric_limits<double>::infinity();
                if (planar) {
                    double cMin = std::numeric_limits<double>::infinity();
                    double cMax = -cMin;
                    bool ahead = true;
                    for (const glm::dvec2& p : corners) {
                        const double b = B.x * p.x + B.y * p.y + B.z;
                        ahead = ahead && b > 0.0;
                        const double d = (A.x * p.x + A.y * p.y + A.z) / b;
                        cMin = std::min(cMin, d);
                        cMax = std::max(cMax, d);
                    }
                    if (ahead && std::isfinite(cMin) && std::isfinite(cMax)) {
                        rectMin = cMin;
                        rectMax = cMax;
                    }
                }
                mark(tx, ty, rectMin, rectMax);
            }
    }

    // Whether one edge of the polygon has the whole rectangle outside it.
    static bool separated(const glm::dvec2* t, int n, double orientation, const std::array<glm::dvec2, 4>& corners) {
        for (int i = 0; i < n; ++i) {
            const glm::dvec2 a = t[i];
            const glm::dvec2 e = t[(i + 1) % n] - a;
            bool allOutside = true;
            for (const glm::dvec2& p : corners) {
                const double side = orientation * (e.x * (p.y - a.y) - e.y * (p.x - a.x));
                if (side >= 0.0) {
                    allOutside = false;
                    break;
                }
            }
            if (allOutside) return true;
        }
        return false;
    }

    void mark(uint32_t tx, uint32_t ty, double dLo, double dHi) {
        const auto lo = static_cast<float>(dLo - std::abs(dLo) * 2.0 * double(kClusterDepthSlack));
        const auto hi = static_cast<float>(std::min(dHi + std::abs(dHi) * 2.0 * double(kClusterDepthSlack), 3.0e38));
        const uint32_t z0 = shape_.sliceOf(lo);
        const uint32_t z1 = shape_.sliceOf(hi);
        for (uint32_t z = z0; z <= z1; ++z) {
            glm::vec2& band = bands_[shape_.froxelIndex(tx, ty, z)];
            band.x = std::min(band.x, lo);
            band.y = std::max(band.y, hi);
        }
    }

    const ClusterGridShape& shape_;
    glm::dmat4 clusterFromWorld_;
    bool orthographic_;
    std::vector<glm::vec2>& bands_;
    glm::dvec2 tilesPerNdc_{1.0};
    double margin_ = 0.0;
    double clipDepth_ = 0.0;
};

}  // namespace

void froxelDepthBands(const ClusterGridShape& shape, const ClusterCamera& camera, const ClusterSurfaces& surfaces,
                      std::vector<glm::vec2>& bands) {
    const size_t froxels = shape.froxelCount();
    bands.assign(froxels, kEmptyBand);
    const glm::dmat4 clusterFromWorld(camera.clusterFromWorld());
    const bool orthographic = camera.eye.orthographic();
    const size_t triangles = surfaces.indices.size() / 3;
    const size_t vertexCount = surfaces.positionsWs.size();
    const auto run = [&](size_t begin, size_t end, std::vector<glm::vec2>& out) {
        BandWriter writer(shape, clusterFromWorld, orthographic, out);
        for (size_t t = begin; t < end; ++t) {
            const uint32_t* i = surfaces.indices.data() + 3 * t;
            if (i[0] >= vertexCount || i[1] >= vertexCount || i[2] >= vertexCount) continue;
            const glm::vec3& a = surfaces.positionsWs[i[0]];
            const glm::vec3& b = surfaces.positionsWs[i[1]];
            const glm::vec3& c = surfaces.positionsWs[i[2]];
            if (!std::isfinite(a.x + a.y + a.z + b.x + b.y + b.z + c.x + c.y + c.z)) continue;
            writer.triangle(a, b, c);
        }
    };
    // Small meshes in one pass; large ones split over threads, each with its own bands, merged.
    constexpr size_t kChunk = 16384;
    if (triangles <= kChunk) {
        run(0, triangles, bands);
        return;
    }
    tbb::enumerable_thread_specific<std::vector<glm::vec2>> partial(
        [&] { return std::vector<glm::vec2>(froxels, kEmptyBand); });
    tbb::parallel_for(tbb::blocked_range<size_t>(0, triangles, kChunk),
                      [&](const tbb::blocked_range<size_t>& r) { run(r.begin(), r.end(), partial.local()); });
    for (const std::vector<glm::vec2>& p : partial)
        tbb::parallel_for(tbb::blocked_range<size_t>(0, froxels, 4096), [&](const tbb::blocked_range<size_t>& r) {
            for (size_t f = r.begin(); f < r.end(); ++f) {
                bands[f].x = std::min(bands[f].x, p[f].x);
                bands[f].y = std::max(bands[f].y, p[f].y);
            }
        });
}

}  // namespace preskin
