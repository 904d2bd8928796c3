// The light grid bounded by where the frame's surfaces are (ClusterSurfaces): every point a
// fragment can have, sampled on the triangles (and, with MSAA, on their planes up to 0.7 pixels
// outside them, found by casting the pixel's ray at the plane), lies inside its froxel's depth
// interval and slab; every light whose volume holds such a point is in its froxel's list (the
// independent point test of test_cluster_reference.h); back faces of single-sided triangles that
// face no eye are left out; and the lists are shorter than without the surfaces.
#include "reference/test_cluster_reference.h"
#include "support/TestLights.h"
#include "support/TestScenes.h"

#include "lights/ClusterGeometry.h"
#include "lights/ClusterSurfaces.h"

#include <preskin/ClusterGrid.h>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include <random>

namespace preskin::test {
namespace {

constexpr uint32_t kWidth = 160;
constexpr uint32_t kHeight = 120;

View testView() { return clusterTestView(float(kWidth), float(kHeight)); }

ClusterSettings testSettings() {
    ClusterSettings s;
    s.tileSizePx = 8;
    s.depthSlices = 12;
    s.nearSliceM = 0.5f;
    return s;
}

// A sphere, a floor that runs under and behind the camera (clipped at the near plane), a wall
// seen almost edge-on, a box, and small triangles scattered at random (some facing away).
struct Surfaces {
    std::vector<glm::vec3> positions;
    std::vector<uint32_t> indices;
    std::vector<uint8_t> culled;  // per triangle

    void add(const Primitive& p, const glm::mat4& worldFromObject) {
        const auto base = static_cast<uint32_t>(positions.size());
        for (const Vertex& v : p.vertices)
            positions.push_back(glm::vec3(worldFromObject * glm::vec4(v.positionOs, 1.0f)));
        for (uint32_t i : p.indices) indices.push_back(base + i);
        culled.resize(indices.size() / 3, 1);
    }
    ClusterSurfaces view(float outsidePx) const { return ClusterSurfaces{positions, indices, culled, outsidePx}; }
};

Surfaces testSurfaces() {
    Surfaces s;
    s.add(makeSphere(0.5f, 24, 12), glm::translate(glm::mat4(1.0f), glm::vec3(-0.4f, 0.0f, 0.0f)));
    s.add(makeQuad(12.0f, 6),
          glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, -0.5f, 1.0f)) *
              glm::rotate(glm::mat4(1.0f), -1.5707963f, glm::vec3(1.0f, 0.0f, 0.0f)));
    // Nearly edge-on: a wall through the eye's column, turned 89 degrees from facing it.
    s.add(makeQuad(3.0f, 4),
          glm::translate(glm::mat4(1.0f), glm::vec3(0.9f, 0.4f, 0.2f)) *
              glm::rotate(glm::mat4(1.0f), 1.5533430f, glm::vec3(0.0f, 1.0f, 0.0f)));
    s.add(makeBox(glm::vec3(0.6f)), glm::translate(glm::mat4(1.0f), glm::vec3(0.7f, -0.2f, -1.2f)));
    std::mt19937 rng(5);
    Primitive bits;
    for (uint32_t i = 0; i < 150; ++i) {
        const glm::vec3 c(uniform(rng, -2.0f, 2.0f), uniform(rng, -0.5f, 1.5f), uniform(rng, -3.0f, 2.5f));
        for (int k = 0; k < 3; ++k) {
            Vertex v;
            v.positionOs =
                c + glm::vec3(uniform(rng, -0.08f, 0.08f), uniform(rng, -0.08f, 0.08f), uniform(rng, -0.08f, 0.08f));
            bits.indices.push_back(static_cast<uint32_t>(bits.vertices.size()));
            bits.vertices.push_back(v);
        }
    }
    s.add(bits, glm::mat4(1.0f));
    return s;
}

// Points a fragment can have: on each triangle facing the eye (random barycentric points) and, when
// outsidePx > 0, where the ray through a pixel up to outsidePx from such a point meets the
// triangle's plane. Only points in the view and beyond its near plane.
std::vector<glm::vec3> fragmentPoints(const Surfaces& s, const Eye& eye, float outsidePx, uint32_t perTriangle) {
    std::mt19937 rng(11);
    const glm::mat4 clipFromWorld = eye.clipFromWorld();
    const glm::mat4 worldFromClip = glm::inverse(clipFromWorld);
    std::vector<glm::vec3> points;
    for (size_t t = 0; t + 2 < s.indices.size(); t += 3) {
        const glm::vec3 a = s.positions[s.indices[t]], b = s.positions[s.indices[t + 1]],
                        c = s.positions[s.indices[t + 2]];
        const glm::vec3 n = glm::cross(b - a, c - a);
        if (glm::dot(n, eye.positionWs - a) < 0.0f) continue;  // a single-sided back face: never drawn
        for (uint32_t k = 0; k < perTriangle; ++k) {
            float u = uniform(rng, 0.0f, 1.0f), v = uniform(rng, 0.0f, 1.0f);
            if (u + v > 1.0f) {
                u = 1.0f - u;
                v = 1.0f - v;
            }
            glm::vec3 p = a + u * (b - a) + v * (c - a);
            if (outsidePx > 0.0f) {
                glm::vec4 clip = clipFromWorld * glm::vec4(p, 1.0f);
                if (!(clip.w > 0.0f)) continue;
                const float angle = uniform(rng, 0.0f, 6.2831853f), r = uniform(rng, 0.0f, outsidePx);
                glm::vec2 ndc = glm::vec2(clip) / clip.w;
                ndc += glm::vec2(std::cos(angle) / float(kWidth), std::sin(angle) / float(kHeight)) * (2.0f * r);
                const glm::vec4 far = worldFromClip * glm::vec4(ndc, 1.0f, 1.0f);
                const glm::vec3 dir = glm::vec3(far) / far.w - eye.positionWs;
                const float along = glm::dot(n, dir);
                if (std::abs(along) < 1e-12f) continue;
                const float hit = glm::dot(n, a - eye.positionWs) / along;
                if (!(hit > 0.0f)) continue;
                p = eye.positionWs + dir * hit;
            }
            const glm::vec4 clip = clipFromWorld * glm::vec4(p, 1.0f);
            const float depth = -(eye.viewFromWorld * glm::vec4(p, 1.0f)).z;
            if (!(clip.w > 0.0f) || depth < eye.nearM || std::abs(clip.x) > clip.w || std::abs(clip.y) > clip.w)
                continue;
            points.push_back(p);
        }
    }
    return points;
}

TEST(ClusterSurfaces, EveryPointAFragmentCanHaveLiesInItsFroxelsExtents) {
    const View view = testView();
    const Surfaces s = testSurfaces();
    const ClusterCamera camera = clusterCamera(view, kWidth, kHeight);
    Bounds bounds;
    for (const glm::vec3& p : s.positions) bounds.extend(p);
    ClusterGrid grid;  // for its froxel lookup
    grid.camera = camera;
    grid.shape = clusterGridShape(testSettings(), camera, bounds);
    const size_t tiles = size_t(grid.shape.dims.x) * grid.shape.dims.y;
    for (float outsidePx : {0.0f, 1.0f}) {
        FroxelSurfaces out;
        froxelSurfaces(grid.shape, camera, s.view(outsidePx), out);
        const std::vector<glm::vec3> points = fragmentPoints(s, view.eye(), outsidePx * 0.7f, 40);
        ASSERT_GT(points.size(), 3000u);
        size_t outsideDepth = 0, outsideSlab = 0, withSlab = 0;
        std::string first;
        for (const glm::vec3& p : points) {
            const glm::vec3 pv(view.eye().viewFromWorld * glm::vec4(p, 1.0f));
            const uint32_t f = grid.froxelAt(p);
            const glm::vec4& e = out.extent(f);
            const glm::vec4& axis = out.axis(f % tiles);
            const float depth = -pv.z;
            const float tolerance = 1e-6f * depth;
            if (!(depth >= e.x - tolerance && depth <= e.y + tolerance)) {
                ++outsideDepth;
                if (first.empty())
                    first = "depth " + std::to_string(depth) + " outside [" + std::to_string(e.x) + ", " +
                        std::to_string(e.y) + "]";
            }
            if (axis.w > 0.0f) {
                ++withSlab;
                const float along = glm::dot(glm::vec3(axis), pv);
                if (!(along >= e.z - tolerance && along <= e.w + tolerance)) ++outsideSlab;
            }
        }
        EXPECT_EQ(outsideDepth, 0u) << "outsidePx " << outsidePx << ": " << first;
        EXPECT_EQ(outsideSlab, 0u) << "outsidePx " << outsidePx;
        EXPECT_GT(withSlab, points.size() / 2);
        // And the extents bound something: without MSAA most occupied froxels hold a thin part of their slice.
        if (outsidePx == 0.0f) {
            size_t occupied = 0, thin = 0;
            for (uint32_t z = 0; z < grid.shape.dims.z; ++z)
                for (size_t t = 0; t < tiles; ++t) {
                    const glm::vec4& e = out.extent(z * tiles + t);
                    if (!(e.x <= e.y)) continue;
                    ++occupied;
                    const float slice = grid.shape.sliceStartM(z + 1) - grid.shape.sliceStartM(z);
                    thin += std::min(e.y, grid.shape.sliceStartM(z + 1)) - std::max(e.x, grid.shape.sliceStartM(z)) <
                            0.5f * slice
                        ? 1
                        : 0;
                }
            EXPECT_GT(occupied, 300u);
            EXPECT_GT(thin, occupied / 2) << thin << " of " << occupied;
            EXPECT_LT(occupied, size_t(grid.shape.froxelCount()) / 3);
        }
    }
}

TEST(ClusterSurfaces, BackFacesOfSingleSidedTrianglesFacingNoEyeHoldNothing) {
    const View view = testView();
    const ClusterCamera camera = clusterCamera(view, kWidth, kHeight);
    ClusterGridShape shape = clusterGridShape(testSettings(), camera, Bounds{});
    // A triangle in front of the camera, wound clockwise as the eye sees it, and its mirror.
    const glm::mat4 worldFromView = glm::inverse(view.eye().viewFromWorld);
    const auto at = [&](float x, float y) { return glm::vec3(worldFromView * glm::vec4(x, y, -2.0f, 1.0f)); };
    const std::vector<glm::vec3> positions{at(-0.3f, -0.3f), at(0.0f, 0.3f), at(0.3f, -0.3f)};
    for (const bool counterClockwise : {false, true})
        for (const uint8_t culled : {uint8_t(0), uint8_t(1)}) {
            const std::vector<uint32_t> indices =
                counterClockwise ? std::vector<uint32_t>{0, 2, 1} : std::vector<uint32_t>{0, 1, 2};
            const std::vector<uint8_t> flags{culled};
            FroxelSurfaces out;
            froxelSurfaces(shape, camera, ClusterSurfaces{positions, indices, flags, 0.0f}, out);
            size_t occupied = 0;
            for (size_t f = 0; f < out.froxels(); ++f) occupied += out.occupied(f) ? 1 : 0;
            if (culled && !counterClockwise)
                EXPECT_EQ(occupied, 0u) << "a culled back face";
            else
                EXPECT_GT(occupied, 10u) << "ccw " << counterClockwise << " culled " << int(culled);
        }
}

TEST(ClusterGrid, SurfaceBoundedListsHoldEveryLightReachingAPointOfTheSurfaces) {
    const View view = testView();
    const Surfaces s = testSurfaces();
    Bounds bounds;
    for (const glm::vec3& p : s.positions) bounds.extend(p);
    const std::vector<Light> lights = randomLights(900, 41, 4.6f);
    const ClusterSettings settings = testSettings();
    const ClusterGrid whole = buildClusterGrid(settings, view, kWidth, kHeight, bounds, lights);
    for (float outsidePx : {0.0f, 1.0f}) {
        const ClusterGrid grid = buildClusterGrid(settings, view, kWidth, kHeight, bounds, lights, s.view(outsidePx));
        // Lights whose volume misses the scene's box are listed nowhere (ClusterGridShape::lightBounds):
        // a point extrapolated past the box's edge is not this test's.
        std::vector<glm::vec3> points;
        for (const glm::vec3& p : fragmentPoints(s, view.eye(), outsidePx * 0.7f, 16))
            if (glm::all(glm::greaterThanEqual(p, bounds.min)) && glm::all(glm::lessThanEqual(p, bounds.max)))
                points.push_back(p);
        const auto lists = froxelLists(grid);
        size_t required = 0, missing = 0;
        std::string first;
        for (const glm::vec3& p : points) {
            const std::vector<uint32_t>& list = lists[grid.froxelAt(p)];
            for (uint32_t i = 0; i < lights.size(); ++i) {
                if (lights[i].type == LightType::Directional || !insideLight(lights[i], glm::dvec3(p), 1e-3)) continue;
                ++required;
                if (!std::binary_search(list.begin(), list.end(), i)) {
                    ++missing;
                    if (first.empty())
                        first =
                            "light " + std::to_string(i) + " at a point of froxel " + std::to_string(grid.froxelAt(p));
                }
            }
        }
        EXPECT_GT(required, 2000u);
        EXPECT_EQ(missing, 0u) << "outsidePx " << outsidePx << ": " << first;
        EXPECT_EQ(grid.overflowedClusters, 0u);
        // Froxels the surfaces miss list nothing, and the rest lists less.
        EXPECT_LT(double(grid.indices.size()), 0.5 * double(whole.indices.size()))
            << grid.indices.size() << " entries against " << whole.indices.size();
        std::printf("[ surfaces ] outsidePx %.0f: %zu entries against %zu for whole froxels; %zu light-point pairs\n",
                    double(outsidePx), grid.indices.size(), whole.indices.size(), required);
    }
}

}  // namespace
}  // namespace preskin::test
