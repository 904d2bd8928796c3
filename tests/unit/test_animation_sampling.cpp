// Animation sampling against hand-computed values: STEP, LINEAR (with slerp over the short arc),
// CUBICSPLINE (Hermite with tangents scaled by the key interval), and times outside the keys.
#include <preskin/Animation.h>
#include <preskin/Error.h>
#include <preskin/Scene.h>

#include <gtest/gtest.h>
#include <glm/gtc/quaternion.hpp>

#include <cmath>
#include <numbers>

using preskin::AnimationSampler;
using preskin::Interpolation;

namespace preskin::test {

namespace {

AnimationSampler sampler(Interpolation interpolation, std::vector<float> times, std::vector<float> values,
                         uint32_t components, bool rotation = false) {
    AnimationSampler s;
    s.interpolation = interpolation;
    s.times = std::move(times);
    s.values = std::move(values);
    s.components = components;
    s.rotation = rotation;
    return s;
}

// (x, y, z, w) of a rotation by `angle` about a unit axis.
std::vector<float> axisAngle(glm::vec3 axis, double angle) {
    const auto s = static_cast<float>(std::sin(angle / 2)), c = static_cast<float>(std::cos(angle / 2));
    return {axis.x * s, axis.y * s, axis.z * s, c};
}

glm::vec3 rotate(const std::vector<float>& q, glm::vec3 v) { return glm::quat(q[3], q[0], q[1], q[2]) * v; }

}  // namespace

TEST(AnimationSampling, StepHoldsEachKeyUntilTheNext) {
    const auto s = sampler(Interpolation::Step, {0.0f, 1.0f, 2.0f}, {0.0f, 10.0f, 20.0f}, 1);
    EXPECT_EQ(s.sample(0.0f)[0], 0.0f);
    EXPECT_EQ(s.sample(0.5f)[0], 0.0f);
    EXPECT_EQ(s.sample(0.999f)[0], 0.0f);
    EXPECT_EQ(s.sample(1.0f)[0], 10.0f);
    EXPECT_EQ(s.sample(1.99f)[0], 10.0f);
    EXPECT_EQ(s.sample(2.0f)[0], 20.0f);
    EXPECT_EQ(s.sample(-3.0f)[0], 0.0f);  // before the first key
    EXPECT_EQ(s.sample(7.0f)[0], 20.0f);  // after the last
}

TEST(AnimationSampling, LinearInterpolatesAndClampsOutsideTheKeys) {
    const auto s = sampler(Interpolation::Linear, {1.0f, 3.0f}, {0.0f, 0.0f, 0.0f, 2.0f, 4.0f, -6.0f}, 3);
    const auto v = s.sample(1.5f);  // a quarter of the way
    ASSERT_EQ(v.size(), 3u);
    EXPECT_FLOAT_EQ(v[0], 0.5f);
    EXPECT_FLOAT_EQ(v[1], 1.0f);
    EXPECT_FLOAT_EQ(v[2], -1.5f);
    EXPECT_EQ(s.sample(0.0f), (std::vector<float>{0.0f, 0.0f, 0.0f}));
    EXPECT_EQ(s.sample(3.0f), (std::vector<float>{2.0f, 4.0f, -6.0f}));
    EXPECT_EQ(s.sample(100.0f), (std::vector<float>{2.0f, 4.0f, -6.0f}));
}

TEST(AnimationSampling, LinearRotationIsSlerpAtConstantAngularSpeed) {
    // 0 to 120 degrees about +Y: at a quarter of the time the rotation is 30 degrees (a plain
    // normalised lerp would give about 26.3 degrees).
    std::vector<float> values = axisAngle({0, 1, 0}, 0.0);
    const auto end = axisAngle({0, 1, 0}, 2.0 * std::numbers::pi / 3.0);
    values.insert(values.end(), end.begin(), end.end());
    const auto s = sampler(Interpolation::Linear, {0.0f, 4.0f}, values, 4, true);
    const glm::vec3 x = rotate(s.sample(1.0f), {1, 0, 0});
    const double angle = std::atan2(-x.z, x.x);  // rotation about +Y turns +X towards -Z
    EXPECT_NEAR(angle, std::numbers::pi / 6.0, 1e-6);
}

TEST(AnimationSampling, SlerpTakesTheShortArcWhenKeysHaveOppositeSigns) {
    // Key 1 is -q for q = 90 degrees about +Z: the same rotation. Half-way is 45 degrees, not the
    // long way round (-135 degrees).
    std::vector<float> values = axisAngle({0, 0, 1}, 0.0);
    for (float c : axisAngle({0, 0, 1}, std::numbers::pi / 2.0)) values.push_back(-c);
    const auto s = sampler(Interpolation::Linear, {0.0f, 1.0f}, values, 4, true);
    const auto q = s.sample(0.5f);
    const glm::vec3 x = rotate(q, {1, 0, 0});
    EXPECT_NEAR(x.x, std::sqrt(0.5), 1e-6);
    EXPECT_NEAR(x.y, std::sqrt(0.5), 1e-6);
    EXPECT_NEAR(x.z, 0.0, 1e-6);
    EXPECT_NEAR(std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]), 1.0, 1e-6);
}

TEST(AnimationSampling, LinearWeightsOfFourTargetsAreNotTreatedAsARotation) {
    const auto s = sampler(Interpolation::Linear, {0.0f, 1.0f}, {0, 0, 0, 0, 1, 1, 1, 1}, 4);
    EXPECT_EQ(s.sample(0.5f), (std::vector<float>{0.5f, 0.5f, 0.5f, 0.5f}));
}

TEST(AnimationSampling, CubicSplineIsHermiteWithTangentsScaledByTheInterval) {
    // Keys (in-tangent, value, out-tangent): t=0: (0, 1, 3); t=2: (-1, 5, 0). At t = 0.5,
    // s = 0.25 and d = 2: h00 = 0.84375, h10 = 0.140625, h01 = 0.15625, h11 = -0.046875, so
    // p = 0.84375 * 1 + 0.140625 * 2 * 3 + 0.15625 * 5 + (-0.046875) * 2 * (-1) = 2.5625.
    const auto s = sampler(Interpolation::CubicSpline, {0.0f, 2.0f}, {0.0f, 1.0f, 3.0f, -1.0f, 5.0f, 0.0f}, 1);
    EXPECT_NEAR(s.sample(0.5f)[0], 2.5625, 1e-6);
    // The slope at a key is its tangent (per second): (p(h) - p(0)) / h -> 3, (p(2) - p(2 - h)) / h -> -1.
    const float h = 1e-3f;
    EXPECT_NEAR((s.sample(h)[0] - s.sample(0.0f)[0]) / h, 3.0, 1e-2);
    EXPECT_NEAR((s.sample(2.0f)[0] - s.sample(2.0f - h)[0]) / h, -1.0, 1e-2);
    // Outside the keys: the values, never the tangents.
    EXPECT_EQ(s.sample(-1.0f)[0], 1.0f);
    EXPECT_EQ(s.sample(9.0f)[0], 5.0f);
}

TEST(AnimationSampling, CubicSplineRotationsAreNormalised) {
    const auto a = axisAngle({1, 0, 0}, 0.0), b = axisAngle({1, 0, 0}, 1.0);
    std::vector<float> values;
    for (const auto* key : {&a, &b}) {
        values.insert(values.end(), {0.0f, 0.0f, 0.0f, 0.0f});  // in-tangent
        values.insert(values.end(), key->begin(), key->end());
        values.insert(values.end(), {0.0f, 0.0f, 0.0f, 0.0f});  // out-tangent
    }
    const auto s = sampler(Interpolation::CubicSpline, {0.0f, 1.0f}, values, 4, true);
    const auto q = s.sample(0.5f);
    EXPECT_NEAR(std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]), 1.0, 1e-6);
    // With zero tangents the Hermite curve is symmetric: half-way between the keys is half the angle.
    const glm::vec3 y = rotate(q, {0, 1, 0});
    EXPECT_NEAR(std::atan2(y.z, y.y), 0.5, 1e-6);
}

TEST(AnimationSampling, BadSamplersThrow) {
    EXPECT_THROW(sampler(Interpolation::Linear, {0.0f, 1.0f}, {0.0f}, 1).sample(0.5f), preskin::Error);
    EXPECT_THROW(sampler(Interpolation::CubicSpline, {0.0f, 1.0f}, {0.0f, 1.0f}, 1).sample(0.5f), preskin::Error);
    EXPECT_THROW(sampler(Interpolation::Linear, {0.0f}, {0.0f}, 1).sample(std::nanf("")), preskin::Error);
    EXPECT_THROW(sampler(Interpolation::Linear, {}, {}, 1).sample(0.0f), preskin::Error);
}

TEST(AnimationSampling, AnimationTimeRangeSpansEverySampler) {
    preskin::Animation animation;
    EXPECT_EQ(animation.startS(), 0.0f);
    EXPECT_EQ(animation.endS(), 0.0f);
    animation.samplers.push_back(sampler(Interpolation::Linear, {0.5f, 2.0f}, {0, 1}, 1));
    animation.samplers.push_back(sampler(Interpolation::Step, {1.0f, 3.0f}, {0, 1}, 1));
    EXPECT_EQ(animation.startS(), 0.5f);
    EXPECT_EQ(animation.endS(), 3.0f);
}

TEST(AnimationSampling, FindAnimationByNameOrIndexAndListsTheNames) {
    preskin::Scene scene;
    scene.sourcePath = "scene.gltf";
    scene.animations.resize(2);
    scene.animations[0].name = "talk";
    scene.animations[1].name = "1";  // a name that looks like an index wins as a name
    EXPECT_EQ(&preskin::findAnimation(scene, "talk"), &scene.animations[0]);
    EXPECT_EQ(&preskin::findAnimation(scene, "0"), &scene.animations[0]);
    EXPECT_EQ(&preskin::findAnimation(scene, "1"), &scene.animations[1]);
    try {
        preskin::findAnimation(scene, "walk\n");
        FAIL() << "no error";
    } catch (const preskin::Error& e) {
        const std::string message = e.what();
        EXPECT_EQ(message, "scene.gltf: no animation named 'walk?' (animations: 0 'talk', 1 '1')");
    }
    EXPECT_THROW(preskin::findAnimation(scene, "2"), preskin::Error);
    scene.animations.clear();
    try {
        preskin::findAnimation(scene, "0");
        FAIL() << "no error";
    } catch (const preskin::Error& e) {
        EXPECT_NE(std::string(e.what()).find("the scene has no animations"), std::string::npos) << e.what();
    }
}

}  // namespace preskin::test
