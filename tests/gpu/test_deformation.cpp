// The GPU deformation and curvature passes (render/GpuDeformer.h, shaders/deform.comp,
// shaders/curvature.comp) against the CPU:
//  - deformed positions, normals and tangents equal deformPrimitive (<preskin/Deformation.h>, an
//    independent double-precision implementation of the glTF rules) within 1e-5 relative, for the
//    skinned tube at several times of its bend and with a morph target added to it (morph, then skin);
//  - the GPU curvature of the deformed mesh equals computeVertexCurvature of the CPU-deformed
//    mesh within the documented tolerance (float against double, relative to the mesh's largest
//    curvature: 97 % of vertices within 2.5 %, every vertex within 15 %), and on the bent tube
//    differs from the bind pose where it bends and not elsewhere; it is signed as the CPU's is
//    (a sphere seen from inside is concave: -1/r);
//  - the skin's normal basis moves like the normals (rigid parts keep each vector's length and
//    normal component) and starts from computeNormalBasis of the rest mesh;
//  - a pose that does not fit the scene is refused and the previous one kept.
#include "support/GpuTest.h"
#include "support/TestScenes.h"

#include <preskin/Curvature.h>
#include <preskin/Deformation.h>
#include <preskin/Error.h>
#include <preskin/NormalBasis.h>
#include <preskin/Renderer.h>
#include <preskin/Scene.h>

#include "render/GpuDeformer.h"
#include "render/GpuScene.h"
#include "render/PoseSurfaces.h"
#include "vk/Device.h"
#include "vk/Resources.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace preskin::test {
namespace {

// A vertex's normal basis as the GPU reads it: the averaged normals, the opposing ones, the
// opposing centroid's offset.
std::array<glm::vec3, 2 * kNormalBasisCount + 1> vectorsOf(const NormalBasis& m) {
    std::array<glm::vec3, 2 * kNormalBasisCount + 1> v{};
    std::copy(m.averaged.begin(), m.averaged.end(), v.begin());
    std::copy(m.opposing.begin(), m.opposing.end(), v.begin() + kNormalBasisCount);
    v.back() = m.opposingCentroid;
    return v;
}

const std::string kTube = std::string(PRESKIN_SOURCE_DIR) + "/samples/assets/tube/tube.gltf";

// The deformer's output for a pose: every deformed vertex of instance 0, in mesh order (and its
// normal basis, and the rest one, when asked).
std::vector<Vertex> gpuDeform(Context& context, const Scene& scene, const ScenePose& pose,
                              std::vector<NormalBasis>* basis = nullptr,
                              std::vector<NormalBasis>* restBasis = nullptr) {
    const vk::Device& device = ContextAccess::core(context);
    GpuScene gpuScene(device, scene);
    GpuDeformer deformer(device, scene, gpuScene.vertices, gpuScene.normalBasis, gpuScene.meshFirstVertex);
    deformer.check(pose);
    deformer.prepare(0, pose);
    size_t count = 0;
    for (const Primitive& p : scene.meshes[size_t(scene.instances[0].mesh)].primitives) count += p.vertices.size();
    vk::Buffer host(device, count * sizeof(Vertex), VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    vk::Buffer hostBasis(device, count * sizeof(NormalBasis), VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    vk::Buffer hostRest(device, count * sizeof(NormalBasis), VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    device.submitAndWait([&](VkCommandBuffer cmd) {
        deformer.recordDeformation(cmd, 0);
        deformer.recordCurvature(cmd, 0);
        const VkBufferCopy region{0, 0, count * sizeof(Vertex)};  // instance 0 is first in the output
        vkCmdCopyBuffer(cmd, deformer.output(0).handle(), host.handle(), 1, &region);
        const VkBufferCopy basisRegion{0, 0, count * sizeof(NormalBasis)};
        vkCmdCopyBuffer(cmd, deformer.normalBasisOutput(0).handle(), hostBasis.handle(), 1, &basisRegion);
        const VkBufferCopy restRegion{gpuScene.meshFirstVertex[size_t(scene.instances[0].mesh)] * sizeof(NormalBasis),
                                      0, count * sizeof(NormalBasis)};
        vkCmdCopyBuffer(cmd, gpuScene.normalBasis.handle(), hostRest.handle(), 1, &restRegion);
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    });
    std::vector<Vertex> out(count);
    std::memcpy(out.data(), host.mapped(), count * sizeof(Vertex));
    if (basis) {
        basis->resize(count);
        std::memcpy(basis->data(), hostBasis.mapped(), count * sizeof(NormalBasis));
    }
    if (restBasis) {
        restBasis->resize(count);
        std::memcpy(restBasis->data(), hostRest.mapped(), count * sizeof(NormalBasis));
    }
    return out;
}

// deformPrimitive over every primitive of instance 0's mesh.
std::vector<Vertex> cpuDeform(const Scene& scene, const ScenePose& pose) {
    std::vector<Vertex> all, part;
    for (const Primitive& p : scene.meshes[size_t(scene.instances[0].mesh)].primitives) {
        deformPrimitive(p, pose.instances[0], part);
        all.insert(all.end(), part.begin(), part.end());
    }
    return all;
}

// computeVertexCurvature of the CPU-deformed mesh (all primitives as one surface).
std::vector<float> cpuCurvature(const Scene& scene, const std::vector<Vertex>& deformed) {
    std::vector<glm::vec3> positions, normals;
    std::vector<uint32_t> indices;
    uint32_t base = 0;
    for (const Primitive& p : scene.meshes[size_t(scene.instances[0].mesh)].primitives) {
        for (uint32_t i : p.indices) indices.push_back(base + i);
        base += static_cast<uint32_t>(p.vertices.size());
    }
    for (const Vertex& v : deformed) {
        positions.push_back(v.positionOs);
        normals.push_back(v.normalOs);
    }
    return computeVertexCurvature(positions, normals, indices);
}

ScenePose tubePose(const Scene& scene, float timeS) {
    return posedScene(scene, animationNodePose(scene, findAnimation(scene, "bend"), timeS));
}

// The tube with a morph target added to its primitive: a radial bulge (and its normals tipped),
// weighted in the pose.
Scene tubeWithMorph() {
    Scene scene = Scene::load(kTube);
    Mesh& mesh = scene.meshes[size_t(scene.instances[0].mesh)];
    for (Primitive& p : mesh.primitives) {
        MorphTarget t;
        for (const Vertex& v : p.vertices) {
            const glm::vec3 radial(v.positionOs.x, 0.0f, v.positionOs.z);
            t.positionDeltas.push_back(0.3f * radial * std::sin(8.0f * v.positionOs.y));
            t.normalDeltas.push_back(glm::vec3(0.0f, 0.2f * std::cos(8.0f * v.positionOs.y), 0.0f));
            t.tangentDeltas.push_back(glm::vec3(0.0f));
        }
        p.targets.push_back(t);
    }
    mesh.weights.assign(1, 0.0f);
    return scene;
}

double meshScale(const std::vector<Vertex>& v) {
    double r = 0.0;
    for (const Vertex& x : v) r = std::max(r, double(glm::length(x.positionOs)));
    return r;
}

class GpuDeformation : public GpuTest {};

TEST_F(GpuDeformation, GpuMatchesCpuDeformation) {
    for (bool morph : {false, true}) {
        const Scene scene = morph ? tubeWithMorph() : Scene::load(kTube);
        ASSERT_FALSE(scene.skins.empty());
        for (float t : {0.0f, 0.37f, 1.0f, 2.5f}) {
            ScenePose pose = tubePose(scene, t);
            if (morph) pose.instances[0].morphWeights = {0.8f};
            const std::vector<Vertex> gpu = gpuDeform(context(), scene, pose);
            const std::vector<Vertex> cpu = cpuDeform(scene, pose);
            ASSERT_EQ(gpu.size(), cpu.size());
            const double scale = meshScale(cpu);
            double worstP = 0.0, worstN = 0.0, worstT = 0.0;
            for (size_t i = 0; i < cpu.size(); ++i) {
                worstP = std::max(worstP, double(glm::length(gpu[i].positionOs - cpu[i].positionOs)) / scale);
                worstN = std::max(worstN, double(glm::length(gpu[i].normalOs - cpu[i].normalOs)));
                worstT =
                    std::max(worstT, double(glm::length(glm::vec3(gpu[i].tangentOs) - glm::vec3(cpu[i].tangentOs))));
                EXPECT_EQ(gpu[i].tangentOs.w, cpu[i].tangentOs.w);
                EXPECT_EQ(gpu[i].uv0, cpu[i].uv0);
            }
            const std::string what = std::string(morph ? "morph + skin" : "skin") + " at t = " + std::to_string(t);
            EXPECT_LE(worstP, 1e-5) << what;
            EXPECT_LE(worstN, 1e-5) << what;
            EXPECT_LE(worstT, 1e-5) << what;
        }
    }
}

// The light grid's triangles (render/PoseSurfaces.h) follow the deformation: their corners are
// the deformed vertices (deformPrimitive, the reference the GPU pass is held to above).
TEST(PoseSurfaces, TrianglesFollowTheDeformation) {
    for (bool morph : {false, true}) {
        const Scene scene = morph ? tubeWithMorph() : Scene::load(kTube);
        ASSERT_EQ(scene.instances.size(), 1u);
        PoseSurfaces posed(scene);
        for (float t : {0.0f, 1.0f, 2.5f}) {
            ScenePose pose = tubePose(scene, t);
            if (morph) pose.instances[0].morphWeights = {0.8f};
            const ClusterSurfaces surfaces = posed.surfaces(pose);
            const std::vector<Vertex> cpu = cpuDeform(scene, pose);
            ASSERT_EQ(surfaces.positionsWs.size(), cpu.size());
            const double scale = meshScale(cpu);
            double worst = 0.0;
            for (size_t i = 0; i < cpu.size(); ++i)
                worst = std::max(worst, double(glm::length(surfaces.positionsWs[i] - cpu[i].positionOs)) / scale);
            EXPECT_LE(worst, 1e-5) << (morph ? "morph + skin" : "skin") << " at t = " << t;
            size_t indices = 0;
            for (const Primitive& p : scene.meshes[size_t(scene.instances[0].mesh)].primitives)
                indices += p.indices.size();
            EXPECT_EQ(surfaces.indices.size(), indices);
            EXPECT_EQ(surfaces.backFaceCulled.size(), indices / 3);
        }
        // A pose that bends it moves the triangles.
        const ClusterSurfaces rest = posed.surfaces(tubePose(scene, 0.0f));
        const std::vector<glm::vec3> restPositions(rest.positionsWs.begin(), rest.positionsWs.end());
        const ClusterSurfaces bent = posed.surfaces(tubePose(scene, 1.0f));
        double moved = 0.0;
        for (size_t i = 0; i < restPositions.size(); ++i)
            moved = std::max(moved, double(glm::length(bent.positionsWs[i] - restPositions[i])));
        EXPECT_GT(moved, 0.05 * meshScale(cpuDeform(scene, tubePose(scene, 0.0f))));
    }
}

TEST_F(GpuDeformation, GpuCurvatureMatchesCpuEstimatorAndFollowsTheBend) {
    Scene scene = Scene::load(kTube);
    scene.makeSkin("all");  // skin materials recompute curvature after deformation (the default)
    std::vector<float> restCurvature;
    for (float t : {0.0f, 1.0f}) {
        const ScenePose pose = tubePose(scene, t);
        const std::vector<Vertex> gpu = gpuDeform(context(), scene, pose);
        const std::vector<Vertex> cpu = cpuDeform(scene, pose);
        const std::vector<float> reference = cpuCurvature(scene, cpu);
        const float largest = *std::max_element(reference.begin(), reference.end());
        ASSERT_GT(largest, 0.0f);
        // Tolerance: float on the GPU against double on the CPU, on an estimator that is
        // ill-conditioned at the triangles linear blend skinning folds on the inside of a sharp bend
        // (there the CPU estimator itself moves by about 2 % of the largest curvature when its
        // input vertices move by float rounding). Documented in docs/animation.md.
        std::vector<double> differences;
        for (size_t i = 0; i < gpu.size(); ++i)
            differences.push_back(std::abs(double(gpu[i].curvaturePerM) - double(reference[i])) / double(largest));
        std::sort(differences.begin(), differences.end());
        EXPECT_LE(differences[differences.size() * 97 / 100], 0.025) << "t = " << t;
        EXPECT_LE(differences.back(), 0.15) << "t = " << t;
        if (t == 0.0f) {
            for (const Vertex& v : gpu) restCurvature.push_back(v.curvaturePerM);
            continue;
        }
        // Bent: the elbow's curvature changes, the straight ends' does not.
        size_t changed = 0, unchanged = 0, elbow = 0, ends = 0;
        const std::vector<Vertex> restCpu = cpuDeform(scene, tubePose(scene, 0.0f));
        float lo = 1e30f, hi = -1e30f;
        for (const Vertex& v : restCpu) {
            lo = std::min(lo, v.positionOs.y);
            hi = std::max(hi, v.positionOs.y);
        }
        for (size_t i = 0; i < gpu.size(); ++i) {
            const float y = (restCpu[i].positionOs.y - lo) / (hi - lo);  // 0 .. 1 along the rest tube
            const float change = std::abs(gpu[i].curvaturePerM - restCurvature[i]);
            if (std::abs(y - 0.5f) < 0.08f) {
                ++elbow;
                changed += change > 0.1f * restCurvature[i];
            } else if (y < 0.25f || y > 0.75f) {
                ++ends;
                unchanged += change < 0.01f * restCurvature[i];
            }
        }
        EXPECT_GT(elbow, 0u);
        EXPECT_GT(changed, elbow / 2) << "the elbow's curvature should follow the bend";
        EXPECT_GT(unchanged, ends * 9 / 10) << "the straight parts keep their curvature";
    }
}

// The skin's normal basis moves like the normals: where the tube moves rigidly (its straight
// ends) each basis vector keeps its length and its component along the normal, and at rest it is
// the basis computeNormalBasis gives the rest mesh; meshes without skin have none.
TEST_F(GpuDeformation, NormalBasisMovesLikeTheNormals) {
    Scene scene = Scene::load(kTube);
    scene.makeSkin("all");
    std::vector<Vertex> rest;
    std::vector<NormalBasis> restBasis, gpuRest;
    for (float t : {0.0f, 1.0f}) {
        std::vector<NormalBasis> basis;
        const std::vector<Vertex> gpu = gpuDeform(context(), scene, tubePose(scene, t), &basis, &gpuRest);
        if (t == 0.0f) {
            rest = gpu;
            restBasis = basis;
            std::vector<glm::vec3> positions, normals;
            std::vector<uint32_t> indices;
            for (const Primitive& p : scene.meshes[size_t(scene.instances[0].mesh)].primitives) {
                for (uint32_t i : p.indices) indices.push_back(uint32_t(positions.size()) + i);
                for (const Vertex& v : p.vertices) {
                    positions.push_back(v.positionOs);
                    normals.push_back(v.normalOs);
                }
            }
            const std::vector<NormalBasis> cpu = computeNormalBasis(positions, normals, indices, 1000.0);
            ASSERT_EQ(cpu.size(), gpuRest.size());
            for (size_t i = 0; i < cpu.size(); ++i)
                for (size_t b = 0; b < vectorsOf(cpu[i]).size(); ++b)
                    EXPECT_LT(glm::length(vectorsOf(gpuRest[i])[b] - vectorsOf(cpu[i])[b]), 1e-6f);
            continue;
        }
        float lo = 1e30f, hi = -1e30f;
        for (const Vertex& v : rest) {
            lo = std::min(lo, v.positionOs.y);
            hi = std::max(hi, v.positionOs.y);
        }
        size_t checked = 0;
        for (size_t i = 0; i < gpu.size(); ++i) {
            const float y = (rest[i].positionOs.y - lo) / (hi - lo);
            if (y > 0.2f && y < 0.8f) continue;  // the bend
            // The averaged and the opposing normals turn with the normal, keeping their lengths.
            for (size_t b = 0; b < 2 * kNormalBasisCount; ++b) {
                const glm::vec3 moved = vectorsOf(basis[i])[b], still = vectorsOf(restBasis[i])[b];
                EXPECT_NEAR(glm::length(moved), glm::length(still), 2e-3f) << "vertex " << i;
                EXPECT_NEAR(glm::dot(moved, gpu[i].normalOs), glm::dot(still, rest[i].normalOs), 2e-3f);
            }
            ++checked;
        }
        EXPECT_GT(checked, gpu.size() / 3);
    }
    // Without skin the basis is zero and stays zero.
    const Scene plain = Scene::load(kTube);
    std::vector<NormalBasis> basis;
    gpuDeform(context(), plain, tubePose(plain, 1.0f), &basis);
    for (const NormalBasis& m : basis)
        for (const glm::vec3& v : vectorsOf(m)) EXPECT_EQ(v, glm::vec3(0.0f));
}

// A sphere seen from outside and from inside (normals and winding turned), each given a morph
// target so the GPU pass recomputes its curvature: +1/r outside, -1/r inside, as on the CPU.
TEST_F(GpuDeformation, GpuCurvatureIsSignedLikeTheCpuEstimator) {
    const float radiusM = 0.1f;
    for (bool inside : {false, true}) {
        Primitive sphere = makeSphere(radiusM, 32, 16);
        if (inside) {
            for (Vertex& v : sphere.vertices) v.normalOs = -v.normalOs;
            for (size_t i = 0; i + 2 < sphere.indices.size(); i += 3)
                std::swap(sphere.indices[i + 1], sphere.indices[i + 2]);
        }
        MorphTarget still;
        still.positionDeltas.assign(sphere.vertices.size(), glm::vec3(0.0f));
        still.normalDeltas.assign(sphere.vertices.size(), glm::vec3(0.0f));
        still.tangentDeltas.assign(sphere.vertices.size(), glm::vec3(0.0f));
        sphere.targets.push_back(still);
        sphere.material = 0;
        Scene scene = makeScene({{sphere, glm::mat4(1.0f)}}, {Material{}});
        scene.meshes[0].weights.assign(1, 0.0f);
        scene.makeSkin("all");
        ScenePose pose = restPose(scene);
        pose.instances[0].morphWeights = {1.0f};
        const std::vector<Vertex> gpu = gpuDeform(context(), scene, pose);
        const std::vector<float> cpu = cpuCurvature(scene, cpuDeform(scene, pose));
        // Away from the poles (where the UV sphere's triangles degenerate) the estimate is 1/r.
        const float want = (inside ? -1.0f : 1.0f) / radiusM;
        for (size_t i = 0; i < gpu.size(); ++i) {
            const char* what = inside ? "inside" : "outside";
            if (std::abs(sphere.vertices[i].positionOs.y) < 0.8f * radiusM) {
                EXPECT_NEAR(cpu[i], want, 0.02f * std::abs(want)) << what << " " << i;
            }
            EXPECT_NEAR(gpu[i].curvaturePerM, cpu[i], 1e-3f * std::abs(want)) << what << " " << i;
        }
    }
}

TEST_F(GpuDeformation, BindPoseCurvatureIsKeptWhenTheMaterialAsks) {
    Scene scene = Scene::load(kTube);
    SkinMaterial bind;
    bind.deformedCurvature = DeformedCurvature::BindPose;
    scene.makeSkin("all", bind);
    const std::vector<Vertex> gpu = gpuDeform(context(), scene, tubePose(scene, 1.0f));
    size_t i = 0;
    for (const Primitive& p : scene.meshes[size_t(scene.instances[0].mesh)].primitives)
        for (const Vertex& v : p.vertices) EXPECT_EQ(gpu[i++].curvaturePerM, v.curvaturePerM);
}

// A morph target that cancels the normal and tangent of every other vertex: those keep their
// undeformed normal and tangent on the GPU, as deformPrimitive does.
TEST_F(GpuDeformation, CollapsedNormalsAndTangentsKeepTheirRestValues) {
    Scene scene = Scene::load(kTube);
    Mesh& mesh = scene.meshes[size_t(scene.instances[0].mesh)];
    for (Primitive& p : mesh.primitives) {
        MorphTarget t;
        for (size_t i = 0; i < p.vertices.size(); ++i) {
            const bool collapse = i % 2 == 0;
            t.positionDeltas.push_back(glm::vec3(0.0f));
            t.normalDeltas.push_back(collapse ? -p.vertices[i].normalOs : glm::vec3(0.0f));
            t.tangentDeltas.push_back(collapse ? -glm::vec3(p.vertices[i].tangentOs) : glm::vec3(0.0f));
        }
        p.targets.push_back(t);
    }
    mesh.weights.assign(1, 0.0f);
    ScenePose pose = restPose(scene);
    pose.instances[0].morphWeights = {1.0f};
    const std::vector<Vertex> gpu = gpuDeform(context(), scene, pose);
    const std::vector<Vertex> cpu = cpuDeform(scene, pose);
    ASSERT_EQ(gpu.size(), cpu.size());
    size_t collapsed = 0;
    for (const Primitive& p : mesh.primitives)
        for (size_t i = 0; i < p.vertices.size(); ++i, ++collapsed) {
            if (i % 2 != 0) continue;
            // The rest transform of a skinned tube is its bind pose: the rest normal comes back.
            EXPECT_LE(glm::length(gpu[collapsed].normalOs - cpu[collapsed].normalOs), 1e-5f) << collapsed;
            EXPECT_LE(glm::length(glm::vec3(gpu[collapsed].tangentOs) - glm::vec3(cpu[collapsed].tangentOs)), 1e-5f)
                << collapsed;
            EXPECT_LE(glm::length(cpu[collapsed].normalOs - p.vertices[i].normalOs), 1e-5f) << collapsed;
        }
}

TEST_F(GpuDeformation, PosesThatDoNotFitAreRefused) {
    const Scene scene = Scene::load(kTube);
    Renderer renderer(context(), scene, Environment::constant(glm::vec3(0.1f)), nullptr);
    const ScenePose good = tubePose(scene, 0.5f);
    renderer.setPose(good);
    ScenePose bad = good;
    bad.instances.clear();
    EXPECT_THROW(renderer.setPose(bad), Error);
    bad = good;
    bad.instances[0].jointMatrices.pop_back();
    EXPECT_THROW(renderer.setPose(bad), Error);
    bad = good;
    bad.instances[0].jointMatrices[0][3][1] = std::nanf("");
    EXPECT_THROW(renderer.setPose(bad), Error);
    bad = good;
    bad.instances[0].morphWeights = {std::numeric_limits<float>::infinity()};
    EXPECT_THROW(renderer.setPose(bad), Error);
    EXPECT_EQ(renderer.pose().instances[0].jointMatrices, good.instances[0].jointMatrices);
}

}  // namespace
}  // namespace preskin::test
