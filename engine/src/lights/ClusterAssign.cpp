// CPU light assignment for the froxel grid; the method and its sources are in ClusterAssign.h.
#include "lights/ClusterAssign.h"

#include "lights/ClusterSurfaces.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

namespace preskin {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

float signedDistance(const glm::vec4& plane, const glm::vec3& p) { return glm::dot(glm::vec3(plane), p) + plane.w; }

// A sphere by its centre and squared radius (infinite for an unlimited light): cutting it and
// testing it against planes needs no square root.
struct Ball {
    glm::vec3 c;
    float r2;
};

Ball ball(const glm::vec3& c, float r) { return {c, r * r}; }

// Does the ball overlap the slab between planes k and k + 1 (a column or a row of tiles)? (Its
// tests, like the cuts below, are free of branches: lights come in no order a branch predicts.)
bool slabOverlaps(const std::vector<glm::vec4>& planes, uint32_t k, const Ball& s) {
    const float below = std::min(signedDistance(planes[k], s.c), 0.0f);      // inside: >= -r
    const float above = std::max(signedDistance(planes[k + 1], s.c), 0.0f);  // inside: <= r
    return (below * below <= s.r2) & (above * above <= s.r2);
}

// The first and last slab in [lo, hi] the ball overlaps; every overlapped slab lies between
// them whatever the order of the planes' distances, so scanning inwards is conservative.
bool slabRange(const std::vector<glm::vec4>& planes, uint32_t lo, uint32_t hi, const Ball& s, uint32_t& first,
               uint32_t& last) {
    uint32_t a = lo;
    while (a <= hi && !slabOverlaps(planes, a, s)) ++a;
    if (a > hi) return false;
    uint32_t b = hi;
    while (b > a && !slabOverlaps(planes, b, s)) --b;
    first = a;
    last = b;
    return true;
}

// Replaces the ball by one bounding its part on the inner side of `plane` (the side where the
// signed distance is >= 0 when `inner` is +1, <= 0 when -1): the centre moves onto the plane, the
// squared radius loses the squared distance. False when nothing is left.
bool cutByPlane(const glm::vec4& plane, float inner, Ball& s) {
    const float outside = std::max(-inner * signedDistance(plane, s.c), 0.0f);
    const float h2 = outside * outside;
    if (h2 > s.r2) return false;
    s.c += glm::vec3(plane) * (inner * outside);
    s.r2 -= h2;  // an infinite ball stays infinite
    return true;
}

// Cuts the ball to the depth slab [d0, d1] (view depth = -z, d0 <= d1). False when nothing is left.
bool cutByDepth(float d0, float d1, Ball& s) {
    const float depth = -s.c.z;
    const float inside = std::min(std::max(depth, d0), d1);
    const float h = depth - inside;
    if (h * h > s.r2) return false;
    s.c.z = -inside;
    s.r2 -= h * h;
    return true;
}

// Bounding sphere (centre, radius) of the part of froxel column (x, y) between view depths dA and dB.
glm::vec4 froxelSphere(const ClusterGeometry& g, uint32_t x, uint32_t y, float dA, float dB) {
    glm::vec3 lo(kInfinity);
    glm::vec3 hi(-kInfinity);
    for (uint32_t j = y; j <= y + 1; ++j)
        for (uint32_t i = x; i <= x + 1; ++i) {
            const uint32_t k = g.cornerIndex(i, j);
            const glm::vec3 origin(g.cornerOrigin[k]);
            const glm::vec3 dir(g.cornerDir[k]);
            for (float d : {dA, dB}) {
                const glm::vec3 p = origin + dir * d;
                lo = glm::min(lo, p);
                hi = glm::max(hi, p);
            }
        }
    return glm::vec4(0.5f * (lo + hi), 0.5f * glm::length(hi - lo) * (1.0f + kClusterRadiusSlack) + 1e-6f);
}

// Cone of a spot against a froxel's bounding sphere.
bool coneReachesSphere(const ClusterCone& b, const glm::vec4& sphere) {
    const glm::vec3 center(sphere);
    const float radius = sphere.w;
    const glm::vec3 v = center - b.apexVs;
    const float along = glm::dot(v, b.axisVs);
    const float across = std::sqrt(std::max(glm::dot(v, v) - along * along, 0.0f));
    const float closest = b.cosOuter * across - along * b.sinOuter;
    return !(closest > radius || along > radius + b.rangeM || along < -radius);
}

float slackenedCosOuter(const ClusterLight& light) {
    return std::clamp(light.cosOuter - kClusterConeSlack, -1.0f, 1.0f);
}

}  // namespace

float clusterSphereOffsetM(const ClusterLight& light) {
    const bool unlimited = !(light.rangeM > 0.0f) || !std::isfinite(light.rangeM);
    const float cosOuter = slackenedCosOuter(light);
    return light.spot && !unlimited && cosOuter > 0.5f ? light.rangeM / (2.0f * cosOuter) : 0.0f;
}

glm::vec4 clusterLightSphereWs(const ClusterLight& light) {
    const float offset = clusterSphereOffsetM(light);
    if (offset > 0.0f) return glm::vec4(light.positionWs + glm::normalize(light.directionWs) * offset, offset);
    const bool unlimited = !(light.rangeM > 0.0f) || !std::isfinite(light.rangeM);
    return glm::vec4(light.positionWs, unlimited ? kInfinity : light.rangeM);
}

bool sphereReachesBox(const Bounds& box, const glm::vec3& center, float radius) {
    const glm::vec3 outside = center - glm::clamp(center, box.min, box.max);  // (branch-free: lights at random)
    return !(glm::dot(outside, outside) > radius * radius);
}

ClusterLightBounds clusterLightBounds(const ClusterLight& light, const glm::mat4& viewFromWorld,
                                      const ClusterGeometry& g, ClusterCone& cone) {
    ClusterLightBounds b;
    b.index = light.index;
    const glm::vec3 apex(viewFromWorld * glm::vec4(light.positionWs, 1.0f));
    const bool unlimited = !(light.rangeM > 0.0f) || !std::isfinite(light.rangeM);
    b.centerVs = apex;
    b.radiusM = unlimited ? kInfinity : light.rangeM;
    const float centerAlongAxis = clusterSphereOffsetM(light);
    const float cosOuter = slackenedCosOuter(light);
    // A cone of 90 degrees or more is culled by its range sphere only.
    b.cone = light.spot && cosOuter > 0.0f;
    if (centerAlongAxis > 0.0f || b.cone) {
        const glm::vec3 axis = glm::mat3(viewFromWorld) * light.directionWs;
        const float axisLength = glm::length(axis);
        const glm::vec3 axisVs = axisLength > 0.0f ? axis / axisLength : glm::vec3(0.0f, 0.0f, -1.0f);
        if (centerAlongAxis > 0.0f) {
            b.centerVs = apex + axisVs * centerAlongAxis;
            b.radiusM = centerAlongAxis;
        }
        if (b.cone) {
            cone.apexVs = apex;
            cone.rangeM = unlimited ? kInfinity : light.rangeM;
            cone.axisVs = axisVs;
            cone.cosOuter = cosOuter;
            cone.sinOuter = std::sqrt(std::max(1.0f - cosOuter * cosOuter, 0.0f));
        }
    }
    if (!unlimited) b.radiusM = b.radiusM * (1.0f + kClusterRadiusSlack) + 1e-6f;

    const ClusterGridShape& s = g.shape;
    if (!unlimited && !s.lightBounds.empty()) {
        // The same sphere in world space (the view transform is rigid), against the scene's box.
        if (!sphereReachesBox(s.lightBounds, glm::vec3(clusterLightSphereWs(light)), b.radiusM))
            return b;  // lo > hi: listed nowhere
    }
    const float depth = -b.centerVs.z;
    const float minDepth = depth - b.radiusM;
    const float maxDepth = depth + b.radiusM;
    if (maxDepth < s.nearM * (1.0f - 2.0f * kClusterDepthSlack)) return b;  // behind the near plane
    uint32_t first = 0;
    uint32_t last = 0;
    // The slabs are tested within the sphere's projected tiles where those are known.
    glm::uvec2 columns(0u, s.dims.x - 1);
    glm::uvec2 rows(0u, s.dims.y - 1);
    if (g.sphereTiles(0, b.centerVs, b.radiusM, first, last)) columns = glm::uvec2(first, last);
    if (g.sphereTiles(1, b.centerVs, b.radiusM, first, last)) rows = glm::uvec2(first, last);
    const Ball sphere = ball(b.centerVs, b.radiusM);
    glm::uvec3 lo(0u);
    glm::uvec3 hi(0u);
    if (!slabRange(g.xPlanes, columns.x, columns.y, sphere, lo.x, hi.x) ||
        !slabRange(g.yPlanes, rows.x, rows.y, sphere, lo.y, hi.y))
        return b;  // off the image
    lo.z = s.sliceOf(minDepth * (1.0f - 2.0f * kClusterDepthSlack));
    hi.z = s.sliceOf(maxDepth * (1.0f + 2.0f * kClusterDepthSlack));
    b.lo = lo;
    b.hi = hi;
    return b;
}

void ClusterAssigner::build(const ClusterSettings& settings, const ClusterGeometry& g, const glm::mat4& viewFromWorld,
                            std::span<const ClusterLight> lights, const FroxelSurfaces& surfaces, ClusterGrid& grid) {
    const ClusterGridShape& s = g.shape;
    grid.shape = s;
    const uint32_t perSlice = s.dims.x * s.dims.y;
    const uint32_t froxels = s.froxelCount();

    const bool withSurfaces = !surfaces.empty() && surfaces.froxels() == froxels;
    const uint32_t stamp = ++stamp_ == 0 ? ++stamp_ : stamp_;  // marks this build's cached spheres
    bounds_.resize(lights.size());
    cones_.resize(lights.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, lights.size(), 64), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i < r.end(); ++i)
            bounds_[i] = clusterLightBounds(lights[i], viewFromWorld, g, cones_[i]);
    });

    // Each slice's candidates: small lights reach few slices, so a slice reads only its own
    // instead of every light's bounds.
    slices_.resize(s.dims.z);
    for (SliceScratch& sc : slices_) sc.candidates.clear();
    for (uint32_t i = 0; i < bounds_.size(); ++i) {
        const ClusterLightBounds& b = bounds_[i];
        if (b.lo.x > b.hi.x || b.lo.y > b.hi.y) continue;
        const Candidate c{b.centerVs, b.radiusM,           glm::uvec2(b.lo.x, b.hi.x), glm::uvec2(b.lo.y, b.hi.y),
                          b.index,    b.cone ? i : kNoCone};
        for (uint32_t z = b.lo.z; z <= b.hi.z && z < s.dims.z; ++z) slices_[z].candidates.push_back(c);
    }
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, s.dims.z, 1), [&](const tbb::blocked_range<uint32_t>& r) {
        for (uint32_t z = r.begin(); z < r.end(); ++z) {
            SliceScratch& sc = slices_[z];
            sc.froxel.clear();
            sc.light.clear();
            sc.count.assign(perSlice, 0u);
            sc.largest = 0;
            if (!withSurfaces) {
                sc.sphere.assign(perSlice, glm::vec4(-1.0f));  // radius < 0: not computed yet
            } else if (sc.sphereStamp.size() != perSlice) {
                sc.sphere.resize(perSlice);
                sc.sphereStamp.assign(perSlice, 0u);  // stamp != 0: not computed in this build
            }
            const float d0 = g.sliceStartM[z] * (1.0f - kClusterDepthSlack);
            const float d1 = z + 1 >= s.dims.z ? kInfinity : g.sliceStartM[z + 1] * (1.0f + kClusterDepthSlack);
            // With surfaces, lights are scanned only over the rows and columns that hold them.
            glm::uvec2 rows(0u, s.dims.y - 1);
            const glm::uvec2* columns = nullptr;
            if (withSurfaces) {
                columns = surfaces.rowColumns.data() + size_t(z) * s.dims.y;
                rows = surfaces.sliceRows[z];
                if (rows.x > rows.y) continue;
            }
            for (const Candidate& b : sc.candidates) {
                const Ball whole = ball(b.centerVs, b.radiusM);
                Ball inSlice = whole;
                if (!cutByDepth(d0, d1, inSlice)) continue;
                uint32_t y0 = 0;
                uint32_t y1 = 0;
                if (!slabRange(g.yPlanes, std::max(b.rows.x, rows.x), std::min(b.rows.y, rows.y), inSlice, y0, y1))
                    continue;
                // Depth extent of the light inside this slice, for the spot's froxel spheres.
                const float coneD0 = std::max(d0, -b.centerVs.z - b.radiusM);
                const float coneD1 = std::min(d1, -b.centerVs.z + b.radiusM);
                const bool fullSlice = coneD0 == d0 && coneD1 == d1;
                for (uint32_t y = y0; y <= y1; ++y) {
                    uint32_t lo = b.columns.x;
                    uint32_t hi = b.columns.y;
                    if (withSurfaces) {
                        lo = std::max(lo, columns[y].x);
                        hi = std::min(hi, columns[y].y);
                        if (lo > hi) continue;
                    }
                    Ball inRow = inSlice;
                    if (!cutByPlane(g.yPlanes[y], 1.0f, inRow) || !cutByPlane(g.yPlanes[y + 1], -1.0f, inRow)) continue;
                    uint32_t x0 = 0;
                    uint32_t x1 = 0;
                    if (!slabRange(g.xPlanes, lo, hi, inRow, x0, x1)) continue;
                    const auto list = [&](uint32_t local) {
                        sc.froxel.push_back(local);
                        sc.light.push_back(b.index);
                        sc.largest = std::max(sc.largest, ++sc.count[local]);
                    };
                    if (withSurfaces) {
                        // The row's froxels with surfaces, by their bits; per froxel the sphere
                        // cut to its surfaces' slab and depths, then to the row, then tested
                        // against the column.
                        const uint64_t* bits = surfaces.occupiedRow(z, y);
                        for (uint32_t w = x0 / 64; w <= x1 / 64; ++w) {
                            uint64_t word = bits[w];
                            if (w == x0 / 64) word &= ~uint64_t(0) << (x0 % 64);
                            if (w == x1 / 64) word &= ~uint64_t(0) >> (63 - x1 % 64);
                            for (; word != 0; word &= word - 1) {
                                const uint32_t x = w * 64 + static_cast<uint32_t>(std::countr_zero(word));
                                const uint32_t local = y * s.dims.x + x;
                                const glm::vec4& extent = surfaces.spanExtent(size_t(z) * perSlice + local);
                                const glm::vec4& axis = surfaces.axis(local);
                                const float e0 = std::max(d0, extent.x);
                                const float e1 = std::min(d1, extent.y);
                                if (!(e0 <= e1)) continue;
                                Ball part = whole;
                                if (axis.w > 0.0f &&
                                    (!cutByPlane(glm::vec4(glm::vec3(axis), -extent.z), 1.0f, part) ||
                                     !cutByPlane(glm::vec4(glm::vec3(axis), -extent.w), -1.0f, part)))
                                    continue;
                                if (!cutByDepth(e0, e1, part) || !cutByPlane(g.yPlanes[y], 1.0f, part) ||
                                    !cutByPlane(g.yPlanes[y + 1], -1.0f, part) || !slabOverlaps(g.xPlanes, x, part))
                                    continue;
                                if (b.cone != kNoCone) {  // against the sphere of the occupied depths, once per froxel
                                    if (sc.sphereStamp[local] != stamp) {
                                        sc.sphere[local] = froxelSphere(g, x, y, e0, e1);
                                        sc.sphereStamp[local] = stamp;
                                    }
                                    if (!coneReachesSphere(cones_[b.cone], sc.sphere[local])) continue;
                                }
                                list(local);
                            }
                        }
                        continue;
                    }
                    for (uint32_t x = x0; x <= x1; ++x) {
                        const uint32_t local = y * s.dims.x + x;
                        if (b.cone != kNoCone && coneD0 <= coneD1 && std::isfinite(coneD1)) {
                            // The whole froxel's sphere is cached per slice; a light ending inside
                            // the slice gets the sphere of the part it can reach.
                            glm::vec4 sphere;
                            if (fullSlice) {
                                glm::vec4& cached = sc.sphere[y * s.dims.x + x];
                                if (!(cached.w >= 0.0f)) cached = froxelSphere(g, x, y, d0, d1);
                                sphere = cached;
                            } else {
                                sphere = froxelSphere(g, x, y, coneD0, coneD1);
                            }
                            if (!coneReachesSphere(cones_[b.cone], sphere)) continue;
                        }
                        list(local);
                    }
                }
            }
        }
    });

    // Offsets in froxel order, both caps applied (see the overflow rule in ClusterGrid.h).
    grid.ranges.resize(froxels);
    const uint64_t perCluster = std::max<uint32_t>(settings.maxLightsPerCluster, 1);
    const uint64_t capacity = std::max<uint32_t>(settings.maxLightIndices, 1);
    uint64_t running = 0;
    grid.overflowedClusters = 0;
    grid.requestedIndices = 0;
    bool capped = false;
    std::vector<uint64_t> sliceBase(s.dims.z + 1, 0);
    for (uint32_t z = 0; z < s.dims.z; ++z) {
        capped = capped || slices_[z].largest > perCluster;
        sliceBase[z + 1] = sliceBase[z] + slices_[z].froxel.size();
    }
    capped = capped || sliceBase[s.dims.z] > capacity;
    if (!capped) {  // no cap applies: every slice's offsets from its own start, in parallel
        tbb::parallel_for(tbb::blocked_range<uint32_t>(0, s.dims.z, 1), [&](const tbb::blocked_range<uint32_t>& r) {
            for (uint32_t z = r.begin(); z < r.end(); ++z) {
                const SliceScratch& sc = slices_[z];
                auto offset = static_cast<uint32_t>(sliceBase[z]);
                glm::uvec2* out = grid.ranges.data() + size_t(z) * perSlice;
                for (uint32_t local = 0; local < perSlice; ++local) {
                    out[local] = glm::uvec2(offset, sc.count[local]);
                    offset += sc.count[local];
                }
            }
        });
        running = grid.requestedIndices = sliceBase[s.dims.z];
    } else {
        for (uint32_t z = 0; z < s.dims.z; ++z) {
            const SliceScratch& sc = slices_[z];
            for (uint32_t local = 0; local < perSlice; ++local) {
                const uint64_t n = sc.count[local];
                const uint64_t kept = std::min({n, perCluster, capacity - running});
                if (kept < n) ++grid.overflowedClusters;
                grid.ranges[z * perSlice + local] =
                    glm::uvec2(static_cast<uint32_t>(running), static_cast<uint32_t>(kept));
                running += kept;
                grid.requestedIndices += n;
            }
        }
    }
    grid.indices.resize(running);
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, s.dims.z, 1), [&](const tbb::blocked_range<uint32_t>& r) {
        for (uint32_t z = r.begin(); z < r.end(); ++z) {
            SliceScratch& sc = slices_[z];
            std::fill(sc.count.begin(), sc.count.end(), 0u);  // now: entries written per froxel
            const glm::uvec2* ranges = grid.ranges.data() + size_t(z) * perSlice;
            for (size_t e = 0; e < sc.froxel.size(); ++e) {
                const uint32_t local = sc.froxel[e];
                uint32_t& written = sc.count[local];
                if (written < ranges[local].y) grid.indices[ranges[local].x + written++] = sc.light[e];
            }
        }
    });
}

}  // namespace preskin
