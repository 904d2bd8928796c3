// preskinSampleLevels (shaders/preskin/mip_levels.glsl), the hand-made trilinear filtering the
// skin's per-channel normal samples use, against the sampler's own: textureLod of the same
// mipmapped texture (linear within and between levels, as the scene's samplers) at each of the
// four levels of detail (three biased ones and the unbiased one, as skin reads its normal map),
// run by tests/reference/shaders/mip_levels.comp. Levels of detail: random bases over and beyond the
// chain (negative and past the last level, which clamp) plus biases with spans up to five levels
// and of either sign, as normalLodBias() and authored biases give; the number of whole levels
// read is normalLevelCount()'s, with the unbiased level in its span. Tolerance: 2/255, what a driver that
// filters 8-bit texels in fixed point (lavapipe quantises the level fraction and rounds each
// level's bilinear result) may differ from filtering in float. One level fewer than
// normalLevelCount() must fail the same comparison, so the count is needed, not generous.
#include "support/ComputeDispatch.h"
#include "support/GpuTest.h"

#include <preskin/SkinParameters.h>

#include "vk/Check.h"
#include "vk/Resources.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

namespace preskin::test {
namespace {

struct Query {
    glm::vec2 uv;
    glm::vec4 lod;
};

struct Result {
    std::array<glm::vec3, 4> levels;     // preskinSampleLevels
    std::array<glm::vec3, 4> reference;  // textureLod
};

class MipLevels : public GpuTest {
protected:
    // A 64x64 RGBA8 texture with its full chain (7 levels) of linear blits.
    static constexpr uint32_t kSize = 64;

    std::vector<Result> run(const std::vector<Query>& queries, int levelCount) {
        const vk::Device& device = ContextAccess::core(context());
        const VkDevice d = device.device();
        // Structure at every scale, so every level differs from its neighbours: quadrants of
        // different colours, an 8x8 checker and per-texel noise.
        std::mt19937 rng(7);
        std::uniform_int_distribution<int> noise(0, 63);
        std::vector<uint8_t> texels(size_t(kSize) * kSize * 4);
        for (uint32_t y = 0; y < kSize; ++y)
            for (uint32_t x = 0; x < kSize; ++x)
                for (uint32_t c = 0; c < 4; ++c) {
                    const uint32_t quadrant = (x / 32) + 2 * (y / 32);
                    const int value = int(((quadrant + c) % 4) * 48) + int(((x / 8 + y / 8 + c) % 2) * 32) + noise(rng);
                    texels[(size_t(y) * kSize + x) * 4 + c] = static_cast<uint8_t>(std::min(value, 255));
                }
        vk::Image image(
            device,
            {VK_FORMAT_R8G8B8A8_UNORM, kSize, kSize, vk::mipLevelCount(kSize, kSize),
             VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT});
        image.uploadAndGenerateMips(texels.data(), texels.size());

        VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
        si.magFilter = VK_FILTER_LINEAR;
        si.minFilter = VK_FILTER_LINEAR;
        si.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
        si.addressModeU = si.addressModeV = si.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
        si.maxLod = VK_LOD_CLAMP_NONE;
        VkSampler sampler = VK_NULL_HANDLE;
        PRESKIN_VK(vkCreateSampler(d, &si, nullptr, &sampler));

        std::vector<glm::vec4> inputData;
        for (const Query& q : queries) {
            inputData.emplace_back(q.uv, q.lod.x, q.lod.y);
            inputData.emplace_back(q.lod.z, q.lod.w, 0.0f, 0.0f);
        }
        const VkDeviceSize inBytes = inputData.size() * sizeof(glm::vec4);
        const VkDeviceSize outBytes = queries.size() * 8 * sizeof(glm::vec4);
        vk::Buffer inputs(device, inBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
        inputs.upload(inputData.data(), inBytes);
        vk::Buffer outputs(device, outBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
        const uint32_t count = static_cast<uint32_t>(queries.size());
        const ComputeResource resources[] = {
            imageResource(sampler, image.view()),
            bufferResource(VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, inputs.handle(), inBytes),
            bufferResource(VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, outputs.handle(), outBytes)};
        const uint32_t push[2] = {count, static_cast<uint32_t>(levelCount)};
        dispatchCompute(device, "mip_levels.comp", resources, push, count);
        std::vector<Result> results(queries.size());
        const auto* out = static_cast<const glm::vec4*>(outputs.mapped());
        for (size_t i = 0; i < results.size(); ++i)
            for (size_t c = 0; c < 4; ++c) {
                results[i].levels[c] = glm::vec3(out[8 * i + c]);
                results[i].reference[c] = glm::vec3(out[8 * i + 4 + c]);
            }
        vkDestroySampler(d, sampler, nullptr);
        return results;
    }
};

// Largest difference from textureLod over the queries, in 8-bit steps.
float largestError(const std::vector<Result>& results) {
    float worst = 0.0f;
    for (const Result& r : results)
        for (size_t c = 0; c < 4; ++c) {
            const glm::vec3 d = glm::abs(r.levels[c] - r.reference[c]) * 255.0f;
            worst = std::max(worst, std::max(d.x, std::max(d.y, d.z)));
        }
    return worst;
}

TEST_F(MipLevels, SharedWholeLevelsMatchTrilinearSamplesForEveryBiasSpan) {
    const uint32_t mips = vk::mipLevelCount(kSize, kSize);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    // One set of biases per span, with the span's lowest bias anywhere in [-2, 1].
    for (float span : {0.0f, 0.3f, 1.0f, 1.47f, 2.0f, 2.6f, 5.0f}) {
        const float low = -2.0f + 3.0f * unit(rng);
        glm::vec3 bias(low + span, low + unit(rng) * span, low);
        std::shuffle(&bias[0], &bias[0] + 3, rng);
        const int levelCount = normalLevelCount(bias, mips, true);
        std::vector<Query> queries;
        for (int i = 0; i < 512; ++i) {
            const float base = -1.5f + (float(mips) + 2.0f) * unit(rng);  // below, over and past the chain
            queries.push_back(
                {{unit(rng) * 3.0f - 1.0f, unit(rng) * 3.0f - 1.0f}, glm::vec4(glm::vec3(base) + bias, base)});
        }
        EXPECT_LE(largestError(run(queries, levelCount)), 2.0f)
            << "span " << span << ", biases " << bias.x << " " << bias.y << " " << bias.z << ", " << levelCount
            << " levels";
        // Whenever the count is below the chain's length, one level fewer must show.
        if (levelCount > 1 && levelCount < int(mips)) {
            EXPECT_GT(largestError(run(queries, levelCount - 1)), 2.0f)
                << "span " << span << ": " << levelCount - 1 << " levels were enough";
        }
    }
}

TEST(NormalLevelCount, SpansTheBiasesAndStaysWithinTheChain) {
    EXPECT_EQ(normalLevelCount(glm::vec3(0.0f), 12), 2);                    // one level of detail: trilinear
    EXPECT_EQ(normalLevelCount(glm::vec3(1.93f, 0.70f, 0.46f), 12), 4);     // the bundled head
    EXPECT_EQ(normalLevelCount(glm::vec3(-1.0f, 1.0f, 0.0f), 12), 4);       // span 2
    EXPECT_EQ(normalLevelCount(glm::vec3(3.0f, 0.5f, 0.5f), 12), 5);        // span 2.5
    EXPECT_EQ(normalLevelCount(glm::vec3(40.0f, 0.0f, 0.0f), 12), 12);      // never more than the chain
    EXPECT_EQ(normalLevelCount(glm::vec3(1.0f, 0.0f, 0.0f), 1), 1);         // no mips
    EXPECT_EQ(normalLevelCount(glm::vec3(NAN, 0.0f, 0.0f), 9), 9);          // not a number: every level
    EXPECT_EQ(normalLevelCount(glm::vec3(3.0f, 2.5f, 2.2f), 12), 3);        // span 0.8
    EXPECT_EQ(normalLevelCount(glm::vec3(3.0f, 2.5f, 2.2f), 12, true), 5);  // span 3 with the unbiased level
}

}  // namespace
}  // namespace preskin::test
