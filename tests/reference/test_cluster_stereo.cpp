// One light grid for every eye of a view (clusterCamera, <preskin/ClusterGrid.h>):
//  - mono: the cluster camera is the eye itself;
//  - several eyes (parallel and canted, symmetric and asymmetric OpenXR-style angles, small and
//    large IPDs): the cluster camera's frustum holds each eye's whole frustum (the eight corners
//    of each eye's frustum between its near plane and a far depth project inside the cluster
//    camera's image and beyond its near plane; frusta are convex, so corners suffice), without
//    being much larger than the union;
//  - the point check per eye, independent of the grid code: points of each eye (pixel centres
//    of that eye through its own inverse projection, at depths from its near plane outwards)
//    are looked up as the forward shader looks them up (ClusterGrid::froxelAt), and every light
//    whose volume contains the point (range sphere, spot cone, with a small margin) must be in
//    that list. Lights sit on and just inside every eye's edge planes, inner and outer edges
//    alike, where a plane-by-plane frustum merge would lose them.
//  - the combined grid's own froxels are conservative (the reference of test_cluster_reference.h).
#include "reference/test_cluster_reference.h"
#include "support/TestLights.h"

#include <preskin/ClusterGrid.h>
#include <preskin/Error.h>
#include <preskin/View.h>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <random>
#include <string>

namespace preskin::test {
namespace {

constexpr uint32_t kWidth = 64;
constexpr uint32_t kHeight = 72;

// A head pose looking down -Z from `eye` towards `target`.
glm::mat4 headPose(const glm::vec3& eye, const glm::vec3& target) {
    return glm::inverse(glm::lookAt(eye, target, glm::vec3(0.0f, 1.0f, 0.0f)));
}

// HMD-like angles: the inner (nasal) side narrower than the outer one.
FovAngles hmdFov(bool left, float inner, float outer) {
    return left ? FovAngles{-outer, inner, 0.8f, -0.85f} : FovAngles{-inner, outer, 0.8f, -0.85f};
}

// A stereo view whose eyes are also turned outwards by `cantRad` about the head's up axis.
View cantedStereo(const glm::mat4& worldFromHead, float ipdM, float cantRad, float nearM) {
    View view = stereoView(worldFromHead, ipdM, hmdFov(true, 0.7f, 0.95f), hmdFov(false, 0.7f, 0.95f), nearM, 20.0f);
    for (uint32_t e = 0; e < 2; ++e) {
        const float angle = e == 0 ? cantRad : -cantRad;
        glm::mat4 worldFromEye = glm::inverse(view.eyes[e].viewFromWorld);
        worldFromEye = worldFromEye * glm::rotate(glm::mat4(1.0f), angle, glm::vec3(0.0f, 1.0f, 0.0f));
        view.eyes[e] = perspectiveEye(worldFromEye, fovOf(view.eyes[e]), nearM, 20.0f);
    }
    return view;
}

std::vector<std::pair<View, std::string>> stereoViews() {
    const glm::mat4 head = headPose(glm::vec3(0.2f, 0.4f, 2.0f), glm::vec3(0.0f, 0.1f, -1.0f));
    std::vector<std::pair<View, std::string>> views;
    views.emplace_back(stereoView(head, 0.064f, hmdFov(true, 0.75f, 0.9f), hmdFov(false, 0.75f, 0.9f), 0.05f, 20.0f),
                       "asymmetric, IPD 64 mm");
    views.emplace_back(stereoFromMono(perspectiveView(head, 0.9f, float(kWidth) / float(kHeight), 0.1f, 20.0f), 0.07f),
                       "symmetric from mono");
    views.emplace_back(cantedStereo(head, 0.064f, 0.17f, 0.05f), "canted 10 degrees");
    views.emplace_back(stereoView(head, 0.3f, hmdFov(true, 0.5f, 0.9f), hmdFov(false, 0.5f, 0.9f), 0.02f, 20.0f),
                       "wide IPD 30 cm");
    return views;
}

// The world point of eye pixel (px, py) (pixel edges at integers) at view depth d, through the
// eye's own inverse projection.
glm::dvec3 eyePoint(const Eye& eye, double px, double py, double depthM) {
    const glm::dmat4 clipFromView(eye.clipFromView);
    const glm::dvec4 clip = clipFromView * glm::dvec4(0.0, 0.0, -depthM, 1.0);
    glm::dvec4 v = glm::inverse(clipFromView) *
        glm::dvec4(px / kWidth * 2.0 - 1.0, py / kHeight * 2.0 - 1.0, clip.z / clip.w, 1.0);
    v /= v.w;
    return glm::dvec3(glm::inverse(glm::dmat4(eye.viewFromWorld)) * v);
}

// Does the light's volume contain p, with a margin (so float rounding at an exact touch never
// decides): inside 0.999 of the range and (spots) 1e-3 inside the outer cone in cosine.
bool lightContains(const Light& l, const glm::dvec3& p) {
    const glm::dvec3 d = p - glm::dvec3(l.positionWs);
    const double dist = glm::length(d);
    if (l.range > 0.0f && dist > 0.999 * double(l.range)) return false;
    if (l.type != LightType::Spot) return true;
    if (dist < 1e-9) return true;
    return glm::dot(d / dist, glm::normalize(glm::dvec3(l.directionWs))) > std::cos(double(l.outerConeAngle)) + 1e-3;
}

// Random lights plus lights at every eye's four edges (on the edge plane and just inside it,
// at several depths, small ranges), and spots along the edges.
std::vector<Light> edgeLights(const View& view, uint32_t seed) {
    std::vector<Light> lights = randomLights(150, seed, 2.4f);
    std::mt19937 rng(seed);
    for (const Eye& eye : view.eyes)
        for (int edge = 0; edge < 4; ++edge)
            for (double depth : {0.08, 0.3, 1.1, 3.5}) {
                const double along = uniform(rng, 0.0f, 1.0f);
                const double inset = uniform(rng, 0.0f, 1.5f);  // pixels inside the edge
                double px = edge == 0 ? inset : edge == 1 ? kWidth - inset : along * kWidth;
                double py = edge == 2 ? inset : edge == 3 ? kHeight - inset : along * kHeight;
                const glm::dvec3 p = eyePoint(eye, px, py, depth);
                lights.push_back(pointLight(glm::vec3(p), float(depth) * uniform(rng, 0.08f, 0.25f)));
                const glm::dvec3 q = eyePoint(eye, px, py, depth * 1.5);
                lights.push_back(spotLight(glm::vec3(p), glm::vec3(q - p), float(depth) * 0.6f, 0.05f));
            }
    return lights;
}

TEST(ClusterCamera, OfOneEyeIsThatEye) {
    const View view = perspectiveView(headPose(glm::vec3(0.0f, 0.5f, 2.0f), glm::vec3(0.0f)), 0.8f, 1.3f, 0.1f, 9.0f);
    const ClusterCamera camera = clusterCamera(view, kWidth, kHeight);
    EXPECT_EQ(camera.eye.viewFromWorld, view.eye().viewFromWorld);
    EXPECT_EQ(camera.eye.clipFromView, view.eye().clipFromView);
    EXPECT_EQ(camera.extentPx, glm::uvec2(kWidth, kHeight));
}

TEST(ClusterCamera, HoldsEveryEyesFrustumAndLittleMore) {
    for (const auto& [view, name] : stereoViews()) {
        const ClusterCamera camera = clusterCamera(view, kWidth, kHeight);
        const glm::dmat4 clusterClip(camera.eye.clipFromWorld());
        const glm::dmat4 clusterView(camera.eye.viewFromWorld);
        glm::dvec2 lo(1e9), hi(-1e9);
        for (uint32_t e = 0; e < view.eyeCount(); ++e)
            for (double depth : {double(view.eyes[e].nearM), 19.0})
                for (int c = 0; c < 4; ++c) {
                    const glm::dvec3 p = eyePoint(view.eyes[e], (c & 1) ? kWidth : 0.0, (c & 2) ? kHeight : 0.0, depth);
                    const glm::dvec4 clip = clusterClip * glm::dvec4(p, 1.0);
                    const glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
                    EXPECT_LE(std::abs(ndc.x), 1.0) << name << ", eye " << e << ", corner " << c << ", depth " << depth;
                    EXPECT_LE(std::abs(ndc.y), 1.0) << name << ", eye " << e << ", corner " << c << ", depth " << depth;
                    EXPECT_GE(-(clusterView * glm::dvec4(p, 1.0)).z, camera.eye.nearM) << name << ", eye " << e;
                    lo = glm::min(lo, ndc);
                    hi = glm::max(hi, ndc);
                }
        // Not much larger than the eyes together: the far corners span nearly the whole image.
        EXPECT_GT(hi.x - lo.x, 1.9) << name;
        EXPECT_GT(hi.y - lo.y, 1.9) << name;
        // Tiles keep the eyes' angular size: the image is at least an eye's, at most 3 eyes wide.
        EXPECT_GE(camera.extentPx.x, kWidth) << name;
        EXPECT_LE(camera.extentPx.x, 3 * kWidth) << name;
        EXPECT_GE(camera.extentPx.y, kHeight) << name;
    }
}

TEST(ClusterCamera, RefusesViewsItCannotHold) {
    EXPECT_THROW(clusterCamera(View{}, kWidth, kHeight), Error);
    const glm::mat4 head = headPose(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f));
    View opposite = stereoView(head, 0.06f, FovAngles{}, FovAngles{}, 0.05f, 10.0f);
    opposite.eyes[1] =
        perspectiveEye(head * glm::rotate(glm::mat4(1.0f), 3.14159f, glm::vec3(0, 1, 0)), FovAngles{}, 0.05f, 10.0f);
    EXPECT_THROW(clusterCamera(opposite, kWidth, kHeight), Error);
    Camera orthoCamera;
    orthoCamera.orthographic = true;
    View mixed = stereoView(head, 0.06f, FovAngles{}, FovAngles{}, 0.05f, 10.0f);
    mixed.eyes[1] = cameraView(orthoCamera, 1.0f, Bounds{}).eye();
    EXPECT_THROW(clusterCamera(mixed, kWidth, kHeight), Error);
}

TEST(ClusterGridStereo, EveryLightTouchingAPointOfEitherEyeIsListed) {
    ClusterSettings settings;
    settings.tileSizePx = 8;
    settings.depthSlices = 16;
    settings.nearSliceM = 0.1f;
    settings.fitDepthToScene = false;
    uint32_t seed = 40;
    for (const auto& [view, name] : stereoViews()) {
        const std::vector<Light> lights = edgeLights(view, ++seed);
        const ClusterGrid grid = buildClusterGrid(settings, view, kWidth, kHeight, Bounds{}, lights);
        ASSERT_EQ(grid.overflowedClusters, 0u) << name;
        const ConservativeCheck own = checkConservative(grid, lights);
        EXPECT_EQ(own.missing, 0u) << name << ": " << own.firstProblem;
        EXPECT_EQ(own.badLists, 0u) << name << ": " << own.firstProblem;

        const auto lists = froxelLists(grid);
        size_t touching = 0, missing = 0, edgeTouching = 0;
        std::string first;
        for (uint32_t e = 0; e < view.eyeCount(); ++e) {
            const Eye& eye = view.eyes[e];
            for (uint32_t py = 0; py < kHeight; py += 1)
                for (uint32_t px = 0; px < kWidth; px += (py % 7 == 0 || px < 3 || px + 4 > kWidth) ? 1 : 5)
                    for (int k = 0; k < 28; ++k) {
                        const double depth = double(eye.nearM) * std::pow(1.25, k + 0.37 * ((px + py) % 3));
                        const glm::dvec3 p = eyePoint(eye, px + 0.5, py + 0.5, depth);
                        const std::vector<uint32_t>& list = lists[grid.froxelAt(glm::vec3(p))];
                        for (uint32_t i = 1; i < lights.size(); ++i) {
                            if (!lightContains(lights[i], p)) continue;
                            ++touching;
                            if (i > 150) ++edgeTouching;
                            if (std::binary_search(list.begin(), list.end(), i)) continue;
                            if (++missing == 1)
                                first = "eye " + std::to_string(e) + " pixel " + std::to_string(px) + "," +
                                    std::to_string(py) + " depth " + std::to_string(depth) + ": light " +
                                    std::to_string(i);
                        }
                    }
        }
        EXPECT_EQ(missing, 0u) << name << ": " << first;
        EXPECT_GT(touching, 2000u) << name;      // the check saw lights
        EXPECT_GT(edgeTouching, 1000u) << name;  // including the edge lights
    }
}

}  // namespace
}  // namespace preskin::test
