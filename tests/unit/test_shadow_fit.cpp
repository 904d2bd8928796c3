// The directional shadow map's fit (render/ShadowFit.h): every point of the skin in view lands
// inside the map with its filter margin, the casters' bounding sphere inside the depth range,
// and texels shrink with the skin in view (not the scene); without skin, or with the skin out of
// view, the map covers the whole scene as before.
#include "render/ShadowFit.h"
#include "support/TestScenes.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <random>

namespace preskin::test {
namespace {

View lookAt(const glm::vec3& eye, const glm::vec3& target, float yfov) {
    return perspectiveView(glm::inverse(glm::lookAt(eye, target, glm::vec3(0.0f, 1.0f, 0.0f))), yfov, 1.0f, 0.05f,
                           20.0f);
}

TEST(ShadowFit, CoversTheSkinInViewAndTheCastersDepth) {
    Bounds casters;  // a 4 m room
    casters.extend(glm::vec3(-2.0f));
    casters.extend(glm::vec3(2.0f));
    Bounds skin;  // a 0.3 m head in it
    skin.extend(glm::vec3(-0.15f, 1.0f, -0.15f));
    skin.extend(glm::vec3(0.15f, 1.3f, 0.15f));
    const glm::vec3 direction = glm::normalize(glm::vec3(0.4f, -1.0f, -0.3f));
    const uint32_t mapSize = 1024;
    const View close = lookAt(glm::vec3(0.0f, 1.15f, 0.6f), glm::vec3(0.0f, 1.15f, 0.0f), 0.5f);
    const ShadowFit fit = fitDirectionalShadow(casters, skin, close, direction, mapSize);
    // Texels: the whole room would give 2 * 3.46 m / 1024; the head in view under a tenth of it.
    EXPECT_LT(fit.texelSizeM, 0.1f * (2.0f * 0.5f * glm::length(casters.extent()) / float(mapSize)));
    // Every skin point in view projects into the map, 8 texels from its border.
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    int inView = 0;
    for (int i = 0; i < 20000; ++i) {
        const glm::vec3 p = skin.min + glm::vec3(unit(rng), unit(rng), unit(rng)) * skin.extent();
        const glm::vec4 clip = close.eye().clipFromWorld() * glm::vec4(p, 1.0f);
        if (std::abs(clip.x) > clip.w || std::abs(clip.y) > clip.w || clip.w <= 0.0f) continue;
        ++inView;
        const glm::vec4 s = fit.clipFromWorld * glm::vec4(p, 1.0f);
        const float margin = 2.0f * 8.0f / float(mapSize) * 0.99f;
        EXPECT_LE(std::abs(s.x), 1.0f - margin) << i;
        EXPECT_LE(std::abs(s.y), 1.0f - margin) << i;
    }
    EXPECT_GT(inView, 1000);
    // Every caster corner is inside the depth range.
    for (int c = 0; c < 8; ++c) {
        const glm::vec3 p((c & 1) ? casters.max.x : casters.min.x, (c & 2) ? casters.max.y : casters.min.y,
                          (c & 4) ? casters.max.z : casters.min.z);
        const float z = (fit.clipFromWorld * glm::vec4(p, 1.0f)).z;
        EXPECT_GE(z, -1e-5f);
        EXPECT_LE(z, 1.0f + 1e-5f);
    }
    EXPECT_NEAR(fit.depthRangeM, glm::length(casters.extent()), 1e-4f);
}

TEST(ShadowFit, CoversTheSkinSeenByAnyEye) {
    Bounds casters;
    casters.extend(glm::vec3(-2.0f));
    casters.extend(glm::vec3(2.0f));
    Bounds skin;
    skin.extend(glm::vec3(-0.15f, 1.0f, -0.15f));
    skin.extend(glm::vec3(0.15f, 1.3f, 0.15f));
    const glm::vec3 direction = glm::normalize(glm::vec3(-0.3f, -1.0f, 0.5f));
    const uint32_t mapSize = 1024;
    // Eye 0 looks away from the skin, eye 1 at it: the fit must follow eye 1.
    View view = lookAt(glm::vec3(0.0f, 1.15f, 0.6f), glm::vec3(0.0f, 1.15f, 3.0f), 0.5f);
    view.eyes.push_back(lookAt(glm::vec3(0.05f, 1.15f, 0.6f), glm::vec3(0.0f, 1.15f, 0.0f), 0.5f).eye());
    const ShadowFit fit = fitDirectionalShadow(casters, skin, view, direction, mapSize);
    EXPECT_LT(fit.texelSizeM, 0.1f * (2.0f * 0.5f * glm::length(casters.extent()) / float(mapSize)));
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    int inView = 0;
    for (int i = 0; i < 20000; ++i) {
        const glm::vec3 p = skin.min + glm::vec3(unit(rng), unit(rng), unit(rng)) * skin.extent();
        const glm::vec4 clip = view.eye(1).clipFromWorld() * glm::vec4(p, 1.0f);
        if (std::abs(clip.x) > clip.w || std::abs(clip.y) > clip.w || clip.w <= 0.0f) continue;
        ++inView;
        const glm::vec4 s = fit.clipFromWorld * glm::vec4(p, 1.0f);
        EXPECT_LE(std::abs(s.x), 1.0f) << i;
        EXPECT_LE(std::abs(s.y), 1.0f) << i;
    }
    EXPECT_GT(inView, 1000);
}

TEST(ShadowFit, WithoutSkinInViewTheSceneIsCovered) {
    Bounds casters;
    casters.extend(glm::vec3(-1.0f));
    casters.extend(glm::vec3(1.0f));
    const glm::vec3 direction(0.0f, -1.0f, 0.0f);
    const View view = lookAt(glm::vec3(0.0f, 0.0f, 5.0f), glm::vec3(0.0f), 0.5f);
    const float sceneTexel = 2.0f * std::sqrt(3.0f) / 512.0f;
    EXPECT_NEAR(fitDirectionalShadow(casters, Bounds{}, view, direction, 512).texelSizeM, sceneTexel, 1e-6f);
    Bounds behind;  // skin behind the camera
    behind.extend(glm::vec3(-0.1f, -0.1f, 8.0f));
    behind.extend(glm::vec3(0.1f, 0.1f, 8.2f));
    EXPECT_NEAR(fitDirectionalShadow(casters, behind, view, direction, 512).texelSizeM, sceneTexel, 1e-6f);
}

TEST(ShadowFit, ReceiversAreTheSkinPrimitives) {
    Material skin;
    skin.skin = SkinMaterial{};
    Material other;
    Primitive a = test::makeBox(glm::vec3(0.2f));
    a.material = 0;
    Primitive b = test::makeBox(glm::vec3(1.0f));
    b.material = 1;
    const Scene scene = test::makeScene(
        {{a, glm::translate(glm::mat4(1.0f), glm::vec3(3.0f, 0.0f, 0.0f))}, {b, glm::mat4(1.0f)}}, {skin, other});
    const Bounds r = skinReceiverBounds(scene).worldBounds(restPose(scene));
    EXPECT_NEAR(r.min.x, 2.9f, 1e-5f);
    EXPECT_NEAR(r.max.x, 3.1f, 1e-5f);
    EXPECT_NEAR(r.extent().y, 0.2f, 1e-5f);
}

}  // namespace
}  // namespace preskin::test
