// Independent CPU reference for the light-grid tests (tests/reference/test_cluster_grid.cpp,
// tests/reference/test_cluster_build.cpp). It shares no code with engine/src/lights: froxels are
// rebuilt from the grid's contract in <preskin/ClusterGrid.h> (tile edges at pixel multiples of
// tileSizePx, slice starts, the view's projection) as hexahedra in world space, and
//  - a point light touches a froxel when the exact distance from its centre to the hexahedron
//    (inside, nearest face, or nearest edge) is below its range;
//  - a spot touches it when one of a 9 x 9 x 9 lattice of points spanning the froxel (corners,
//    edges and faces included) lies inside its range and outer cone.
// A light is "required" in a froxel only when it touches with a small margin (1e-3 of the range,
// 1e-3 in cone cosine), so float rounding at an exact touch never decides a test; at such a
// touch the light's contribution is zero anyway (range window and cone attenuation end at 0).
// Limits: the lattice can miss a spot that only grazes a froxel between lattice points; the
// tests then check less, never wrongly.
#pragma once

#include <preskin/ClusterGrid.h>
#include <preskin/Scene.h>
#include <preskin/View.h>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace preskin::test {

// Corners c = i + 2 j + 4 k: i/j the low/high pixel edge in x/y, k the slice's near/far depth.
struct ReferenceFroxel {
    std::array<glm::dvec3, 8> cornersWs;
};

// `farM` replaces the last slice's infinite end.
inline ReferenceFroxel referenceFroxel(const ClusterGridShape& shape, const Eye& view, uint32_t x, uint32_t y,
                                       uint32_t z, double farM) {
    const glm::dmat4 clipFromView(view.clipFromView);
    const glm::dmat4 viewFromClip = glm::inverse(clipFromView);
    const glm::dmat4 worldFromView = glm::inverse(glm::dmat4(view.viewFromWorld));
    const double w = shape.extentPx.x;
    const double h = shape.extentPx.y;
    const double t = shape.tileSizePx;
    const double px[2] = {x * t, std::min((x + 1) * t, w)};
    const double py[2] = {y * t, std::min((y + 1) * t, h)};
    const double d0 = z == 0 ? double(shape.nearM) : double(shape.sliceStartM(z));
    const double d1 = z + 1 >= shape.dims.z ? farM : double(shape.sliceStartM(z + 1));
    const double depth[2] = {d0, std::max(d1, d0)};
    ReferenceFroxel f;
    for (int k = 0; k < 2; ++k) {
        const glm::dvec4 clip = clipFromView * glm::dvec4(0.0, 0.0, -depth[k], 1.0);
        for (int j = 0; j < 2; ++j)
            for (int i = 0; i < 2; ++i) {
                glm::dvec4 p =
                    viewFromClip * glm::dvec4(px[i] / w * 2.0 - 1.0, py[j] / h * 2.0 - 1.0, clip.z / clip.w, 1.0);
                p /= p.w;
                f.cornersWs[size_t(i + 2 * j + 4 * k)] = glm::dvec3(worldFromView * p);
            }
    }
    return f;
}

inline double segmentDistance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b) {
    const glm::dvec3 ab = b - a;
    const double len2 = glm::dot(ab, ab);
    const double t = len2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
    return glm::length(p - (a + ab * t));
}

// Exact distance from p to the (convex) froxel; 0 inside.
inline double distanceToFroxel(const ReferenceFroxel& f, const glm::dvec3& p) {
    static constexpr int faces[6][4] = {{0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                        {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6}};
    glm::dvec3 centroid(0.0);
    for (const glm::dvec3& c : f.cornersWs) centroid += c / 8.0;
    bool inside = true;
    double best = std::numeric_limits<double>::infinity();
    for (const auto& face : faces) {
        const glm::dvec3& a = f.cornersWs[size_t(face[0])];
        glm::dvec3 n = glm::cross(f.cornersWs[size_t(face[1])] - a, f.cornersWs[size_t(face[3])] - a);
        if (glm::length(n) == 0.0) continue;
        n = glm::normalize(n);
        if (glm::dot(n, centroid - a) > 0.0) n = -n;
        const double distance = glm::dot(n, p - a);
        if (distance <= 0.0) continue;
        inside = false;
        // The projection onto the face plane: inside the face polygon?
        const glm::dvec3 q = p - n * distance;
        glm::dvec3 faceCentre(0.0);
        for (int c : face) faceCentre += f.cornersWs[size_t(c)] / 4.0;
        bool within = true;
        for (int e = 0; e < 4 && within; ++e) {
            const glm::dvec3& e0 = f.cornersWs[size_t(face[e])];
            const glm::dvec3& e1 = f.cornersWs[size_t(face[(e + 1) % 4])];
            glm::dvec3 out = glm::cross(e1 - e0, n);
            if (glm::dot(out, faceCentre - e0) > 0.0) out = -out;
            within = glm::dot(out, q - e0) <= 0.0;
        }
        if (within) best = std::min(best, distance);
    }
    if (inside) return 0.0;
    for (int c = 0; c < 8; ++c)
        for (int bit : {1, 2, 4})
            if ((c & bit) == 0)
                best = std::min(best, segmentDistance(p, f.cornersWs[size_t(c)], f.cornersWs[size_t(c | bit)]));
    return best;
}

// The world point at pixel (px, py) of a widthPx x heightPx image of `eye`, at view depth d
// (tile edges at px, py = multiples of the tile size).
inline glm::vec3 pointAtPixel(const Eye& eye, float px, float py, float widthPx, float heightPx, float d) {
    const glm::vec4 clip = eye.clipFromView * glm::vec4(0.0f, 0.0f, -d, 1.0f);
    glm::vec4 p = glm::inverse(eye.clipFromView) *
        glm::vec4(px / widthPx * 2.0f - 1.0f, py / heightPx * 2.0f - 1.0f, clip.z / clip.w, 1.0f);
    p /= p.w;
    return glm::vec3(glm::inverse(eye.viewFromWorld) * p);
}

// Does p lie inside the light's volume, `margin` (a fraction of the range, and of the cone
// cosine) inside its boundary?
inline bool insideLight(const Light& l, const glm::dvec3& p, double margin) {
    const glm::dvec3 toPoint = p - glm::dvec3(l.positionWs);
    const double d = glm::length(toPoint);
    if (l.range > 0.0f && d >= double(l.range) * (1.0 - margin)) return false;
    if (l.type != LightType::Spot) return true;
    if (d == 0.0) return true;
    const glm::dvec3 dir = glm::normalize(glm::dvec3(l.directionWs));
    return glm::dot(dir, toPoint) / d > std::cos(double(l.outerConeAngle)) + margin;
}

// Must the light be listed in this froxel (it touches it with a margin)?
inline bool lightRequired(const Light& l, const ReferenceFroxel& f) {
    constexpr double kMargin = 1e-3;
    if (l.type == LightType::Directional) return false;
    const bool limited = l.range > 0.0f;
    if (limited && distanceToFroxel(f, glm::dvec3(l.positionWs)) >= double(l.range) * (1.0 - kMargin)) return false;
    if (l.type == LightType::Point) return true;
    constexpr int n = 9;
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const double u = double(i) / (n - 1), v = double(j) / (n - 1), w = double(k) / (n - 1);
                glm::dvec3 p(0.0);
                for (int c = 0; c < 8; ++c)
                    p += f.cornersWs[size_t(c)] *
                        ((c & 1 ? u : 1.0 - u) * (c & 2 ? v : 1.0 - v) * (c & 4 ? w : 1.0 - w));
                if (insideLight(l, p, kMargin)) return true;
            }
    return false;
}

// The grid's lists as one vector of light indices per froxel.
inline std::vector<std::vector<uint32_t>> froxelLists(const ClusterGrid& grid) {
    std::vector<std::vector<uint32_t>> lists(grid.ranges.size());
    for (size_t i = 0; i < grid.ranges.size(); ++i) {
        const glm::uvec2 r = grid.ranges[i];
        lists[i].assign(grid.indices.begin() + r.x, grid.indices.begin() + r.x + r.y);
    }
    return lists;
}

// A depth beyond every light's reach, to close the last slice.
// Entries that are in one grid's list of a froxel and not in the other's, over all froxels.
inline size_t differingEntries(const ClusterGrid& a, const ClusterGrid& b) {
    const auto listsA = froxelLists(a);
    const auto listsB = froxelLists(b);
    size_t differing = 0;
    for (size_t i = 0; i < listsA.size() && i < listsB.size(); ++i) {
        std::vector<uint32_t> onlyOne;
        std::set_symmetric_difference(listsA[i].begin(), listsA[i].end(), listsB[i].begin(), listsB[i].end(),
                                      std::back_inserter(onlyOne));
        differing += onlyOne.size();
    }
    return differing;
}

// The view of the grid tests (160 x 120 pixels): from above and in front of the origin.
inline View clusterTestView(float widthPx, float heightPx) {
    const glm::mat4 worldFromView =
        glm::inverse(glm::lookAt(glm::vec3(0.3f, 1.0f, 4.0f), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f)));
    return perspectiveView(worldFromView, 0.8f, widthPx / heightPx, 0.2f, 12.0f);
}

inline double farEnough(const Eye& view, const std::vector<Light>& lights) {
    double farM = view.farM;
    for (const Light& l : lights) {
        const double depth = -(view.viewFromWorld * glm::vec4(l.positionWs, 1.0f)).z;
        farM = std::max(farM, depth + double(l.range) + 1.0);
    }
    return farM;
}

struct ConservativeCheck {
    size_t required = 0;              // (froxel, light) pairs that must be listed
    size_t listed = 0;                // entries in the lists
    size_t requiredPointEntries = 0;  // of those, point lights
    size_t listedPointEntries = 0;
    size_t missing = 0;   // required but not listed
    size_t badLists = 0;  // lists not strictly ascending, or holding a directional light
    std::string firstProblem;
};

// Does a point light's range sphere reach the box (its distance to the box at most the range)?
inline bool pointLightReaches(const Light& l, const Bounds& box) {
    const glm::dvec3 p(l.positionWs);
    const glm::dvec3 outside = glm::max(glm::max(glm::dvec3(box.min) - p, p - glm::dvec3(box.max)), glm::dvec3(0.0));
    return !(l.range > 0.0f) || glm::length(outside) <= double(l.range);
}

// Checks every froxel of `grid` (built from `lights`, whose list entries index `lights`), as
// seen from the grid's camera (grid.camera: for one eye the eye itself; whether a camera of
// several eyes holds every eye is checked separately, by the eyes' own points). With a box
// (`reach` not empty; point lights only), a light is required only where its range also reaches
// the box.
inline ConservativeCheck checkConservative(const ClusterGrid& grid, const std::vector<Light>& lights,
                                           const Bounds& reach = {}) {
    const Eye& view = grid.camera.eye;
    const ClusterGridShape& s = grid.shape;
    const double farM = farEnough(view, lights);
    const auto lists = froxelLists(grid);
    ConservativeCheck check;
    auto problem = [&](const std::string& text) {
        if (check.firstProblem.empty()) check.firstProblem = text;
    };
    for (uint32_t z = 0; z < s.dims.z; ++z)
        for (uint32_t y = 0; y < s.dims.y; ++y)
            for (uint32_t x = 0; x < s.dims.x; ++x) {
                std::ostringstream where;
                where << "froxel " << x << "," << y << "," << z;
                const std::vector<uint32_t>& list = lists[s.froxelIndex(x, y, z)];
                check.listed += list.size();
                for (size_t e = 0; e < list.size(); ++e) {
                    const bool ascending = e == 0 || list[e] > list[e - 1];
                    const bool local = list[e] < lights.size() && lights[list[e]].type != LightType::Directional;
                    if (!ascending || !local) {
                        ++check.badLists;
                        problem(where.str() + ": list not ascending or holding a directional light");
                        break;
                    }
                    if (lights[list[e]].type == LightType::Point) ++check.listedPointEntries;
                }
                const ReferenceFroxel f = referenceFroxel(s, view, x, y, z, farM);
                for (uint32_t i = 0; i < lights.size(); ++i) {
                    if (!lightRequired(lights[i], f)) continue;
                    if (!reach.empty() && !pointLightReaches(lights[i], reach)) continue;
                    ++check.required;
                    if (lights[i].type == LightType::Point) ++check.requiredPointEntries;
                    if (!std::binary_search(list.begin(), list.end(), i)) {
                        ++check.missing;
                        problem(where.str() + ": light " + std::to_string(i) + " touches it but is not listed");
                    }
                }
            }
    return check;
}

}  // namespace preskin::test
