// Node poses and posedScene on a small hand-built hierarchy, against matrices worked out by hand:
// world transforms through parents (TRS and a fixed matrix), instance transforms, morph weight
// precedence, joint matrices, animation channels over the rest pose, and refused poses.
#include <preskin/Animation.h>
#include <preskin/Error.h>
#include <preskin/Scene.h>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <numbers>

using preskin::Node;
using preskin::Scene;

namespace preskin::test {

namespace {

glm::vec3 apply(const glm::mat4& m, glm::vec3 p) { return glm::vec3(m * glm::vec4(p, 1.0f)); }

void expectNear(glm::vec3 a, glm::vec3 b, float tolerance = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

glm::quat aboutZ(double angle) {
    return glm::quat(static_cast<float>(std::cos(angle / 2)), 0.0f, 0.0f, static_cast<float>(std::sin(angle / 2)));
}

// node 0: T(1,0,0) Rz(90)       root, joint 0
// node 1: T(0,2,0) S(2)         child of 0, joint 1, draws mesh 0 skinned by skin 0
// node 2: matrix T(0,0,5)       child of 1, draws mesh 0 unskinned
// mesh 0 has two morph targets with default weights (0.1, 0.2).
Scene hierarchy() {
    Scene scene;
    scene.nodes.resize(3);
    scene.nodes[0].transform.translation = {1, 0, 0};
    scene.nodes[0].transform.rotation = aboutZ(std::numbers::pi / 2);
    scene.nodes[0].children = {1};
    scene.nodes[1].parent = 0;
    scene.nodes[1].transform.translation = {0, 2, 0};
    scene.nodes[1].transform.scale = {2, 2, 2};
    scene.nodes[1].children = {2};
    scene.nodes[1].mesh = 0;
    scene.nodes[1].skin = 0;
    scene.nodes[1].weights = {0.5f, 0.6f};
    scene.nodes[2].parent = 1;
    scene.nodes[2].matrix = glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 5));
    scene.nodes[2].transform.translation = {0, 0, 5};
    scene.nodes[2].mesh = 0;

    preskin::Mesh mesh;
    mesh.primitives.resize(1);
    mesh.primitives[0].targets.resize(2);
    mesh.weights = {0.1f, 0.2f};
    scene.meshes.push_back(mesh);

    preskin::Skin skin;
    skin.joints = {0, 1};
    skin.inverseBindMatrices = {glm::mat4(1.0f), glm::translate(glm::mat4(1.0f), glm::vec3(0, -3, 0))};
    scene.skins.push_back(skin);

    preskin::MeshInstance skinned;
    skinned.mesh = 0;
    skinned.node = 1;
    skinned.skin = 0;
    skinned.nodeName = "skinned";
    preskin::MeshInstance rigid;
    rigid.mesh = 0;
    rigid.node = 2;
    rigid.nodeName = "rigid";
    scene.instances = {skinned, rigid};
    return scene;
}

}  // namespace

TEST(ScenePose, NodeTransformMatrixIsTranslationRotationScale) {
    preskin::NodeTransform t;
    t.translation = {1, 2, 3};
    t.rotation = aboutZ(std::numbers::pi / 2);
    t.scale = {2, 3, 4};
    // M (1,0,0) = R (2,0,0) + t = (0,2,0) + t;  M (0,1,0) = R (0,3,0) + t = (-3,0,0) + t;  M (0,0,1) = (0,0,4) + t.
    expectNear(apply(t.matrix(), {1, 0, 0}), {1, 4, 3});
    expectNear(apply(t.matrix(), {0, 1, 0}), {-2, 2, 3});
    expectNear(apply(t.matrix(), {0, 0, 1}), {1, 2, 7});
}

TEST(ScenePose, WorldTransformsJointMatricesAndWeightsOfTheRestPose) {
    const Scene scene = hierarchy();
    const preskin::ScenePose pose = preskin::restPose(scene);
    ASSERT_EQ(pose.instances.size(), 2u);

    // world0: p -> (1 - py, px, pz);  world1: p -> world0((0,2,0) + 2p) = (-1 - 2py, 2px, 2pz);
    // world2: p -> world1(p + (0,0,5)) = (-1 - 2py, 2px, 2pz + 10).
    const preskin::InstancePose& rigid = pose.instances[1];
    expectNear(apply(rigid.worldFromObject, {0, 0, 0}), {-1, 0, 10});
    expectNear(apply(rigid.worldFromObject, {1, 0, 0}), {-1, 2, 10});
    expectNear(apply(rigid.worldFromObject, {0, 1, 0}), {-3, 0, 10});
    EXPECT_TRUE(rigid.jointMatrices.empty());
    EXPECT_EQ(rigid.morphWeights, (std::vector<float>{0.1f, 0.2f}));  // the mesh's defaults

    // Skinned: identity draw transform; joint 0 = world0; joint 1 = world1 * T(0,-3,0):
    // p -> (-1 - 2(py - 3), 2px, 2pz) = (5 - 2py, 2px, 2pz).
    const preskin::InstancePose& skinned = pose.instances[0];
    EXPECT_EQ(skinned.worldFromObject, glm::mat4(1.0f));
    ASSERT_EQ(skinned.jointMatrices.size(), 2u);
    expectNear(apply(skinned.jointMatrices[0], {0, 0, 0}), {1, 0, 0});
    expectNear(apply(skinned.jointMatrices[0], {1, 0, 0}), {1, 1, 0});
    expectNear(apply(skinned.jointMatrices[1], {0, 0, 0}), {5, 0, 0});
    expectNear(apply(skinned.jointMatrices[1], {0, 1, 0}), {3, 0, 0});
    expectNear(apply(skinned.jointMatrices[1], {1, 0, 1}), {5, 2, 2});
    EXPECT_EQ(skinned.morphWeights, (std::vector<float>{0.5f, 0.6f}));  // the node's weights
}

TEST(ScenePose, PoseTransformsAndWeightsOverrideTheRest) {
    const Scene scene = hierarchy();
    preskin::NodePose nodes = preskin::restNodePose(scene);
    nodes.transforms[0].rotation = glm::quat(1, 0, 0, 0);
    nodes.transforms[0].translation = {0, 0, 0};
    nodes.transforms[2].translation = {7, 7, 7};  // node 2 has a matrix: never animated
    nodes.weights[1] = {0.9f, 1.0f};
    const preskin::ScenePose pose = preskin::posedScene(scene, nodes);
    // world1 is now T(0,2,0) S(2); world2 = world1 * T(0,0,5): origin -> (0, 2, 10).
    expectNear(apply(pose.instances[1].worldFromObject, {0, 0, 0}), {0, 2, 10});
    EXPECT_EQ(pose.instances[0].morphWeights, (std::vector<float>{0.9f, 1.0f}));
}

TEST(ScenePose, AnimationChannelsApplyOverTheRestPose) {
    Scene scene = hierarchy();
    preskin::Animation animation;
    preskin::AnimationSampler move;
    move.times = {0.0f, 2.0f};
    move.values = {0, 0, 0, 4, 0, 0};
    move.components = 3;
    preskin::AnimationSampler weights;
    weights.times = {0.0f, 2.0f};
    weights.values = {0, 0, 1, 0.5f};
    weights.components = 2;
    animation.samplers = {move, weights};
    animation.channels = {{0, 1, preskin::AnimationPath::Translation}, {1, 1, preskin::AnimationPath::Weights}};
    const preskin::NodePose nodes = preskin::animationNodePose(scene, animation, 1.0f);
    EXPECT_EQ(nodes.transforms[1].translation, glm::vec3(2, 0, 0));
    EXPECT_EQ(nodes.transforms[1].scale, glm::vec3(2, 2, 2));  // untouched paths keep the rest
    EXPECT_EQ(nodes.transforms[0].translation, glm::vec3(1, 0, 0));
    EXPECT_EQ(nodes.weights[1], (std::vector<float>{0.5f, 0.25f}));
    animation.channels.push_back({5, 1, preskin::AnimationPath::Scale});
    EXPECT_THROW(preskin::animationNodePose(scene, animation, 1.0f), preskin::Error);
}

TEST(ScenePose, RefusesPosesThatDoNotMatchTheScene) {
    Scene scene = hierarchy();
    preskin::NodePose nodes = preskin::restNodePose(scene);
    nodes.transforms.pop_back();
    EXPECT_THROW(preskin::posedScene(scene, nodes), preskin::Error);
    nodes = preskin::restNodePose(scene);
    nodes.weights[1] = {1.0f};  // one weight for two targets
    EXPECT_THROW(preskin::posedScene(scene, nodes), preskin::Error);
    nodes = preskin::restNodePose(scene);
    nodes.transforms[1].translation.x = std::nanf("");
    EXPECT_THROW(preskin::posedScene(scene, nodes), preskin::Error);
    // A cycle of parents is refused, not followed forever.
    scene.nodes[0].parent = 2;
    EXPECT_THROW(preskin::restPose(scene), preskin::Error);
}

TEST(ScenePose, InstancesWithoutNodesKeepTheirTransform) {
    Scene scene;
    scene.meshes.resize(1);
    preskin::MeshInstance instance;
    instance.worldFromObject = glm::translate(glm::mat4(1.0f), glm::vec3(1, 2, 3));
    scene.instances.push_back(instance);
    const preskin::ScenePose pose = preskin::restPose(scene);
    EXPECT_EQ(pose.instances.at(0).worldFromObject, instance.worldFromObject);
    EXPECT_TRUE(pose.instances[0].morphWeights.empty());
}

}  // namespace preskin::test
