// The frame's light array (frameLightRecords, converted in parallel chunks) against the order the
// shaders rely on, built here one light at a time: the shadow light first, the other directional
// lights, then the point and spot lights in their order, each grid record naming its entry.
#include "lights/ClusterAssign.h"

#include <preskin/LightRecord.h>

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

namespace preskin::test {
namespace {

bool sameRecord(const gpu::GpuLight& a, const gpu::GpuLight& b) { return std::memcmp(&a, &b, sizeof(a)) == 0; }

std::vector<Light> mixedLights(size_t count, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::vector<Light> lights(count);
    for (size_t i = 0; i < count; ++i) {
        Light& l = lights[i];
        const uint32_t kind = rng() % 16;
        l.type = kind == 0 ? LightType::Directional : kind < 9 ? LightType::Point : LightType::Spot;
        l.positionWs = glm::vec3(u(rng), u(rng), u(rng));
        l.directionWs = glm::vec3(u(rng), u(rng), u(rng) - 1.5f);
        l.range = 0.5f + u(rng) * 0.4f;
        l.intensity = 2.0f + u(rng);
        l.outerConeAngle = 0.6f + 0.3f * u(rng);
        l.castsShadow = l.type == LightType::Directional && rng() % 4 == 0;
    }
    return lights;
}

TEST(LightRecords, FrameArrayIsTheShadowLightThenDirectionalThenLocalLightsInOrder) {
    // Several of the conversion's chunks (4,096 lights each), and the small cases.
    for (const size_t count : {size_t(0), size_t(1), size_t(37), size_t(4096), size_t(10000)}) {
        const std::vector<Light> lights = mixedLights(count, static_cast<uint32_t>(count) + 7u);
        for (const bool withShadow : {false, true}) {
            const int shadowLight = withShadow ? shadowLightIndex(lights) : -1;
            std::vector<gpu::GpuLight> expected;
            std::vector<ClusterLight> expectedLocal;
            if (shadowLight >= 0) expected.push_back(toGpuLight(lights[size_t(shadowLight)], true));
            for (size_t i = 0; i < lights.size(); ++i)
                if (lights[i].type == LightType::Directional && int(i) != shadowLight)
                    expected.push_back(toGpuLight(lights[i], false));
            const auto directional = static_cast<uint32_t>(expected.size());
            for (const Light& l : lights)
                if (l.type != LightType::Directional) {
                    expectedLocal.push_back(clusterLight(l, static_cast<uint32_t>(expected.size())));
                    expected.push_back(toGpuLight(l, false));
                }

            std::vector<gpu::GpuLight> records(3);  // stale contents are replaced
            std::vector<ClusterLight> local(5);
            EXPECT_EQ(frameLightRecords(lights, shadowLight, records, local), directional) << count;
            ASSERT_EQ(records.size(), expected.size()) << count;
            ASSERT_EQ(local.size(), expectedLocal.size()) << count;
            for (size_t i = 0; i < records.size(); ++i) EXPECT_TRUE(sameRecord(records[i], expected[i])) << i;
            for (size_t i = 0; i < local.size(); ++i) {
                EXPECT_EQ(local[i].index, expectedLocal[i].index) << i;
                EXPECT_EQ(local[i].index, directional + i) << i;
                EXPECT_EQ(local[i].positionWs, expectedLocal[i].positionWs) << i;
                EXPECT_EQ(local[i].rangeM, expectedLocal[i].rangeM) << i;
                EXPECT_EQ(local[i].spot, expectedLocal[i].spot) << i;
                EXPECT_EQ(local[i].cosOuter, expectedLocal[i].cosOuter) << i;
            }
        }
    }
}

}  // namespace
}  // namespace preskin::test
