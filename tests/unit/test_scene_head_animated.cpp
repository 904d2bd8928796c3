// The bundled animated head (samples/assets/head/head_animated.gltf, made by
// make_head_animated.py from head.gltf): counts and names, the rest pose reproduces the static
// head, each morph target moves its own region of the face, and the "talk" animation drives every
// target and turns the head on its neck while the shoulders stay.
#include <preskin/Animation.h>
#include <preskin/Deformation.h>
#include <preskin/Scene.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

namespace preskin::test {

namespace {

const std::filesystem::path kFolder = std::filesystem::path(PRESKIN_SOURCE_DIR) / "samples/assets/head";

const preskin::Scene& animated() {
    static const preskin::Scene scene = preskin::Scene::load(kFolder / "head_animated.gltf");
    return scene;
}

const preskin::Scene& staticHead() {
    static const preskin::Scene scene = preskin::Scene::load(kFolder / "head.gltf");
    return scene;
}

std::vector<preskin::Vertex> deformed(const preskin::InstancePose& pose) {
    std::vector<preskin::Vertex> out;
    preskin::deformPrimitive(animated().meshes.at(0).primitives.at(0), pose, out);
    return out;
}

// Largest displacement (m) from the static head over the vertices `select` picks.
template <typename Select>
float largestMove(const std::vector<preskin::Vertex>& out, Select select) {
    const auto& base = staticHead().meshes[0].primitives[0].vertices;
    float largest = 0.0f;
    for (size_t i = 0; i < out.size(); ++i)
        if (select(base[i].positionOs))
            largest = std::max(largest, glm::length(out[i].positionOs - base[i].positionOs));
    return largest;
}

}  // namespace

TEST(SceneHeadAnimated, CountsNamesAndStructure) {
    const preskin::Scene& s = animated();
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
    ASSERT_EQ(s.meshes.size(), 1u);
    const preskin::Mesh& mesh = s.meshes[0];
    EXPECT_EQ(mesh.targetNames, (std::vector<std::string>{"jawOpen", "cheekPuff", "browRaise"}));
    EXPECT_EQ(mesh.weights, std::vector<float>(3, 0.0f));
    const preskin::Primitive& p = mesh.primitives.at(0);
    EXPECT_EQ(p.vertices.size(), staticHead().meshes[0].primitives[0].vertices.size());
    EXPECT_EQ(p.indices, staticHead().meshes[0].primitives[0].indices);
    ASSERT_EQ(p.targets.size(), 3u);
    for (const preskin::MorphTarget& t : p.targets) {
        EXPECT_EQ(t.positionDeltas.size(), p.vertices.size());
        EXPECT_EQ(t.normalDeltas.size(), p.vertices.size());
    }
    EXPECT_EQ(p.influences.size(), p.vertices.size());
    ASSERT_EQ(s.skins.size(), 1u);
    EXPECT_EQ(s.skins[0].joints.size(), 3u);
    ASSERT_EQ(s.instances.size(), 1u);
    EXPECT_EQ(s.instances[0].skin, 0);
    EXPECT_EQ(s.lights.size(), staticHead().lights.size());
    ASSERT_FALSE(s.cameras.empty());  // the static head's front view (its close-ups are not copied)
    EXPECT_EQ(s.cameras[0].name, staticHead().cameras[0].name);
    EXPECT_EQ(s.images.size(), staticHead().images.size());
    const preskin::Animation& talk = preskin::findAnimation(s, "talk");
    EXPECT_EQ(talk.startS(), 0.0f);
    EXPECT_EQ(talk.endS(), 4.0f);
    EXPECT_EQ(talk.channels.size(), 3u);
}

TEST(SceneHeadAnimated, RestPoseReproducesTheStaticHead) {
    const auto out = deformed(preskin::restPose(animated()).instances.at(0));
    const auto& base = staticHead().meshes[0].primitives[0].vertices;
    ASSERT_EQ(out.size(), base.size());
    for (size_t i = 0; i < out.size(); ++i) {
        ASSERT_LT(glm::length(out[i].positionOs - base[i].positionOs), 1e-6f) << i;
        ASSERT_GT(glm::dot(out[i].normalOs, base[i].normalOs), 0.999999f) << i;
    }
}

TEST(SceneHeadAnimated, EachTargetMovesItsRegion) {
    const preskin::Scene& s = animated();
    const preskin::InstancePose rest = preskin::restPose(s).instances.at(0);
    // The face looks toward +Z; the mouth is near y = 0, the brows near y = 0.1, the crown at 0.19.
    auto below = [](float y) { return [y](glm::vec3 p) { return p.z > 0.0f && p.y < y; }; };
    auto above = [](float y) { return [y](glm::vec3 p) { return p.y > y; }; };
    auto weighted = [&](std::vector<float> w) {
        preskin::InstancePose pose = rest;
        pose.morphWeights = std::move(w);
        return deformed(pose);
    };
    const auto jaw = weighted({1, 0, 0});
    EXPECT_GT(largestMove(jaw, below(-0.02f)), 0.015f);  // the chin drops centimetres
    EXPECT_LT(largestMove(jaw, above(0.06f)), 1e-6f);    // the upper face stays
    const auto cheeks = weighted({0, 1, 0});
    EXPECT_GT(largestMove(cheeks, [](glm::vec3 p) { return std::abs(p.x) > 0.03f && p.z > 0.04f; }), 0.004f);
    EXPECT_LT(largestMove(cheeks, above(0.1f)), 1e-4f);
    const auto brows = weighted({0, 0, 1});
    EXPECT_GT(largestMove(brows, above(0.09f)), 0.005f);
    EXPECT_LT(largestMove(brows, below(0.04f)), 1e-6f);
}

TEST(SceneHeadAnimated, TalkDrivesEveryTargetAndTurnsTheHead) {
    const preskin::Scene& s = animated();
    const preskin::Animation& talk = preskin::findAnimation(s, "talk");
    std::vector<float> peak(3, 0.0f);
    float largestHeadMove = 0.0f, largestShoulderMove = 0.0f;
    for (float t = talk.startS(); t <= talk.endS(); t += 0.25f) {
        const preskin::ScenePose pose = preskin::posedScene(s, preskin::animationNodePose(s, talk, t));
        const preskin::InstancePose& instance = pose.instances.at(0);
        for (size_t k = 0; k < 3; ++k) peak[k] = std::max(peak[k], instance.morphWeights.at(k));
        const auto out = deformed(instance);
        largestHeadMove = std::max(largestHeadMove, largestMove(out, [](glm::vec3 p) { return p.y > 0.15f; }));
        largestShoulderMove = std::max(largestShoulderMove, largestMove(out, [](glm::vec3 p) { return p.y < -0.15f; }));
    }
    for (size_t k = 0; k < 3; ++k) EXPECT_GT(peak[k], 0.3f) << s.meshes[0].targetNames[k];
    EXPECT_GT(largestHeadMove, 0.03f);      // the crown swings by centimetres
    EXPECT_LT(largestShoulderMove, 1e-6f);  // the shoulders follow the chest joint, which does not move
}

}  // namespace preskin::test
