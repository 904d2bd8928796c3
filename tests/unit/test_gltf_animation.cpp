// Loading animation data from glTF: the node hierarchy, skins and joint influences (both sets,
// integer and normalised types, weight normalisation with one warning), morph targets (dense,
// sparse, names, default and node weights), animations (paths, interpolations, quantised
// rotations), the bundled skinned tube in its rest pose and bent, and every bad skin, morph
// target or animation case with its one-line error.
#include "unit/GltfTestFiles.h"

#include <preskin/Animation.h>
#include <preskin/Deformation.h>
#include <preskin/Error.h>
#include <preskin/Scene.h>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <filesystem>
#include <numbers>

using nlohmann::json;
namespace fs = std::filesystem;

namespace preskin::test {

namespace {

const fs::path kData = fs::path(PRESKIN_SOURCE_DIR) / "tests/data/gltf";
const fs::path kTube = fs::path(PRESKIN_SOURCE_DIR) / "samples/assets/tube/tube.gltf";

void expectNear(glm::vec3 a, glm::vec3 b, float tolerance) {
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

std::vector<std::string> warningsWith(const preskin::Scene& s, const std::string& text) {
    std::vector<std::string> out;
    for (const auto& w : s.warnings)
        if (w.find(text) != std::string::npos) out.push_back(w);
    return out;
}

// A triangle (accessors 0..3 as in triangleScene) plus JOINTS_0/WEIGHTS_0 given by the caller,
// skinned by two joint nodes (1 root, 2 child at y = 1).
GltfBuilder skinnedTriangle(int jointsAccessorType, const std::vector<uint8_t>& jointBytes, int weightsType,
                            const std::vector<uint8_t>& weightBytes, bool normalizedWeights) {
    GltfBuilder b = preskin::test::triangleScene();
    const int joints = b.addAccessor(b.addView(jointBytes), jointsAccessorType, 3, "VEC4");
    const int weights =
        b.addAccessor(b.addView(weightBytes), weightsType, 3, "VEC4", {{"normalized", normalizedWeights}});
    b.doc["meshes"][0]["primitives"][0]["attributes"]["JOINTS_0"] = joints;
    b.doc["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_0"] = weights;
    b.doc["nodes"][0]["skin"] = 0;
    b.doc["nodes"].push_back({{"name", "root"}, {"children", {2}}});
    b.doc["nodes"].push_back({{"name", "tip"}, {"translation", {0, 1, 0}}});
    b.doc["scenes"][0]["nodes"].push_back(1);
    b.doc["skins"] = json::array({{{"joints", {1, 2}}}});
    return b;
}

template <typename T>
std::vector<uint8_t> bytesOf(const std::vector<T>& values) {
    std::vector<uint8_t> out(values.size() * sizeof(T));
    std::memcpy(out.data(), values.data(), out.size());
    return out;
}

}  // namespace

TEST(GltfAnimation, StaticFilesGetNodesAndKeepTheirRestPose) {
    const auto s = preskin::Scene::load(kData / "triangle.gltf");
    EXPECT_TRUE(s.warnings.empty());
    ASSERT_EQ(s.nodes.size(), 1u);
    EXPECT_EQ(s.nodes[0].mesh, 0);
    EXPECT_EQ(s.nodes[0].parent, -1);
    ASSERT_EQ(s.instances.size(), 1u);
    EXPECT_EQ(s.instances[0].node, 0);
    EXPECT_EQ(s.instances[0].skin, -1);
    EXPECT_TRUE(s.skins.empty());
    EXPECT_TRUE(s.animations.empty());
    EXPECT_TRUE(s.meshes[0].weights.empty());
    EXPECT_TRUE(s.meshes[0].primitives[0].targets.empty());
    EXPECT_TRUE(s.meshes[0].primitives[0].influences.empty());
}

TEST(GltfAnimation, HierarchyWithMatrixAndTrsMatchesTheFlattenedInstances) {
    TempDir dir;
    GltfBuilder b = preskin::test::triangleScene();
    // nodes[0] (mesh) under nodes[1] (matrix: rotation 90 about X, scale 2, translation), which is
    // under nodes[2] (TRS).
    const float m[16] = {2, 0, 0, 0, 0, 0, 2, 0, 0, -2, 0, 0, 1, 2, 3, 1};
    b.doc["nodes"].push_back({{"name", "matrix"}, {"matrix", std::vector<float>(m, m + 16)}, {"children", {0}}});
    b.doc["nodes"].push_back({{"name", "trs"},
                              {"translation", {0, 0, -1}},
                              {"rotation", {0, 0.6, 0, 0.8}},
                              {"scale", {1, 3, 1}},
                              {"children", {1}}});
    b.doc["scenes"][0]["nodes"] = {2};
    const auto s = preskin::Scene::load(b.writeGltf(dir.path()));
    ASSERT_EQ(s.nodes.size(), 3u);
    EXPECT_EQ(s.nodes[0].parent, 1);
    EXPECT_EQ(s.nodes[1].parent, 2);
    EXPECT_EQ(s.nodes[2].children, std::vector<int>{1});
    ASSERT_TRUE(s.nodes[1].matrix.has_value());
    EXPECT_FALSE(s.nodes[2].matrix.has_value());
    // The decomposition reproduces the matrix: scale 2, 90 degrees about X.
    const glm::mat4 recomposed = s.nodes[1].transform.matrix();
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) EXPECT_NEAR(recomposed[c][r], (*s.nodes[1].matrix)[c][r], 1e-6f) << c << r;
    expectNear(s.nodes[1].transform.scale, {2, 2, 2}, 1e-6f);
    EXPECT_NEAR(s.nodes[2].transform.rotation.y, 0.6f, 1e-7f);
    EXPECT_NEAR(s.nodes[2].transform.rotation.w, 0.8f, 1e-7f);
    // The rest pose gives the loader's flattened transform.
    const preskin::ScenePose pose = preskin::restPose(s);
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            EXPECT_NEAR(pose.instances[0].worldFromObject[c][r], s.instances[0].worldFromObject[c][r], 1e-5f);
}

TEST(GltfAnimation, NormalizedByteWeightsAreNormalisedWithOneWarning) {
    TempDir dir;
    // Vertex 0: 255 -> 1 (fine). Vertex 1: 100 + 100 -> 0.784 (off). Vertex 2: 200 + 100 (off).
    GltfBuilder b = skinnedTriangle(5121, {0, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0}, 5121,
                                    {255, 0, 0, 0, 100, 100, 0, 0, 200, 100, 0, 0}, true);
    const fs::path path = b.writeGltf(dir.path());
    const auto s = preskin::Scene::load(path);
    const auto warnings = warningsWith(s, "WEIGHTS_0");
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0].rfind(path.string() + ": meshes[0].primitives[0].attributes.WEIGHTS_0: 2 of 3 vertices", 0),
              0u)
        << warnings[0];
    const auto& influences = s.meshes[0].primitives[0].influences;
    ASSERT_EQ(influences.size(), 3u);
    EXPECT_EQ(influences[1].joints[0], glm::uvec4(0, 1, 0, 0));
    EXPECT_FLOAT_EQ(influences[1].weights[0].x, 0.5f);
    EXPECT_FLOAT_EQ(influences[1].weights[0].y, 0.5f);
    EXPECT_FLOAT_EQ(influences[2].weights[0].x, 2.0f / 3.0f);
    EXPECT_FLOAT_EQ(influences[2].weights[0].y, 1.0f / 3.0f);
    EXPECT_EQ(influences[2].joints[0], glm::uvec4(1, 0, 0, 0));
    ASSERT_EQ(s.skins.size(), 1u);
    EXPECT_EQ(s.skins[0].joints, (std::vector<int>{1, 2}));
    EXPECT_EQ(s.skins[0].inverseBindMatrices, std::vector<glm::mat4>(2, glm::mat4(1.0f)));
    EXPECT_EQ(s.instances[0].skin, 0);
    EXPECT_EQ(s.nodes[2].parent, 1);
}

TEST(GltfAnimation, SecondInfluenceSetWithShortJointsAndFloatWeights) {
    TempDir dir;
    GltfBuilder b = skinnedTriangle(5123, bytesOf(std::vector<uint16_t>{0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0}), 5126,
                                    bytesOf(std::vector<float>{0.25f, 0, 0, 0, 1, 0, 0, 0, 0.5f, 0, 0, 0}), false);
    const int joints1 =
        b.addAccessor(b.addView(std::vector<uint16_t>{1, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0}), 5123, 3, "VEC4");
    const int weights1 = b.addFloats({0.75f, 0, 0, 0, 0, 0, 0, 0, 0.5f, 0, 0, 0}, "VEC4");
    b.doc["meshes"][0]["primitives"][0]["attributes"]["JOINTS_1"] = joints1;
    b.doc["meshes"][0]["primitives"][0]["attributes"]["WEIGHTS_1"] = weights1;
    const auto s = preskin::Scene::load(b.writeGltf(dir.path()));
    EXPECT_TRUE(warningsWith(s, "WEIGHTS").empty()) << s.warnings.front();
    const auto& influences = s.meshes[0].primitives[0].influences;
    EXPECT_EQ(influences[0].joints[1], glm::uvec4(1, 0, 0, 0));
    EXPECT_EQ(influences[0].weights[1].x, 0.75f);
    EXPECT_EQ(influences[2].weights[0].x, 0.5f);
    EXPECT_EQ(influences[2].weights[1].x, 0.5f);
}

TEST(GltfAnimation, InverseBindMatricesAndSkeleton) {
    TempDir dir;
    GltfBuilder b = skinnedTriangle(5121, std::vector<uint8_t>(12, 0), 5126,
                                    bytesOf(std::vector<float>{1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}), false);
    std::vector<float> ibm = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0,  0, 1,
                              1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1};
    b.doc["skins"][0]["inverseBindMatrices"] = b.addAccessor(b.addView(ibm), 5126, 2, "MAT4");
    b.doc["skins"][0]["skeleton"] = 1;
    const auto s = preskin::Scene::load(b.writeGltf(dir.path()));
    ASSERT_EQ(s.skins.at(0).inverseBindMatrices.size(), 2u);
    EXPECT_EQ(s.skins[0].inverseBindMatrices[1], glm::translate(glm::mat4(1.0f), glm::vec3(0, -1, 0)));
    EXPECT_EQ(s.skins[0].skeleton, 1);
    // Rest pose: joint 1's world (T(0,1,0)) times its inverse bind is the identity.
    const preskin::ScenePose pose = preskin::restPose(s);
    EXPECT_EQ(pose.instances[0].jointMatrices[1], glm::mat4(1.0f));
    EXPECT_EQ(pose.instances[0].worldFromObject, glm::mat4(1.0f));
}

TEST(GltfAnimation, MorphTargetsDenseSparseNamedAndWeighted) {
    TempDir dir;
    GltfBuilder b = preskin::test::triangleScene();
    const int dense = b.addFloats({0, 0, 1, 0, 0, 2, 0, 0, 3}, "VEC3");
    // Sparse: no bufferView, vertex 2 moved by (0.5, 0, 0); normals moved on vertex 1 only.
    const int sparseIndices = b.addView(std::vector<uint8_t>{2, 0, 0, 0});
    const int sparseValues = b.addView(std::vector<float>{0.5f, 0, 0});
    const int sparse = b.addAccessor(-1, 5126, 3, "VEC3",
                                     {{"sparse",
                                       {{"count", 1},
                                        {"indices", {{"bufferView", sparseIndices}, {"componentType", 5121}}},
                                        {"values", {{"bufferView", sparseValues}}}}}});
    const int normalIndices = b.addView(std::vector<uint8_t>{1, 0, 0, 0});
    const int normalValues = b.addView(std::vector<float>{1, 0, 0});
    const int sparseNormals = b.addAccessor(-1, 5126, 3, "VEC3",
                                            {{"sparse",
                                              {{"count", 1},
                                               {"indices", {{"bufferView", normalIndices}, {"componentType", 5121}}},
                                               {"values", {{"bufferView", normalValues}}}}}});
    const int uvDelta = b.addFloats({0, 0, 0, 0, 0, 0}, "VEC2");
    b.doc["meshes"][0]["primitives"][0]["targets"] = json::array(
        {{{"POSITION", dense}}, {{"POSITION", sparse}, {"NORMAL", sparseNormals}, {"TEXCOORD_0", uvDelta}}});
    b.doc["meshes"][0]["weights"] = {0.25, 0.5};
    b.doc["meshes"][0]["extras"] = {{"targetNames", {"lift", "slide"}}};
    b.doc["nodes"][0]["weights"] = {1.0, 0.0};
    const fs::path path = b.writeGltf(dir.path());
    const auto s = preskin::Scene::load(path);
    const preskin::Mesh& mesh = s.meshes.at(0);
    EXPECT_EQ(mesh.weights, (std::vector<float>{0.25f, 0.5f}));
    EXPECT_EQ(mesh.targetNames, (std::vector<std::string>{"lift", "slide"}));
    EXPECT_EQ(s.nodes[0].weights, (std::vector<float>{1.0f, 0.0f}));
    const auto& targets = mesh.primitives[0].targets;
    ASSERT_EQ(targets.size(), 2u);
    EXPECT_EQ(targets[0].positionDeltas, (std::vector<glm::vec3>{{0, 0, 1}, {0, 0, 2}, {0, 0, 3}}));
    EXPECT_TRUE(targets[0].normalDeltas.empty());
    EXPECT_EQ(targets[1].positionDeltas, (std::vector<glm::vec3>{{0, 0, 0}, {0, 0, 0}, {0.5f, 0, 0}}));
    EXPECT_EQ(targets[1].normalDeltas, (std::vector<glm::vec3>{{0, 0, 0}, {1, 0, 0}, {0, 0, 0}}));
    const auto uvWarnings = warningsWith(s, "TEXCOORD_0");
    ASSERT_EQ(uvWarnings.size(), 1u);
    EXPECT_EQ(uvWarnings[0].rfind(path.string() + ": meshes[0].primitives[0].targets[1]: 'TEXCOORD_0': ", 0), 0u);
    // The rest pose takes the node's weights over the mesh's.
    EXPECT_EQ(preskin::restPose(s).instances[0].morphWeights, (std::vector<float>{1.0f, 0.0f}));
}

TEST(GltfAnimation, FlatShadedPrimitivesKeepTheirDeltasAndInfluences) {
    // Without NORMAL the loader splits vertices per triangle; the deltas and influences must follow.
    TempDir dir;
    GltfBuilder b;
    const int position = b.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0}, "VEC3");
    const int indices = b.addIndices(std::vector<uint16_t>{0, 1, 2, 2, 1, 3});
    const int delta = b.addFloats({0, 0, 0, 0, 0, 1, 0, 0, 2, 0, 0, 3}, "VEC3");
    b.addMeshNode(
        {{"attributes", {{"POSITION", position}}}, {"indices", indices}, {"targets", {{{"POSITION", delta}}}}});
    const auto s = preskin::Scene::load(b.writeGltf(dir.path()));
    const preskin::Primitive& p = s.meshes.at(0).primitives.at(0);
    ASSERT_EQ(p.vertices.size(), 6u);
    ASSERT_EQ(p.targets.at(0).positionDeltas.size(), 6u);
    for (size_t i = 0; i < 6; ++i) {
        const glm::vec3 position0 = p.vertices[i].positionOs;
        EXPECT_EQ(p.targets[0].positionDeltas[i].z, position0.x + 2.0f * position0.y)
            << i;  // delta z = index of the source vertex
    }
}

TEST(GltfAnimation, AnimationsWithEveryPathAndInterpolation) {
    TempDir dir;
    GltfBuilder b = preskin::test::triangleScene();
    const int target = b.addFloats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
    b.doc["meshes"][0]["primitives"][0]["targets"] = json::array({{{"POSITION", target}}});
    b.doc["nodes"].push_back({{"name", "mover"}});
    b.doc["scenes"][0]["nodes"].push_back(1);
    const int times =
        b.addAccessor(b.addView(std::vector<float>{0.5f, 1.5f}), 5126, 2, "SCALAR", {{"min", {0.5}}, {"max", {1.5}}});
    const int translations = b.addFloats({0, 0, 0, 2, 0, 0}, "VEC3");
    // Rotations as normalized shorts: identity and 90 degrees about +Z (0, 0, 0.7071, 0.7071).
    const auto q = static_cast<int16_t>(std::lround(32767 * std::sqrt(0.5)));
    const int rotations = b.addAccessor(b.addView(std::vector<int16_t>{0, 0, 0, 32767, 0, 0, q, q}), 5122, 2, "VEC4",
                                        {{"normalized", true}});
    // CUBICSPLINE scale: (in, value, out) per key.
    const int scales = b.addFloats({0, 0, 0, 1, 1, 1, 0, 0, 0, 0, 0, 0, 3, 3, 3, 0, 0, 0}, "VEC3");
    const int weights = b.addFloats({0, 1}, "SCALAR");
    b.doc["animations"] = json::array({{{"name", "all"},
                                        {"samplers",
                                         {{{"input", times}, {"output", translations}},
                                          {{"input", times}, {"output", rotations}},
                                          {{"input", times}, {"output", scales}, {"interpolation", "CUBICSPLINE"}},
                                          {{"input", times}, {"output", weights}, {"interpolation", "STEP"}}}},
                                        {"channels",
                                         {{{"sampler", 0}, {"target", {{"node", 1}, {"path", "translation"}}}},
                                          {{"sampler", 1}, {"target", {{"node", 1}, {"path", "rotation"}}}},
                                          {{"sampler", 2}, {"target", {{"node", 1}, {"path", "scale"}}}},
                                          {{"sampler", 3}, {"target", {{"node", 0}, {"path", "weights"}}}},
                                          {{"sampler", 0}, {"target", {{"node", 1}, {"path", "pointer"}}}}}}}});
    const fs::path path = b.writeGltf(dir.path());
    const auto s = preskin::Scene::load(path);
    ASSERT_EQ(s.animations.size(), 1u);
    const preskin::Animation& a = s.animations[0];
    EXPECT_EQ(a.name, "all");
    EXPECT_EQ(a.startS(), 0.5f);
    EXPECT_EQ(a.endS(), 1.5f);
    ASSERT_EQ(a.channels.size(), 4u);  // "pointer" ignored, with a warning
    EXPECT_EQ(warningsWith(s, "animations[0].channels[4].target.path").size(), 1u);
    EXPECT_TRUE(a.samplers[1].rotation);
    EXPECT_FALSE(a.samplers[3].rotation);
    EXPECT_EQ(a.samplers[2].interpolation, preskin::Interpolation::CubicSpline);
    EXPECT_EQ(a.samplers[2].values.size(), 18u);
    EXPECT_EQ(a.samplers[3].components, 1u);

    const preskin::NodePose pose = preskin::animationNodePose(s, a, 1.0f);
    expectNear(pose.transforms[1].translation, {1, 0, 0}, 1e-6f);
    const glm::vec3 x = pose.transforms[1].rotation * glm::vec3(1, 0, 0);
    expectNear(x, {std::cos(0.25f * std::numbers::pi_v<float>), std::sin(0.25f * std::numbers::pi_v<float>), 0}, 1e-4f);
    expectNear(pose.transforms[1].scale, {2, 2, 2}, 1e-6f);  // Hermite with zero tangents, half-way
    EXPECT_EQ(pose.weights[0], std::vector<float>{0.0f});    // STEP: still the first key
    EXPECT_EQ(preskin::animationNodePose(s, a, 2.0f).weights[0], std::vector<float>{1.0f});
}

TEST(GltfAnimation, TubeLoadsWithSkinAndAnimation) {
    const auto s = preskin::Scene::load(kTube);
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
    ASSERT_EQ(s.meshes.size(), 1u);
    const preskin::Primitive& p = s.meshes[0].primitives.at(0);
    EXPECT_EQ(p.vertices.size(), 17u * 13u);
    EXPECT_EQ(p.influences.size(), p.vertices.size());
    ASSERT_EQ(s.skins.size(), 1u);
    EXPECT_EQ(s.skins[0].joints, (std::vector<int>{1, 2}));
    ASSERT_EQ(s.nodes.size(), 3u);
    EXPECT_EQ(s.nodes[2].name, "bend");
    EXPECT_EQ(s.nodes[2].parent, 1);
    ASSERT_EQ(s.instances.size(), 1u);
    EXPECT_EQ(s.instances[0].skin, 0);
    const preskin::Animation& bend = preskin::findAnimation(s, "bend");
    EXPECT_EQ(bend.startS(), 0.0f);
    EXPECT_EQ(bend.endS(), 1.0f);

    // Rest pose: the deformation gives back the loaded geometry (world space = object space here).
    std::vector<preskin::Vertex> out;
    preskin::deformPrimitive(p, preskin::restPose(s).instances[0], out);
    for (size_t i = 0; i < out.size(); ++i) {
        expectNear(out[i].positionOs, p.vertices[i].positionOs, 1e-6f);
        expectNear(out[i].normalOs, p.vertices[i].normalOs, 1e-6f);
    }

    // Bent: the top (weight 1 on the bend joint, y >= 0.65) turns by the animated angle about +Z
    // around (0, 0.5, 0); the bottom (y <= 0.35) stays. At 0.4 s the angle is 36 degrees.
    for (const auto& [timeS, angle] : {std::pair{1.0f, std::numbers::pi / 2}, std::pair{0.4f, std::numbers::pi / 5}}) {
        const preskin::ScenePose pose = preskin::posedScene(s, preskin::animationNodePose(s, bend, timeS));
        preskin::deformPrimitive(p, pose.instances[0], out);
        const auto c = static_cast<float>(std::cos(angle)), sn = static_cast<float>(std::sin(angle));
        size_t top = 0, bottom = 0;
        for (size_t i = 0; i < out.size(); ++i) {
            const glm::vec3 p0 = p.vertices[i].positionOs, n0 = p.vertices[i].normalOs;
            if (p0.y >= 0.65f) {
                const glm::vec3 r = p0 - glm::vec3(0, 0.5f, 0);
                expectNear(out[i].positionOs, glm::vec3(c * r.x - sn * r.y, sn * r.x + c * r.y + 0.5f, r.z), 1e-5f);
                expectNear(out[i].normalOs, glm::vec3(c * n0.x - sn * n0.y, sn * n0.x + c * n0.y, n0.z), 1e-5f);
                ++top;
            } else if (p0.y <= 0.35f) {
                expectNear(out[i].positionOs, p0, 1e-6f);
                ++bottom;
            }
        }
        EXPECT_EQ(top, 6u * 13u);
        EXPECT_EQ(bottom, 6u * 13u);
    }
}

struct BadCase {
    const char* file;
    std::vector<const char*> fragments;
};

class GltfAnimationErrors : public ::testing::TestWithParam<BadCase> {};

TEST_P(GltfAnimationErrors, OneLineNamingFileFieldAndProblem) {
    preskin::test::expectLoadError(kData / GetParam().file, GetParam().fragments);
}

TEST(GltfAnimation, CommittedSkinnedTriangleLoads) {
    // The bad cases below are this file with one defect each.
    const auto s = preskin::Scene::load(kData / "skinned_triangle.gltf");
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
    EXPECT_EQ(s.skins.size(), 1u);
    EXPECT_EQ(s.animations.size(), 1u);
    EXPECT_EQ(s.meshes.at(0).primitives.at(0).targets.size(), 1u);
}

INSTANTIATE_TEST_SUITE_P(
    Committed, GltfAnimationErrors,
    ::testing::Values(
        BadCase{"skin_joint_out_of_range.gltf",
                {"meshes[0].primitives[0].attributes.JOINTS_0: ", "joint 2 at vertex 1 is out of range",
                 "skins[0], which has 2 joints"}},
        BadCase{"skin_no_joints.gltf", {"skins[0].joints: ", "empty"}},
        BadCase{"skin_joints_missing.gltf", {"skins[0].joints: ", "missing"}},
        BadCase{"skin_inverse_bind_count.gltf", {"skins[0].inverseBindMatrices: ", "1 matrices for 2 joints"}},
        BadCase{"anim_count_mismatch.gltf", {"animations[0].samplers[0]: ", "2 keys", "3 elements", "1 per key"}},
        BadCase{"anim_cubic_count.gltf", {"animations[0].samplers[0]: ", "2 elements", "CUBICSPLINE: 3 per key"}},
        // The element and component named are the NaN and the infinity (the wording of the number
        // problem itself is the accessor reader's).
        BadCase{"anim_nan_time.gltf", {"accessors[7]: ", "element 1 (component 0) of animations[0].samplers[0].input"}},
        BadCase{"anim_infinite_value.gltf",
                {"accessors[8]: ", "element 1 (component 1) of animations[0].samplers[0].output", "finite"}},
        BadCase{"anim_times_not_increasing.gltf",
                {"animations[0].samplers[0].input: ", "key 1 is not after", "times must increase"}},
        BadCase{"anim_matrix_node.gltf", {"animations[0].channels[0].target.node: ", "nodes[2] has a matrix"}},
        BadCase{"morph_target_count_mismatch.gltf",
                {"meshes[0].primitives[1].targets: ", "2 morph targets, primitives[0] has 1"}},
        BadCase{"morph_weights_length.gltf", {"meshes[0].weights: ", "2 weights for 1 morph targets"}}));

TEST(GltfAnimation, MoreBadCasesGeneratedHere) {
    TempDir dir;
    auto expectError = [&](GltfBuilder b, const std::string& name, std::initializer_list<const char*> fragments) {
        preskin::test::expectLoadError(b.writeGltf(dir.path(), name), fragments);
    };
    const std::vector<uint8_t> joints(12, 0);
    const auto weights = bytesOf(std::vector<float>{1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0});

    GltfBuilder b = skinnedTriangle(5121, joints, 5126, weights, false);
    b.doc["meshes"][0]["primitives"][0]["attributes"].erase("WEIGHTS_0");
    expectError(b, "pair", {"attributes.WEIGHTS_0: ", "come in pairs"});

    b = skinnedTriangle(5121, joints, 5126, bytesOf(std::vector<float>{1, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0}), false);
    expectError(b, "zero", {"attributes.WEIGHTS_0: ", "vertex 1 has no joint weight"});

    b = skinnedTriangle(5121, joints, 5126, bytesOf(std::vector<float>{1, 0, 0, 0, 1.5f, -0.5f, 0, 0, 1, 0, 0, 0}),
                        false);
    expectError(b, "negative", {"attributes.WEIGHTS_0: ", "negative weight -0.5 at vertex 1"});

    b = skinnedTriangle(5126, bytesOf(std::vector<float>(12, 0.0f)), 5126, weights, false);
    expectError(b, "float_joints", {".componentType: ", "JOINTS_0 needs unsigned byte"});

    b = skinnedTriangle(5121, joints, 5126, weights, false);
    b.doc["meshes"][0]["primitives"][0]["attributes"].erase("JOINTS_0");
    b.doc["meshes"][0]["primitives"][0]["attributes"].erase("WEIGHTS_0");
    expectError(b, "unskinnable",
                {"meshes[0].primitives[0].attributes: ", "no JOINTS_0", "nodes[0] draws meshes[0] with skins[0]"});

    b = skinnedTriangle(5121, joints, 5126, weights, false);
    b.doc["skins"][0]["joints"] = {1, 9};
    expectError(b, "joint_node", {"skins[0].joints[1]: ", "9 is out of range"});

    b = preskin::test::triangleScene();
    b.doc["nodes"][0]["weights"] = {0.5};
    expectError(b, "node_weights", {"nodes[0].weights: ", "1 weights, but meshes[0] has 0 morph targets"});

    b = preskin::test::triangleScene();
    b.doc["nodes"].push_back({{"name", "a"}, {"children", {2}}});
    b.doc["nodes"].push_back({{"name", "b"}, {"children", {1}}});
    expectError(b, "cycle", {"nodes[1]: ", "cycle"});

    b = preskin::test::triangleScene();
    const int times = b.addFloats({0, 1}, "SCALAR");
    const int zero = b.addFloats({0, 0, 0, 1, 0, 0, 0, 0}, "VEC4");
    b.doc["animations"] =
        json::array({{{"samplers", {{{"input", times}, {"output", zero}}}},
                      {"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "rotation"}}}}}}}});
    expectError(b, "zero_rotation", {"animations[0].samplers[0].output: ", "key 1 is a zero quaternion"});

    b.doc["animations"][0]["channels"][0]["target"]["path"] = "weights";
    expectError(b, "weights_without_targets",
                {"animations[0].channels[0].target.node: ", "no mesh with morph targets"});

    b.doc["animations"][0]["channels"][0]["target"]["path"] = "translation";
    expectError(b, "wrong_type", {".type: ", "VEC4, but animations[0].samplers[0].output needs VEC3"});

    b.doc["animations"][0]["channels"][0]["target"]["path"] = "rotation";
    b.doc["animations"][0]["samplers"][0]["interpolation"] = "SMOOTH";
    expectError(b, "interpolation", {"animations[0].samplers[0].interpolation: ", "'SMOOTH'"});
}

}  // namespace preskin::test
