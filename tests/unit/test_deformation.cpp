// deformPrimitive against analytic cases: morph deltas with known weights, a two-joint skin
// turning 90 degrees (exact positions and normals, a half-and-half vertex), the second influence
// set, morph before skin, non-uniform and mirroring joint scales (normals by the inverse transpose).
#include <preskin/Deformation.h>
#include <preskin/Error.h>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <numbers>

using preskin::InstancePose;
using preskin::Primitive;
using preskin::Vertex;

namespace preskin::test {

namespace {

void expectNear(glm::vec3 a, glm::vec3 b, float tolerance = 1e-6f) {
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

Vertex vertex(glm::vec3 p, glm::vec3 n = {1, 0, 0}, glm::vec4 t = {0, 1, 0, -1}) {
    Vertex v;
    v.positionOs = p;
    v.normalOs = n;
    v.tangentOs = t;
    v.uv0 = {p.x, p.y};
    v.curvaturePerM = 3.0f + p.y;
    return v;
}

preskin::JointInfluences only(uint32_t joint, int set = 0) {
    preskin::JointInfluences influence;
    influence.joints[set][0] = joint;
    influence.weights[set][0] = 1.0f;
    return influence;
}

// Joint 0: identity. Joint 1: 90 degrees about +Z around the pivot (0, 1, 0), i.e.
// worldFromNode = T(0,1,0) Rz(90), inverseBind = T(0,-1,0).
InstancePose bentPose() {
    InstancePose pose;
    const glm::mat4 world = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(0, 1, 0)),
                                        static_cast<float>(std::numbers::pi / 2), glm::vec3(0, 0, 1));
    pose.jointMatrices = {glm::mat4(1.0f), world * glm::translate(glm::mat4(1.0f), glm::vec3(0, -1, 0))};
    return pose;
}

}  // namespace

TEST(Deformation, MorphTargetsAddWeightedDeltas) {
    Primitive primitive;
    primitive.vertices = {vertex({0, 0, 0}, {0, 0, 1}, {1, 0, 0, 1}), vertex({1, 2, 3}, {0, 0, 1}, {1, 0, 0, -1})};
    primitive.targets.resize(3);
    primitive.targets[0].positionDeltas = {{1, 0, 0}, {0, 1, 0}};
    primitive.targets[0].normalDeltas = {{1, 0, 0}, {0, 0, 0}};
    primitive.targets[1].positionDeltas = {{0, 0, 2}, {-1, -1, -1}};
    primitive.targets[1].tangentDeltas = {{0, 0.5f, 0}, {0, 0, 0}};
    primitive.targets[2].positionDeltas = {{100, 100, 100}, {100, 100, 100}};  // no weight given: 0
    InstancePose pose;
    pose.morphWeights = {0.5f, 2.0f};
    std::vector<Vertex> out;
    preskin::deformPrimitive(primitive, pose, out);
    ASSERT_EQ(out.size(), 2u);
    expectNear(out[0].positionOs, {0.5f, 0.0f, 4.0f});   // 0.5 (1,0,0) + 2 (0,0,2)
    expectNear(out[1].positionOs, {-1.0f, 0.5f, 1.0f});  // (1,2,3) + 0.5 (0,1,0) + 2 (-1,-1,-1)
    expectNear(out[0].normalOs, glm::normalize(glm::vec3(0.5f, 0.0f, 1.0f)));
    expectNear(glm::vec3(out[0].tangentOs), glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f)));
    EXPECT_EQ(out[0].tangentOs.w, 1.0f);
    EXPECT_EQ(out[1].tangentOs.w, -1.0f);
    EXPECT_EQ(out[1].uv0, primitive.vertices[1].uv0);
    EXPECT_EQ(out[1].curvaturePerM, primitive.vertices[1].curvaturePerM);
}

TEST(Deformation, TwoJointSkinTurningNinetyDegrees) {
    Primitive primitive;
    primitive.vertices = {vertex({1, 0, 0}), vertex({1, 2, 0}), vertex({1, 1, 0}),
                          vertex({0, 2, 1}, {0, 0, 1}, {1, 0, 0, 1})};
    preskin::JointInfluences half;
    half.joints[0] = {0, 1, 0, 0};
    half.weights[0] = {0.5f, 0.5f, 0.0f, 0.0f};
    primitive.influences = {only(0), only(1), half, only(1, 1)};  // the last one through the second set
    std::vector<Vertex> out;
    preskin::deformPrimitive(primitive, bentPose(), out);
    // Joint 0 leaves the vertex as it is.
    expectNear(out[0].positionOs, {1, 0, 0});
    expectNear(out[0].normalOs, {1, 0, 0});
    // Joint 1: p -> Rz90 (p - (0,1,0)) + (0,1,0); Rz90 (x, y, z) = (-y, x, z).
    expectNear(out[1].positionOs, {-1, 2, 0});
    expectNear(out[1].normalOs, {0, 1, 0});
    expectNear(glm::vec3(out[1].tangentOs), {-1, 0, 0});
    EXPECT_EQ(out[1].tangentOs.w, -1.0f);
    // Half and half: 0.5 (1,1,0) + 0.5 (0,2,0) = (0.5, 1.5, 0); the blended 3x3 (I + Rz90) / 2 is
    // a scaled 45-degree rotation, so the normal turns by 45 degrees.
    expectNear(out[2].positionOs, {0.5f, 1.5f, 0.0f});
    expectNear(out[2].normalOs, {std::sqrt(0.5f), std::sqrt(0.5f), 0.0f});
    expectNear(out[3].positionOs, {-1, 1, 1});
    expectNear(out[3].normalOs, {0, 0, 1});
    expectNear(glm::vec3(out[3].tangentOs), {0, 1, 0});
}

TEST(Deformation, MorphTargetsComeBeforeSkinning) {
    Primitive primitive;
    primitive.vertices = {vertex({1, 2, 0})};
    primitive.targets.resize(1);
    primitive.targets[0].positionDeltas = {{0, 1, 0}};
    primitive.influences = {only(1)};
    InstancePose pose = bentPose();
    pose.morphWeights = {1.0f};
    std::vector<Vertex> out;
    preskin::deformPrimitive(primitive, pose, out);
    // (1,3,0) -> Rz90 (1,2,0) + (0,1,0) = (-2, 2, 0); skinning first would give (-2+0, 1+1, 0) + (0,1,0).
    expectNear(out[0].positionOs, {-2, 2, 0});
}

TEST(Deformation, NormalsTakeTheInverseTransposeUnderNonUniformScale) {
    Primitive primitive;
    primitive.vertices = {
        vertex({1, 1, 1}, glm::normalize(glm::vec3(1, 1, 0)), {std::sqrt(0.5f), -std::sqrt(0.5f), 0, 1})};
    primitive.influences = {only(0)};
    InstancePose pose;
    pose.jointMatrices = {glm::scale(glm::mat4(1.0f), glm::vec3(2, 1, 1))};
    std::vector<Vertex> out;
    preskin::deformPrimitive(primitive, pose, out);
    expectNear(out[0].positionOs, {2, 1, 1});
    // inverse transpose = S(0.5, 1, 1): (1,1,0) -> (0.5,1,0) ~ (1,2,0)/sqrt 5; the tangent takes S: (2,-1,0)/sqrt 5.
    expectNear(out[0].normalOs, glm::vec3(1, 2, 0) / std::sqrt(5.0f));
    expectNear(glm::vec3(out[0].tangentOs), glm::vec3(2, -1, 0) / std::sqrt(5.0f));
    EXPECT_NEAR(glm::dot(out[0].normalOs, glm::vec3(out[0].tangentOs)), 0.0f, 1e-6f);  // stays perpendicular

    // A mirroring joint (negative determinant) mirrors the normal too.
    pose.jointMatrices = {glm::scale(glm::mat4(1.0f), glm::vec3(-1, 1, 1))};
    preskin::deformPrimitive(primitive, pose, out);
    expectNear(out[0].normalOs, glm::normalize(glm::vec3(-1, 1, 0)));
}

TEST(Deformation, UnskinnedPrimitivesStayInObjectSpace) {
    Primitive primitive;
    primitive.vertices = {vertex({1, 2, 3})};
    primitive.influences = {only(0)};
    InstancePose pose;  // no joint matrices: the primitive is drawn rigidly
    pose.worldFromObject = glm::translate(glm::mat4(1.0f), glm::vec3(5, 5, 5));
    std::vector<Vertex> out;
    preskin::deformPrimitive(primitive, pose, out);
    expectNear(out[0].positionOs, {1, 2, 3});
}

TEST(Deformation, RefusesMismatchedInput) {
    Primitive primitive;
    primitive.vertices = {vertex({0, 0, 0}), vertex({1, 0, 0})};
    primitive.influences = {only(0), only(2)};
    std::vector<Vertex> out;
    EXPECT_THROW(preskin::deformPrimitive(primitive, bentPose(), out), preskin::Error);  // joint 2 of 2
    primitive.influences = {only(0)};
    EXPECT_THROW(preskin::deformPrimitive(primitive, bentPose(), out), preskin::Error);  // 1 influence, 2 vertices
    primitive.influences.clear();
    primitive.targets.resize(1);
    primitive.targets[0].normalDeltas = {{0, 0, 1}};
    EXPECT_THROW(preskin::deformPrimitive(primitive, InstancePose{}, out), preskin::Error);
}

}  // namespace preskin::test
