// The CPU light grid (buildClusterGrid, <preskin/ClusterGrid.h>) against the independent reference
// of test_cluster_reference.h: every light whose volume touches a froxel is in its list, for
// random lights, lights straddling froxel edges and corners, lights at the near plane, behind the
// camera and beyond the last slice, spots pointing across clusters, unlimited lights, and
// perspective, off-centre and orthographic views. Also: the slice formula, the depth fit to the
// scene, the documented overflow rule for both caps, and more than 255 (and 4096) lights.
#include "reference/test_cluster_reference.h"
#include "support/TestLights.h"

#include <preskin/ClusterGrid.h>
#include <preskin/View.h>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <limits>
#include <random>
#include <string>

namespace preskin::test {
namespace {

constexpr uint32_t kWidth = 160;
constexpr uint32_t kHeight = 120;

View testView() { return clusterTestView(float(kWidth), float(kHeight)); }

ClusterSettings testSettings() {
    ClusterSettings s;
    s.tileSizePx = 16;
    s.depthSlices = 12;
    s.nearSliceM = 0.5f;
    s.fitDepthToScene = false;
    return s;
}

// One directional light first (never clustered), then `count` points and spots around and in
// the view, some behind the camera and beyond the far slices.
std::vector<Light> randomLights(uint32_t count, uint32_t seed) {
    return preskin::test::randomLights(count, seed, 4.6f);
}

// Every required light is listed; lists ascend, hold no directional light and no duplicates.
ConservativeCheck expectConservative(const ClusterGrid& grid, const std::vector<Light>& lights,
                                     const std::string& what) {
    const ConservativeCheck c = checkConservative(grid, lights);
    EXPECT_EQ(c.missing, 0u) << what << ": " << c.firstProblem;
    EXPECT_EQ(c.badLists, 0u) << what << ": " << c.firstProblem;
    return c;
}

TEST(ClusterGridShape, SliceFormulaMatchesSliceStarts) {
    const View view = testView();
    for (bool fit : {false, true}) {
        ClusterSettings settings = testSettings();
        settings.fitDepthToScene = fit;
        Bounds bounds;
        bounds.extend(glm::vec3(-1.0f, -1.0f, -1.5f));
        bounds.extend(glm::vec3(1.0f, 1.2f, 1.0f));
        const ClusterGridShape s = clusterGridShape(settings, clusterCamera(view, kWidth, kHeight), bounds);
        EXPECT_EQ(s.dims, glm::uvec3(10, 8, 12));
        EXPECT_EQ(s.sliceOf(s.nearM), 0u);
        EXPECT_EQ(s.sliceOf(1e6f), s.dims.z - 1);
        EXPECT_GE(s.logStartM, settings.nearSliceM);
        EXPECT_NEAR(s.sliceStartM(1), s.logStartM, 1e-5f * s.logStartM);
        EXPECT_TRUE(std::isinf(s.sliceStartM(s.dims.z)));
        for (uint32_t z = 1; z < s.dims.z; ++z) {
            const float d = s.sliceStartM(z);
            EXPECT_EQ(s.sliceOf(d * (1.0f + 1e-5f)), z) << "fit " << fit << " slice " << z;
            EXPECT_EQ(s.sliceOf(d * (1.0f - 1e-5f)), z - 1) << "fit " << fit << " slice " << z;
            // Logarithmic: every slice after the first has the same depth ratio.
            if (z + 1 < s.dims.z) {
                EXPECT_NEAR(s.sliceStartM(z + 1) / d, std::pow(s.logEndM / s.logStartM, 1.0f / float(s.dims.z - 1)),
                            1e-4f);
            }
        }
    }
    // A tile size that does not divide the image: the last tiles are partial.
    ClusterSettings odd = testSettings();
    odd.tileSizePx = 13;
    EXPECT_EQ(clusterGridShape(odd, clusterCamera(view, kWidth, kHeight), {}).dims, glm::uvec3(13, 10, 12));
}

TEST(ClusterGridShape, FitsTheSceneDepthRange) {
    const View view = testView();
    Bounds bounds;
    bounds.extend(glm::vec3(-0.5f, -0.5f, -0.5f));
    bounds.extend(glm::vec3(0.5f, 0.5f, 0.5f));
    float minDepth = 1e9f, maxDepth = 0.0f;
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 c((i & 1) ? 0.5f : -0.5f, (i & 2) ? 0.5f : -0.5f, (i & 4) ? 0.5f : -0.5f);
        const float d = -(view.eye().viewFromWorld * glm::vec4(c, 1.0f)).z;
        minDepth = std::min(minDepth, d);
        maxDepth = std::max(maxDepth, d);
    }
    ClusterSettings settings = testSettings();
    settings.fitDepthToScene = true;
    const ClusterGridShape fitted = clusterGridShape(settings, clusterCamera(view, kWidth, kHeight), bounds);
    EXPECT_NEAR(fitted.logStartM, minDepth, 1e-5f);
    EXPECT_NEAR(fitted.logEndM, maxDepth, 1e-5f);
    settings.fitDepthToScene = false;
    const ClusterGridShape unfitted = clusterGridShape(settings, clusterCamera(view, kWidth, kHeight), bounds);
    EXPECT_NEAR(unfitted.logStartM, settings.nearSliceM, 1e-6f);
    EXPECT_NEAR(unfitted.logEndM, view.eye().farM, 1e-5f);
    // Empty bounds: nothing to fit.
    settings.fitDepthToScene = true;
    EXPECT_NEAR(clusterGridShape(settings, clusterCamera(view, kWidth, kHeight), Bounds{}).logEndM, view.eye().farM,
                1e-5f);
}

// The automatic tile (ClusterSettings::tileSizePx = 0): the largest of 16, 8, 4 px that the median
// listed light spans 8 tiles in radius. Lights are placed by their radius in pixels, measured on
// the image (the world distance between two pixels at the light's depth), not by the rule's formula.
TEST(ClusterGridShape, AutomaticTileFollowsTheMedianLightsProjectedSize) {
    Bounds box;
    box.extend(glm::vec3(-3.0f));
    box.extend(glm::vec3(3.0f));
    ClusterSettings settings;  // the defaults: automatic tile, 32 slices, fitted to the box
    ASSERT_EQ(settings.tileSizePx, 0u);
    auto shapeFor = [&](uint32_t width, uint32_t height, const std::vector<std::pair<float, int>>& radiiPx) {
        const View view = clusterTestView(float(width), float(height));
        std::vector<Light> lights{shadowedDirectionalLight(glm::vec3(0.0f, -1.0f, 0.0f), 1.0f)};
        std::mt19937 rng(7);
        std::uniform_real_distribution<float> u(0.2f, 0.8f);
        std::uniform_real_distribution<float> depth(3.0f, 5.0f);
        for (const auto& [radiusPx, count] : radiiPx)
            for (int i = 0; i < count; ++i) {
                const float px = u(rng) * float(width);
                const float py = u(rng) * float(height);
                const float d = depth(rng);
                const glm::vec3 c = pointAtPixel(view.eye(), px, py, float(width), float(height), d);
                const glm::vec3 side = pointAtPixel(view.eye(), px + radiusPx, py, float(width), float(height), d);
                lights.push_back(pointLight(c, glm::length(side - c)));
            }
        return clusterGridShape(settings, clusterCamera(view, width, height), box, lights);
    };
    struct Case {
        std::vector<std::pair<float, int>> radiiPx;
        uint32_t tile;
    };
    const Case cases[] = {
        {{{200.0f, 40}}, 16},
        {{{130.0f, 40}}, 16},
        {{{120.0f, 40}}, 8},
        {{{70.0f, 40}}, 8},
        {{{60.0f, 40}}, 4},
        {{{10.0f, 40}}, 4},
        {{{40.0f, 51}, {200.0f, 50}}, 4},
        {{{40.0f, 49}, {200.0f, 52}}, 16},
        {{}, 16},
    };
    for (const Case& c : cases) {
        const ClusterGridShape s = shapeFor(1280, 720, c.radiiPx);
        const float first = c.radiiPx.empty() ? 0.0f : c.radiiPx.front().first;
        EXPECT_EQ(s.tileSizePx, c.tile) << "lights of " << first << " px first";
        EXPECT_EQ(s.dims.z, c.tile < 16 ? 16u : 32u);
        EXPECT_EQ(s.dims.x, (1280u + s.tileSizePx - 1) / s.tileSizePx);
    }
    // Lights listed nowhere (their sphere misses the scene's box) do not count: 200 small ones beyond it.
    {
        const View view = clusterTestView(1280.0f, 720.0f);
        std::vector<Light> lights;
        for (int i = 0; i < 40; ++i) lights.push_back(pointLight(glm::vec3(0.01f * float(i), 0.0f, 0.0f), 1.0f));
        for (int i = 0; i < 200; ++i) lights.push_back(pointLight(glm::vec3(0.01f * float(i), 0.0f, -6.0f), 0.01f));
        EXPECT_EQ(clusterGridShape(settings, clusterCamera(view, 1280, 720), box, lights).tileSizePx, 16u);
        // Lights at a NaN position light nothing and do not count either.
        std::vector<Light> withNan = lights;
        for (int i = 0; i < 200; ++i)
            withNan.push_back(pointLight(glm::vec3(std::numeric_limits<float>::quiet_NaN()), 0.01f));
        EXPECT_EQ(clusterGridShape(settings, clusterCamera(view, 1280, 720), box, withNan).tileSizePx, 16u);
        // Unlimited lights are as large as can be.
        for (Light& l : lights) l.range = 0.0f;
        EXPECT_EQ(clusterGridShape(settings, clusterCamera(view, 1280, 720), box, lights).tileSizePx, 16u);
    }
    // At most 2^20 froxels: 4 px tiles at 1920 x 1080 would be 480 x 270 x 16 = 2.07 M.
    const ClusterGridShape large = shapeFor(1920, 1080, {{10.0f, 40}});
    EXPECT_EQ(large.tileSizePx, 8u);
    EXPECT_LE(large.froxelCount(), 1u << 20);
    // A tile that is set is kept.
    settings.tileSizePx = 24;
    EXPECT_EQ(shapeFor(1280, 720, {{10.0f, 40}}).tileSizePx, 24u);
}

// With the automatic tile the lists stay complete: small lights (4 px tiles) against the reference.
TEST(ClusterGrid, AutomaticTileListsEveryTouchingLight) {
    const View view = testView();
    ClusterSettings settings;
    settings.fitDepthToScene = false;
    std::vector<Light> lights{shadowedDirectionalLight(glm::vec3(0.0f, -1.0f, 0.0f), 1.0f)};
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int i = 0; i < 300; ++i) {
        const glm::vec3 c = pointAtPixel(view.eye(), u(rng) * float(kWidth), u(rng) * float(kHeight), float(kWidth),
                                         float(kHeight), 2.0f + 4.0f * u(rng));
        lights.push_back(pointLight(c, 0.05f + 0.1f * u(rng)));
    }
    const ClusterGrid grid = buildClusterGrid(settings, view, kWidth, kHeight, {}, lights);
    EXPECT_EQ(grid.shape.tileSizePx, 4u);
    expectConservative(grid, lights, "automatic tile");
}

TEST(ClusterGrid, EveryTouchingLightIsListed) {
    const View view = testView();
    for (uint32_t seed : {1u, 2u, 3u}) {
        const std::vector<Light> lights = randomLights(260, seed);
        const ClusterGrid grid = buildClusterGrid(testSettings(), view, kWidth, kHeight, {}, lights);
        EXPECT_EQ(grid.overflowedClusters, 0u);
        const ConservativeCheck c = expectConservative(grid, lights, "random seed " + std::to_string(seed));
        EXPECT_GT(c.required, 2000u) << "the scenario should exercise many froxels";
        // Not only conservative but tight: point lights are listed in few froxels they miss.
        EXPECT_LE(double(c.listedPointEntries), 1.5 * double(c.requiredPointEntries));
    }
}

TEST(ClusterGrid, LightsStraddlingFroxelEdgesAndCorners) {
    const View view = testView();
    const ClusterSettings settings = testSettings();
    const ClusterGridShape s = clusterGridShape(settings, clusterCamera(view, kWidth, kHeight), {});
    const glm::mat4 worldFromView = glm::inverse(view.eye().viewFromWorld);
    auto edgePoint = [&](float px, float py, float d) {
        return pointAtPixel(view.eye(), px, py, float(kWidth), float(kHeight), d);
    };
    std::vector<Light> lights;
    std::mt19937 rng(7);
    for (uint32_t z = 1; z < s.dims.z; ++z)
        for (uint32_t y = 1; y < s.dims.y; y += 2)
            for (uint32_t x = 1; x < s.dims.x; x += 3) {
                const float d = s.sliceStartM(z);
                const glm::vec3 corner = edgePoint(float(x * s.tileSizePx), float(y * s.tileSizePx), d);
                const float tile = d * 0.02f;  // about a tile at this depth
                // On the corner, on an edge, and just off a face.
                lights.push_back(pointLight(corner, tile * uniform(rng, 0.05f, 0.6f)));
                lights.push_back(pointLight(edgePoint(float(x * s.tileSizePx) + 5.0f, float(y * s.tileSizePx), d),
                                            tile * uniform(rng, 0.05f, 0.6f)));
                lights.push_back(
                    pointLight(edgePoint(float(x * s.tileSizePx) + 0.5f, float(y * s.tileSizePx) + 6.0f, d * 1.002f),
                               tile * 0.1f));
                // Spots aimed across the corner, along the tile diagonal and into the depth.
                const glm::vec3 across =
                    edgePoint(float((x + 1) * s.tileSizePx), float((y + 1) * s.tileSizePx), d * 1.05f);
                lights.push_back(spotLight(corner - (across - corner), across - corner,
                                           3.0f * glm::length(across - corner), uniform(rng, 0.05f, 0.4f)));
                lights.push_back(spotLight(corner, glm::vec3(worldFromView * glm::vec4(0, 0, -1, 0)), 4.0f * tile,
                                           uniform(rng, 0.05f, 0.3f)));
            }
    const ClusterGrid grid = buildClusterGrid(settings, view, kWidth, kHeight, {}, lights);
    const ConservativeCheck c = expectConservative(grid, lights, "straddling");
    EXPECT_GT(c.required, lights.size()) << "straddling lights touch several froxels each";
}

TEST(ClusterGrid, NearPlaneBehindTheCameraBeyondTheLastSliceAndUnlimited) {
    const View view = testView();
    const glm::mat4 worldFromView = glm::inverse(view.eye().viewFromWorld);
    auto at = [&](float x, float y, float depth) { return glm::vec3(worldFromView * glm::vec4(x, y, -depth, 1.0f)); };
    const glm::vec3 forward(worldFromView * glm::vec4(0, 0, -1, 0));
    std::vector<Light> lights = {
        pointLight(at(0.0f, 0.0f, 0.25f), 0.1f),                // just past the near plane (0.2)
        pointLight(at(0.05f, 0.0f, 0.15f), 0.1f),               // centre before the near plane, reaching past it
        pointLight(at(0.0f, 0.05f, -0.3f), 0.55f),              // behind the camera, reaching in
        pointLight(at(0.0f, 0.0f, -0.3f), 0.45f),               // behind the camera, not reaching the near plane
        pointLight(at(0.1f, -0.1f, 11.5f), 1.0f),               // straddling the far distance
        pointLight(at(0.0f, 0.0f, 30.0f), 5.0f),                // beyond it: the last slice only
        spotLight(at(0.0f, 0.0f, -0.5f), forward, 3.0f, 0.3f),  // behind, shining in
        spotLight(at(0.0f, 0.0f, 0.4f), -forward, 3.0f, 0.3f),  // in front, shining back at the camera
        spotLight(at(0.3f, 0.2f, 2.0f), forward, 0.0f, 0.25f),  // unlimited spot
        pointLight(at(0.0f, 0.0f, 5.0f), 0.0f),                 // unlimited point: every froxel
    };
    const ClusterGrid grid = buildClusterGrid(testSettings(), view, kWidth, kHeight, {}, lights);
    expectConservative(grid, lights, "near/far");
    // The unlimited point light is in every froxel; the light that stays behind the camera in none.
    const auto lists = froxelLists(grid);
    size_t withUnlimited = 0, withHidden = 0;
    for (const auto& list : lists) {
        withUnlimited += std::count(list.begin(), list.end(), 9u);
        withHidden += std::count(list.begin(), list.end(), 3u);
    }
    EXPECT_EQ(withUnlimited, lists.size());
    EXPECT_EQ(withHidden, 0u);
}

TEST(ClusterGrid, OffCentreAndOrthographicViews) {
    View offCentre = testView();
    offCentre.eye().clipFromView[2][0] = 0.35f;  // a shifted (off-axis) frustum
    offCentre.eye().clipFromView[2][1] = -0.2f;
    Camera orthoCamera;
    orthoCamera.orthographic = true;
    orthoCamera.xmag = 2.5f;
    orthoCamera.ymag = 2.0f;
    orthoCamera.znear = 0.2f;
    orthoCamera.zfar = 12.0f;
    orthoCamera.worldFromView =
        glm::inverse(glm::lookAt(glm::vec3(0.3f, 1.0f, 4.0f), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f)));
    const View ortho = cameraView(orthoCamera, float(kWidth) / float(kHeight), Bounds{});
    for (const auto& [view, name] : {std::pair<View, const char*>{offCentre, "off-centre"}, {ortho, "orthographic"}}) {
        const std::vector<Light> lights = randomLights(200, 11);
        const ClusterGrid grid = buildClusterGrid(testSettings(), view, kWidth, kHeight, {}, lights);
        const ConservativeCheck c = expectConservative(grid, lights, name);
        EXPECT_GT(c.required, 1000u) << name;
    }
}

TEST(ClusterGrid, PerClusterOverflowKeepsTheLowestIndices) {
    const View view = testView();
    const std::vector<Light> lights = randomLights(400, 5);
    const ClusterGrid full = buildClusterGrid(testSettings(), view, kWidth, kHeight, {}, lights);
    ClusterSettings capped = testSettings();
    capped.maxLightsPerCluster = 3;
    const ClusterGrid grid = buildClusterGrid(capped, view, kWidth, kHeight, {}, lights);
    const auto fullLists = froxelLists(full);
    const auto lists = froxelLists(grid);
    uint32_t expectedOverflows = 0;
    for (size_t i = 0; i < lists.size(); ++i) {
        const size_t keep = std::min<size_t>(fullLists[i].size(), 3);
        expectedOverflows += fullLists[i].size() > 3 ? 1 : 0;
        ASSERT_EQ(lists[i].size(), keep) << "froxel " << i;
        EXPECT_TRUE(std::equal(lists[i].begin(), lists[i].end(), fullLists[i].begin())) << "froxel " << i;
    }
    EXPECT_GT(expectedOverflows, 10u) << "the scenario should overflow";
    EXPECT_EQ(grid.overflowedClusters, expectedOverflows);
    EXPECT_EQ(grid.requestedIndices, full.indices.size());
}

TEST(ClusterGrid, IndexListOverflowTruncatesInFroxelOrder) {
    const View view = testView();
    const std::vector<Light> lights = randomLights(400, 6);
    const ClusterGrid full = buildClusterGrid(testSettings(), view, kWidth, kHeight, {}, lights);
    ASSERT_GT(full.indices.size(), 1000u);
    for (uint32_t perCluster : {256u, 5u}) {
        ClusterSettings capped = testSettings();
        capped.maxLightsPerCluster = perCluster;
        capped.maxLightIndices = static_cast<uint32_t>(full.indices.size() / 2);
        const ClusterGrid grid = buildClusterGrid(capped, view, kWidth, kHeight, {}, lights);
        const auto fullLists = froxelLists(full);
        const auto lists = froxelLists(grid);
        uint64_t running = 0;
        uint32_t expectedOverflows = 0;
        for (size_t i = 0; i < lists.size(); ++i) {
            const uint64_t room = capped.maxLightIndices - running;
            const size_t keep = static_cast<size_t>(std::min<uint64_t>({fullLists[i].size(), perCluster, room}));
            expectedOverflows += keep < fullLists[i].size() ? 1 : 0;
            running += keep;
            ASSERT_EQ(lists[i].size(), keep) << "froxel " << i << ", cap " << perCluster;
            EXPECT_TRUE(std::equal(lists[i].begin(), lists[i].end(), fullLists[i].begin()));
        }
        EXPECT_EQ(grid.indices.size(), capped.maxLightIndices);
        EXPECT_EQ(grid.overflowedClusters, expectedOverflows);
        EXPECT_EQ(grid.ranges.back().y, 0u) << "the last froxels lose out first";
    }
}

TEST(ClusterGrid, MoreThan255LightsPerClusterAnd4096PerView) {
    const View view = testView();
    std::vector<Light> lights = randomLights(4700, 8);
    // 300 lights around one point in view, all reaching it.
    const glm::vec3 target = glm::vec3(glm::inverse(view.eye().viewFromWorld) * glm::vec4(0.05f, 0.02f, -3.0f, 1.0f));
    std::mt19937 rng(9);
    for (int i = 0; i < 300; ++i) lights.push_back(pointLight(target + randomDirection(rng) * 0.2f, 0.5f));
    ClusterSettings settings = testSettings();
    settings.maxLightsPerCluster = 1024;
    const ClusterGrid grid = buildClusterGrid(settings, view, kWidth, kHeight, {}, lights);
    EXPECT_EQ(grid.overflowedClusters, 0u);
    const ClusterGridShape& s = grid.shape;
    const glm::vec4 clip = view.eye().clipFromWorld() * glm::vec4(target, 1.0f);
    const glm::vec2 pixel = (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * glm::vec2(kWidth, kHeight);
    const uint32_t froxel =
        s.froxelIndex(uint32_t(pixel.x) / s.tileSizePx, uint32_t(pixel.y) / s.tileSizePx, s.sliceOf(3.0f));
    const auto lists = froxelLists(grid);
    const std::vector<uint32_t>& list = lists[froxel];
    EXPECT_GE(list.size(), 300u);
    size_t clustered = 0;
    for (uint32_t i = 4701; i < lights.size(); ++i)
        clustered += std::binary_search(list.begin(), list.end(), i) ? 1 : 0;
    EXPECT_EQ(clustered, 300u) << "every light index above 4096 kept";
}

}  // namespace
}  // namespace preskin::test
