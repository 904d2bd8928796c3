// The light grid on lavapipe: the compute build (shaders/cluster_build.comp) against the CPU build
// and the independent reference of tests/reference/test_cluster_reference.h, its overflow rule, and
// whole frames: clustered renders (CPU and compute builds) agree with brute force (every light)
// within 1/255 for standard and skin materials, with lights straddling froxel edges, at the near
// plane and beyond the far slices, and spots aimed across clusters; the light-count debug view
// reports each pixel's list length.
#include <preskin/LightRecord.h>
#include "reference/test_cluster_reference.h"
#include "support/GpuTest.h"
#include "support/ImageCompare.h"
#include "support/TestLights.h"
#include "support/TestScenes.h"

#include "lights/ClusterBuilder.h"
#include "shared/cluster_build.h"
#include "shared/gpu_types.h"

#include <preskin/ClusterGrid.h>
#include <preskin/LutSet.h>
#include <preskin/Renderer.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <random>

namespace preskin::test {
namespace {

constexpr uint32_t kWidth = 160;
constexpr uint32_t kHeight = 120;

View testView() {
    const glm::mat4 worldFromView = glm::inverse(
        glm::lookAt(glm::vec3(0.4f, 1.2f, 3.2f), glm::vec3(0.0f, 0.1f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f)));
    return perspectiveView(worldFromView, 0.9f, float(kWidth) / float(kHeight), 0.3f, 12.0f);
}

// Lists from the renderer's builder for `lights` (directional ones first, as the renderer orders them);
// `before`: a view the same builder built lists for first (on the CPU), as a moving camera does.
ClusterGrid buildLists(Context& context, ClusterSettings settings, ClusterBuild build, const View& view,
                       const std::vector<Light>& lights, const Bounds& sceneBounds = {},
                       const ClusterSurfaces& surfaces = {}, const View* before = nullptr,
                       uint32_t blockListLimit = 0xffffffffu) {
    const vk::Device& device = ContextAccess::core(context);
    std::vector<gpu::GpuLight> gpuLights;
    std::vector<ClusterLight> gridLights;
    uint32_t firstLocal = 0;
    for (const Light& l : lights) {
        // The renderer's own conversions.
        if (l.type == LightType::Directional)
            ++firstLocal;
        else
            gridLights.push_back(clusterLight(l, static_cast<uint32_t>(gpuLights.size())));
        gpuLights.push_back(toGpuLight(l, false));
    }
    vk::Buffer lightBuffer(device, std::max<size_t>(gpuLights.size(), 1) * sizeof(gpu::GpuLight),
                           VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
    lightBuffer.upload(gpuLights.data(), gpuLights.size() * sizeof(gpu::GpuLight));
    ClusterBuilder builder(device);
    builder.limitBlockList(blockListLimit);
    if (before) {
        settings.build = ClusterBuild::Cpu;
        builder.prepare(0, settings, clusterCamera(*before, kWidth, kHeight), sceneBounds, gridLights, firstLocal,
                        lightBuffer, surfaces);
        device.submitAndWait([&](VkCommandBuffer cmd) { builder.record(cmd, 0); });
    }
    settings.build = build;
    const ClusterBuilder::FrameGrid frame = builder.prepare(0, settings, clusterCamera(view, kWidth, kHeight),
                                                            sceneBounds, gridLights, firstLocal, lightBuffer, surfaces);
    device.submitAndWait([&](VkCommandBuffer cmd) { builder.record(cmd, 0); });
    EXPECT_EQ(builder.usesGpu(0), build == ClusterBuild::Gpu);
    ClusterGrid grid = builder.readBack(0);
    EXPECT_EQ(glm::uvec3(frame.dims), grid.shape.dims);
    EXPECT_EQ(frame.lookupScale, grid.shape.lookupScale());
    return grid;
}

std::vector<Light> randomLights(uint32_t count, uint32_t seed) {
    return preskin::test::randomLights(count, seed, 3.8f);
}

ClusterSettings gridSettings() {
    ClusterSettings s;
    s.tileSizePx = 16;
    s.depthSlices = 12;
    s.nearSliceM = 0.6f;
    s.fitDepthToScene = false;
    return s;
}

class ClusterBuildGpu : public GpuTest {};

TEST_F(ClusterBuildGpu, ComputeBuildMatchesCpuBuildAndReference) {
    const View view = testView();
    for (uint32_t seed : {21u, 22u}) {
        const std::vector<Light> lights = randomLights(300, seed);
        const ClusterGrid cpu = buildLists(context(), gridSettings(), ClusterBuild::Cpu, view, lights);
        const ClusterGrid gpu = buildLists(context(), gridSettings(), ClusterBuild::Gpu, view, lights);
        ASSERT_EQ(gpu.ranges.size(), cpu.ranges.size());
        EXPECT_EQ(gpu.overflowedClusters, 0u);
        EXPECT_EQ(gpu.requestedIndices, cpu.requestedIndices);
        const size_t differing = differingEntries(cpu, gpu);
        // Both builds run the same tests; float rounding may differ only where a light grazes a froxel.
        EXPECT_LE(double(differing), 1e-3 * double(cpu.indices.size()))
            << differing << " of " << cpu.indices.size() << " entries differ";
        const ConservativeCheck c = checkConservative(gpu, lights);
        EXPECT_EQ(c.missing, 0u) << c.firstProblem;
        EXPECT_EQ(c.badLists, 0u) << c.firstProblem;
        EXPECT_GT(c.required, 2000u);
    }
}

// With fitDepthToScene a light whose range reaches no part of the scene's box lights nothing and
// is listed nowhere, by either build; every light that reaches the box is still listed wherever
// it touches a froxel (the independent reference, restricted to lights reaching the box).
TEST_F(ClusterBuildGpu, LightsThatCannotReachTheSceneAreListedNowhere) {
    const View view = testView();
    std::vector<Light> lights;
    for (const Light& l : randomLights(600, 24))
        if (l.type == LightType::Point) lights.push_back(l);
    Bounds box;
    box.extend(glm::vec3(-1.2f, -0.6f, -1.0f));
    box.extend(glm::vec3(1.0f, 1.0f, 0.8f));
    size_t reaching = 0;
    for (const Light& l : lights) reaching += pointLightReaches(l, box) ? 1 : 0;
    ASSERT_GT(reaching, 20u);
    ASSERT_LT(reaching, lights.size() / 2);
    ClusterSettings settings = gridSettings();
    settings.fitDepthToScene = true;
    for (ClusterBuild build : {ClusterBuild::Cpu, ClusterBuild::Gpu}) {
        const ClusterGrid grid = buildLists(context(), settings, build, view, lights, box);
        size_t unreachableEntries = 0;
        for (uint32_t index : grid.indices) unreachableEntries += pointLightReaches(lights[index], box) ? 0 : 1;
        EXPECT_EQ(unreachableEntries, 0u) << (build == ClusterBuild::Cpu ? "CPU" : "GPU") << " build";
        const ConservativeCheck c = checkConservative(grid, lights, box);
        EXPECT_EQ(c.missing, 0u) << c.firstProblem;
        EXPECT_EQ(c.badLists, 0u) << c.firstProblem;
        EXPECT_GT(c.required, 500u);
        std::printf("[ clusters ] %s build: %zu of %zu lights reach the box; %zu entries, none of the others\n",
                    build == ClusterBuild::Cpu ? "CPU" : "GPU", reaching, lights.size(), grid.indices.size());
    }
    // Without the fit every light in view is listed, the unreachable ones too.
    const ClusterGrid all = buildLists(context(), gridSettings(), ClusterBuild::Cpu, view, lights, box);
    size_t unreachableEntries = 0;
    for (uint32_t index : all.indices) unreachableEntries += pointLightReaches(lights[index], box) ? 0 : 1;
    EXPECT_GT(unreachableEntries, 100u);
}

TEST_F(ClusterBuildGpu, ComputeBuildOverflowRule) {
    const View view = testView();
    const std::vector<Light> lights = randomLights(400, 23);
    const ClusterGrid full = buildLists(context(), gridSettings(), ClusterBuild::Gpu, view, lights);
    const auto fullLists = froxelLists(full);

    // Per-froxel cap: the lowest indices.
    ClusterSettings capped = gridSettings();
    capped.maxLightsPerCluster = 3;
    const ClusterGrid perCluster = buildLists(context(), capped, ClusterBuild::Gpu, view, lights);
    const auto lists = froxelLists(perCluster);
    uint32_t expected = 0;
    for (size_t i = 0; i < lists.size(); ++i) {
        ASSERT_EQ(lists[i].size(), std::min<size_t>(fullLists[i].size(), 3)) << "froxel " << i;
        EXPECT_TRUE(std::equal(lists[i].begin(), lists[i].end(), fullLists[i].begin())) << "froxel " << i;
        expected += fullLists[i].size() > 3 ? 1 : 0;
    }
    EXPECT_GT(expected, 10u);
    EXPECT_EQ(perCluster.overflowedClusters, expected);

    // Index list capacity: every list a prefix of its full list, the space filled exactly.
    ClusterSettings small = gridSettings();
    small.maxLightIndices = static_cast<uint32_t>(full.indices.size() / 3);
    const ClusterGrid limited = buildLists(context(), small, ClusterBuild::Gpu, view, lights);
    const auto limitedLists = froxelLists(limited);
    uint64_t total = 0;
    uint32_t shortened = 0;
    for (size_t i = 0; i < limitedLists.size(); ++i) {
        ASSERT_LE(limitedLists[i].size(), fullLists[i].size());
        EXPECT_TRUE(std::equal(limitedLists[i].begin(), limitedLists[i].end(), fullLists[i].begin())) << "froxel " << i;
        EXPECT_LE(uint64_t(limited.ranges[i].x) + limited.ranges[i].y, small.maxLightIndices);
        total += limitedLists[i].size();
        shortened += limitedLists[i].size() < fullLists[i].size() ? 1 : 0;
    }
    EXPECT_EQ(total, small.maxLightIndices);
    EXPECT_EQ(limited.overflowedClusters, shortened);
    EXPECT_GT(shortened, 0u);
}

// A floor, a back wall, a sphere and a box spanning the grid's depth.
Scene testScene(bool skin) {
    Material m;
    m.baseColorFactor = glm::vec4(0.8f, 0.7f, 0.6f, 1.0f);
    m.metallicFactor = 0.0f;
    m.roughnessFactor = 0.5f;
    if (skin) m.skin = SkinMaterial{};
    const glm::mat4 floor = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, -0.5f, -1.0f)) *
        glm::rotate(glm::mat4(1.0f), -1.5707963f, glm::vec3(1.0f, 0.0f, 0.0f));
    const glm::mat4 wall = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 1.0f, -3.5f));
    Scene scene =
        makeScene({{makeQuad(7.0f, 16), floor},
                   {makeQuad(7.0f, 16), wall},
                   {makeSphere(0.5f, 48, 24), glm::translate(glm::mat4(1.0f), glm::vec3(-0.4f, 0.0f, 0.0f))},
                   {makeBox(glm::vec3(0.6f)), glm::translate(glm::mat4(1.0f), glm::vec3(0.7f, -0.2f, -1.2f))}},
                  {m});
    for (Mesh& mesh : scene.meshes)
        for (Primitive& p : mesh.primitives) p.material = 0;
    return scene;
}

// Bright lights: random ones in the scene, ones centred on froxel corners and edges, ones at the
// near plane, and spots aimed across clusters.
std::vector<Light> frameLights(const Scene& scene, const View& view, const ClusterSettings& settings) {
    std::mt19937 rng(31);
    std::vector<Light> lights(1);
    lights[0].type = LightType::Directional;
    lights[0].directionWs = glm::normalize(glm::vec3(0.3f, -1.0f, -0.4f));
    lights[0].intensity = 0.3f;
    lights[0].castsShadow = true;
    for (int i = 0; i < 120; ++i) {
        const glm::vec3 p(uniform(rng, -2.5f, 2.5f), uniform(rng, -0.45f, 2.0f), uniform(rng, -3.4f, 1.5f));
        const glm::vec3 color(uniform(rng, 0.2f, 1.0f), uniform(rng, 0.2f, 1.0f), uniform(rng, 0.2f, 1.0f));
        if (i % 3 == 2)
            lights.push_back(
                spotLight(p, randomDirection(rng), uniform(rng, 0.4f, 2.0f), uniform(rng, 0.2f, 1.2f), 3.0f));
        else
            lights.push_back(pointLight(p, uniform(rng, 0.2f, 0.9f), color, 2.0f));
    }
    const ClusterGridShape s = clusterGridShape(settings, clusterCamera(view, kWidth, kHeight), scene.worldBounds());
    auto edgePoint = [&](float px, float py, float d) {
        return pointAtPixel(view.eye(), px, py, float(kWidth), float(kHeight), d);
    };
    for (uint32_t z = 1; z < s.dims.z; z += 2)
        for (uint32_t y = 1; y < s.dims.y; y += 3)
            for (uint32_t x = 1; x < s.dims.x; x += 3) {
                const float d = s.sliceStartM(z);
                const glm::vec3 corner = edgePoint(float(x * s.tileSizePx), float(y * s.tileSizePx), d);
                lights.push_back(pointLight(corner, d * uniform(rng, 0.03f, 0.15f), glm::vec3(1.0f, 0.6f, 0.3f), 4.0f));
                const glm::vec3 next =
                    edgePoint(float((x + 1) * s.tileSizePx), float((y + 1) * s.tileSizePx), d * 1.1f);
                lights.push_back(spotLight(corner, next - corner, 6.0f * glm::length(next - corner), 0.25f, 6.0f));
            }
    // Lights on the floor and the wall where tile edges meet them: they light surfaces on both
    // sides of tile and slice boundaries, so a list missing them shows in the image.
    const glm::vec3 eye = view.eye().positionWs;
    for (uint32_t py = 4; py < kHeight; py += 9)
        for (uint32_t tx = 1; tx < s.dims.x; tx += 2) {
            const glm::vec3 dir = glm::normalize(edgePoint(float(tx * s.tileSizePx), float(py), 1.0f) - eye);
            float t = dir.y < 0.0f ? (-0.5f - eye.y) / dir.y : 1e9f;  // floor y = -0.5
            glm::vec3 normal(0.0f, 1.0f, 0.0f);
            const float tWall = dir.z < 0.0f ? (-3.5f - eye.z) / dir.z : 1e9f;  // wall z = -3.5
            if (tWall < t) {
                t = tWall;
                normal = glm::vec3(0.0f, 0.0f, 1.0f);
            }
            if (t > 100.0f) continue;
            const glm::vec3 color(uniform(rng, 0.3f, 1.0f), uniform(rng, 0.3f, 1.0f), uniform(rng, 0.3f, 1.0f));
            lights.push_back(pointLight(eye + dir * t + normal * 0.03f, uniform(rng, 0.25f, 0.5f), color, 0.3f));
        }
    const glm::mat4 worldFromView = glm::inverse(view.eye().viewFromWorld);
    const glm::vec3 forward(worldFromView * glm::vec4(0, 0, -1, 0));
    lights.push_back(
        pointLight(glm::vec3(worldFromView * glm::vec4(0.1f, -0.1f, -0.35f, 1.0f)), 2.5f, glm::vec3(1.0f), 0.5f));
    lights.push_back(
        spotLight(glm::vec3(worldFromView * glm::vec4(0.0f, 0.0f, 0.5f, 1.0f)), forward, 6.0f, 0.2f, 4.0f));
    return lights;
}

struct Frames {
    RenderedImage brute, clusteredCpu, clusteredGpu, starved;
};

Frames renderFrames(Context& context, bool skin, uint32_t msaaSamples = 1) {
    const Scene scene = testScene(skin);
    const View view = testView();
    static const LutSet luts = LutSet::load(std::filesystem::path(PRESKIN_SOURCE_DIR) / "luts");
    RenderSettings settings;
    settings.clusters.tileSizePx = 16;
    settings.clusters.depthSlices = 16;
    settings.msaaSamples = msaaSamples;
    Renderer renderer(context, scene, Environment::constant(glm::vec3(0.05f)), &luts, settings);
    renderer.setLights(frameLights(scene, view, settings.clusters));
    Frames f;
    auto render = [&](LightLoop loop, ClusterBuild build, uint32_t perCluster) {
        RenderSettings s = settings;
        s.lightLoop = loop;
        s.clusters.build = build;
        s.clusters.maxLightsPerCluster = perCluster;
        renderer.setSettings(s);
        RenderedImage image = renderer.render(view, kWidth, kHeight, OutputEncoding::DisplaySrgb8);
        EXPECT_EQ(renderer.frameStats().clusterBuildGpu, loop == LightLoop::Clustered && build == ClusterBuild::Gpu);
        return image;
    };
    f.brute = render(LightLoop::All, ClusterBuild::Cpu, 256);
    f.clusteredCpu = render(LightLoop::Clustered, ClusterBuild::Cpu, 256);
    f.clusteredGpu = render(LightLoop::Clustered, ClusterBuild::Gpu, 256);
    f.starved = render(LightLoop::Clustered, ClusterBuild::Cpu, 1);  // negative control
    return f;
}

int maxByteDifference(const RenderedImage& a, const RenderedImage& b, size_t* differing = nullptr) {
    int worst = 0;
    size_t count = 0;
    for (size_t i = 0; i < a.rgba8.size(); ++i) {
        const int d = std::abs(int(a.rgba8[i]) - int(b.rgba8[i]));
        worst = std::max(worst, d);
        count += d > 1 ? 1 : 0;
    }
    if (differing) *differing = count;
    return worst;
}

TEST_F(ClusterBuildGpu, ClusteredRendersMatchBruteForceStandardMaterial) {
    const Frames f = renderFrames(context(), false);
    dumpImage("cluster_standard_brute", f.brute);
    dumpImage("cluster_standard_clustered", f.clusteredCpu);
    EXPECT_LE(maxByteDifference(f.brute, f.clusteredCpu), 1) << "CPU build";
    EXPECT_LE(maxByteDifference(f.brute, f.clusteredGpu), 1) << "compute build";
    size_t differing = 0;
    EXPECT_GT(maxByteDifference(f.brute, f.starved, &differing), 8) << "one light per cluster must show";
    EXPECT_GT(differing, 500u) << "the comparison must be able to fail";
}

TEST_F(ClusterBuildGpu, ClusteredRendersMatchBruteForceSkinMaterial) {
    const Frames f = renderFrames(context(), true);
    dumpImage("cluster_skin_brute", f.brute);
    EXPECT_LE(maxByteDifference(f.brute, f.clusteredCpu), 1) << "CPU build";
    EXPECT_LE(maxByteDifference(f.brute, f.clusteredGpu), 1) << "compute build";
    size_t differing = 0;
    EXPECT_GT(maxByteDifference(f.brute, f.starved, &differing), 8);
    EXPECT_GT(differing, 500u);
}

// With MSAA a pixel a triangle covers in part is shaded at its centre, off the triangle: the
// lists bounded by the surfaces allow for it (ClusterSurfaces::outsidePx).
TEST_F(ClusterBuildGpu, ClusteredRendersMatchBruteForceWithMsaa) {
    const Frames f = renderFrames(context(), true, 4);
    EXPECT_LE(maxByteDifference(f.brute, f.clusteredCpu), 1) << "CPU build";
    EXPECT_LE(maxByteDifference(f.brute, f.clusteredGpu), 1) << "compute build";
    size_t differing = 0;
    EXPECT_GT(maxByteDifference(f.brute, f.starved, &differing), 8);
    EXPECT_GT(differing, 500u);
}

// The scene's triangles in world space (its single-sided materials: back faces culled), as the
// renderer gives them to the light grid.
struct SceneTriangles {
    std::vector<glm::vec3> positions;
    std::vector<uint32_t> indices;
    std::vector<uint8_t> culled;

    explicit SceneTriangles(const Scene& scene) {
        for (const MeshInstance& inst : scene.instances)
            for (const Primitive& p : scene.meshes[size_t(inst.mesh)].primitives) {
                const auto base = static_cast<uint32_t>(positions.size());
                for (const Vertex& v : p.vertices)
                    positions.push_back(glm::vec3(inst.worldFromObject * glm::vec4(v.positionOs, 1.0f)));
                for (uint32_t i : p.indices) indices.push_back(base + i);
            }
        culled.assign(indices.size() / 3, 1);
    }
    ClusterSurfaces surfaces(float outsidePx) const { return ClusterSurfaces{positions, indices, culled, outsidePx}; }
};

// With the scene's surfaces both builds cut each light to where they are in each froxel, and
// list the same lights; every light reaching a point of the surfaces is listed where it is.
TEST_F(ClusterBuildGpu, ComputeBuildWithSurfacesMatchesCpuBuild) {
    const View view = testView();
    const Scene scene = testScene(false);
    const SceneTriangles triangles(scene);
    ClusterSettings settings = gridSettings();
    settings.fitDepthToScene = true;
    const std::vector<Light> lights = frameLights(scene, view, settings);
    for (float outsidePx : {0.0f, 1.0f}) {
        const ClusterSurfaces surfaces = triangles.surfaces(outsidePx);
        const ClusterGrid cpu =
            buildLists(context(), settings, ClusterBuild::Cpu, view, lights, scene.worldBounds(), surfaces);
        const ClusterGrid gpu =
            buildLists(context(), settings, ClusterBuild::Gpu, view, lights, scene.worldBounds(), surfaces);
        const ClusterGrid whole = buildLists(context(), settings, ClusterBuild::Cpu, view, lights, scene.worldBounds());
        EXPECT_EQ(gpu.overflowedClusters, 0u);
        const size_t differing = differingEntries(cpu, gpu);
        EXPECT_LE(double(differing), 1e-3 * double(cpu.indices.size()))
            << differing << " of " << cpu.indices.size() << " entries differ (outsidePx " << outsidePx << ")";
        EXPECT_GT(cpu.indices.size(), 200u);
        EXPECT_LT(double(cpu.indices.size()), 0.8 * double(whole.indices.size()));
        std::printf(
            "[ clusters ] surfaces, outsidePx %.0f: CPU %zu, compute %zu entries, %zu differ; whole froxels %zu\n",
            double(outsidePx), cpu.indices.size(), gpu.indices.size(), differing, whole.indices.size());
    }
}

// Past one batch of candidates (kClusterBatchLights) and past the batches the assign pass keeps
// between its two sweeps (kClusterCachedBatches, after which batches are marked again), with
// whole froxels and with the surfaces (whose empty slices and tiles test no light), and with
// block lists that fit, that fit for some blocks only, and that fit for none (their tiles test
// every light): the compute build lists what the CPU build lists, lights of the last batches
// included.
TEST_F(ClusterBuildGpu, ComputeBuildMatchesCpuBuildOverManyBatches) {
    const View view = testView();
    const Scene scene = testScene(false);
    const SceneTriangles triangles(scene);
    const ClusterSurfaces surfaces = triangles.surfaces(0.0f);
    ClusterSettings settings = gridSettings();
    settings.fitDepthToScene = true;
    settings.tileSizePx = 4;  // 40 x 30 tiles: 5 x 4 blocks
    for (uint32_t count :
         {3 * gpu::kClusterBatchLights + 17, (gpu::kClusterCachedBatches + 2) * gpu::kClusterBatchLights + 5}) {
        std::vector<Light> lights = randomLights(count, 40 + count);
        // A few lights per froxel at every count (volume per light inversely as the count).
        const float scale = 0.2f * std::cbrt(3000.0f / float(count));
        for (size_t i = 1; i < lights.size(); ++i) lights[i].range *= scale;
        for (bool withSurfaces : {false, true}) {
            const ClusterSurfaces given = withSurfaces ? surfaces : ClusterSurfaces{};
            const ClusterGrid cpu =
                buildLists(context(), settings, ClusterBuild::Cpu, view, lights, scene.worldBounds(), given);
            EXPECT_GT(cpu.indices.size(), size_t(count) / 100);
            for (uint32_t blockList : {0xffffffffu, count / 8, 1u}) {
                const ClusterGrid gpu = buildLists(context(), settings, ClusterBuild::Gpu, view, lights,
                                                   scene.worldBounds(), given, nullptr, blockList);
                EXPECT_EQ(gpu.overflowedClusters, cpu.overflowedClusters);  // the per-froxel cap: lowest indices kept
                EXPECT_EQ(gpu.requestedIndices, cpu.requestedIndices);
                const size_t differing = differingEntries(cpu, gpu);
                EXPECT_LE(double(differing), 1e-3 * double(cpu.indices.size()))
                    << differing << " of " << cpu.indices.size() << " entries differ (" << count
                    << " lights, block list " << blockList << ")";
                // Lights of the later batches (of the shared slot where there are more than it keeps).
                const uint32_t later = std::min(count / gpu::kClusterBatchLights, gpu::kClusterCachedBatches - 1u) *
                    gpu::kClusterBatchLights;
                EXPECT_TRUE(std::any_of(gpu.indices.begin(), gpu.indices.end(), [&](uint32_t i) { return i > later; }))
                    << "no light past index " << later << " listed (" << count << " lights)";
                std::printf("[ clusters ] %u lights, %s, block list %u: CPU %zu, compute %zu entries, %zu differ\n",
                            count, withSurfaces ? "surfaces" : "whole froxels", blockList, cpu.indices.size(),
                            gpu.indices.size(), differing);
            }
        }
    }
}

// The CPU build writes each froxel row within the span holding surfaces only; the compute build
// reads every froxel, so what an earlier view left outside the spans must not reach it.
TEST_F(ClusterBuildGpu, ComputeBuildAfterAnotherViewListsOnlyThisViewsSurfaces) {
    const View view = testView();
    const glm::mat4 worldFromOther = glm::inverse(
        glm::lookAt(glm::vec3(-1.6f, 0.6f, 2.4f), glm::vec3(0.2f, 0.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f)));
    const View other = perspectiveView(worldFromOther, 0.9f, float(kWidth) / float(kHeight), 0.3f, 12.0f);
    const Scene scene = testScene(false);
    const SceneTriangles triangles(scene);
    ClusterSettings settings = gridSettings();
    settings.fitDepthToScene = true;
    const std::vector<Light> lights = frameLights(scene, view, settings);
    const ClusterSurfaces surfaces = triangles.surfaces(0.0f);
    const ClusterGrid cpu =
        buildLists(context(), settings, ClusterBuild::Cpu, view, lights, scene.worldBounds(), surfaces);
    const ClusterGrid gpu =
        buildLists(context(), settings, ClusterBuild::Gpu, view, lights, scene.worldBounds(), surfaces, &other);
    const size_t differing = differingEntries(cpu, gpu);
    EXPECT_GT(cpu.indices.size(), 200u);
    EXPECT_LE(double(differing), 1e-3 * double(cpu.indices.size()))
        << differing << " of " << cpu.indices.size() << " entries differ";
}

TEST_F(ClusterBuildGpu, LightCountViewReportsEachPixelsList) {
    const Scene scene = testScene(false);
    const View view = testView();
    RenderSettings settings;
    settings.clusters.tileSizePx = 16;
    settings.clusters.depthSlices = 16;
    settings.debugView = DebugView::LightCount;
    Renderer renderer(context(), scene, Environment::constant(glm::vec3(0.05f)), nullptr, settings);
    const std::vector<Light> lights = frameLights(scene, view, settings.clusters);
    renderer.setLights(lights);
    const RenderedImage image = renderer.render(view, kWidth, kHeight, OutputEncoding::LinearFloat);
    // The renderer bounds the lists by the scene's surfaces; so does this grid.
    const SceneTriangles triangles(scene);
    const ClusterGrid grid = buildClusterGrid(settings.clusters, view, kWidth, kHeight, scene.worldBounds(), lights,
                                              triangles.surfaces(0.0f));
    // The renderer lists lights by their index in its own array (directional first): here the
    // directional light is already first, so indices agree and so do the list lengths.
    size_t covered = 0, agree = 0;
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < kWidth; ++x) {
            const float* px = &image.rgba32f[(size_t(y) * kWidth + x) * 4];
            if (!(px[2] > 0.5f * view.eye().nearM)) continue;
            ++covered;
            const uint32_t z = grid.shape.sliceOf(px[2]);
            const uint32_t froxel = grid.shape.froxelIndex(x / grid.shape.tileSizePx, y / grid.shape.tileSizePx, z);
            const float listed = float(grid.ranges[froxel].y);
            if (px[0] == listed && px[1] == listed + 1.0f) ++agree;
        }
    ASSERT_GT(covered, size_t(kWidth * kHeight / 2));
    // A pixel whose depth sits on a slice boundary may round into the neighbouring slice.
    EXPECT_GE(double(agree), 0.995 * double(covered)) << agree << " of " << covered;
}

}  // namespace
}  // namespace preskin::test
