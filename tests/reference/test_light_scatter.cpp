// scatterLights at a density (<preskin/LightScatter.h>): the number of lights whose volume (range
// sphere, spot cone: test_cluster_reference.h's insideLight, independent of the library) holds a
// point of the scene, counted over random points, against the density asked for, at 4,096 to
// 65,536 lights.
#include "reference/test_cluster_reference.h"

#include <preskin/Error.h>
#include <preskin/LightScatter.h>

#include <gtest/gtest.h>

#include <random>

namespace preskin::test {
namespace {

Bounds sceneBounds() {
    Bounds b;
    b.extend(glm::vec3(-1.0f, 0.0f, -0.5f));
    b.extend(glm::vec3(1.0f, 1.0f, 1.0f));
    return b;
}

// Mean number of lights holding a point, over `samples` points uniform in the scene's bounds.
double meanLightsPerPoint(const std::vector<Light>& lights, const Bounds& bounds, int samples) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    uint64_t total = 0;
    for (int i = 0; i < samples; ++i) {
        const glm::vec3 p = bounds.min + glm::vec3(u(rng), u(rng), u(rng)) * (bounds.max - bounds.min);
        for (const Light& l : lights) total += insideLight(l, glm::dvec3(p), 0.0) ? 1 : 0;
    }
    return double(total) / double(samples);
}

TEST(LightScatter, DensityHoldsTheLightsPerPointWhateverTheCount) {
    const Bounds bounds = sceneBounds();
    for (float density : {2.0f, 8.0f}) {
        for (uint32_t count : {4096u, 16384u, 65536u}) {
            const std::vector<Light> lights = scatterLights(bounds, count, 3, density);
            ASSERT_EQ(lights.size(), count);
            const double mean = meanLightsPerPoint(lights, bounds, count > 16384 ? 400 : 1500);
            EXPECT_NEAR(mean / double(density), 1.0, 0.08) << count << " lights at density " << density;
        }
    }
}

TEST(LightScatter, WithoutDensityTheRangesFollowTheScene) {
    const Bounds bounds = sceneBounds();
    const std::vector<Light> a = scatterLights(bounds, 500, 9);
    const std::vector<Light> b = scatterLights(bounds, 500, 9, 0.0f);
    ASSERT_EQ(a.size(), b.size());
    const float radius = 0.5f * glm::length(bounds.extent());
    for (size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].range, b[i].range);
        const float factor = a[i].range / radius / (a[i].type == LightType::Spot ? 1.5f : 1.0f);
        EXPECT_GE(factor, 0.15f - 1e-6f);
        EXPECT_LE(factor, 0.40f + 1e-6f);
    }
    // Lights per point grow with the count when the ranges follow the scene.
    EXPECT_GT(meanLightsPerPoint(scatterLights(bounds, 4096, 9), bounds, 200),
              3.0 * meanLightsPerPoint(scatterLights(bounds, 1024, 9), bounds, 200));
}

TEST(LightScatter, BadDensityIsRefused) {
    EXPECT_THROW(scatterLights(sceneBounds(), 10, 1, -1.0f), Error);
    EXPECT_THROW(scatterLights(sceneBounds(), 10, 1, std::nanf("")), Error);
    EXPECT_THROW(scatterLights(sceneBounds(), 10, 1, std::numeric_limits<float>::infinity()), Error);
}

}  // namespace
}  // namespace preskin::test
