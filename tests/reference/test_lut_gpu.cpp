// The GLSL LUT lookups of shaders/preskin/lut.glsl (run by tests/reference/shaders/lut_lookup.comp on
// the renderer's own LUT textures and sampler, render/GpuLuts) against LutSet's CPU lookups, over
// grids that include every axis end, values just inside and outside them, and far out-of-range
// inputs (which must clamp like the CPU). Tolerance per lookup: a GPU quantises the bilinear
// weights to subTexelPrecisionBits (LutTable.h), so it may differ from the exact bilinear value by
// up to 2^-bits of the spread of the 2x2 texels it blends along each of the two axes; plus
// float rounding. A lookup half a texel off, a wrong row or a missing clamp exceeds that.
// The tables are layers of array textures (as the renderer binds them, read through a
// PreskinProfileMix of one layer): once as the only layer, and once as layer 1 behind a larger
// set, so padded to the larger size and addressed through its own LutMapping.
#include "support/ComputeDispatch.h"
#include "support/GpuTest.h"

#include <preskin/Environment.h>
#include <preskin/LutSet.h>

#include "render/GpuLuts.h"
#include "vk/Check.h"
#include "vk/Pipeline.h"
#include "vk/Resources.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

namespace preskin::test {
namespace {

enum Table : int { kDiffuse = 0, kPenumbra = 1, kShTransfer = 2, kTransmittance = 3 };

struct Lookup {
    int table;
    float a;
    float b;
};

// Runs lut_lookup.comp over `lookups` and returns one RGB result per lookup.
std::vector<glm::vec3> runOnGpu(const vk::Device& device, const std::vector<const LutSet*>& layers, uint32_t layer,
                                const std::vector<Lookup>& lookups) {
    const GpuLuts gpuLuts(device, layers);
    const gpu::LutMapping mapping = gpuLuts.layers().at(layer).mapping;
    vk::Buffer uniforms(device, sizeof(mapping), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true);
    uniforms.upload(&mapping, sizeof(mapping));
    std::vector<glm::vec4> inputData;
    for (const Lookup& l : lookups) inputData.emplace_back(float(l.table), l.a, l.b, 0.0f);
    const VkDeviceSize bytes = inputData.size() * sizeof(glm::vec4);
    vk::Buffer inputs(device, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
    inputs.upload(inputData.data(), bytes);
    vk::Buffer outputs(device, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
    const auto images = gpuLuts.descriptors();
    std::vector<ComputeResource> resources{
        bufferResource(VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, uniforms.handle(), sizeof(mapping))};
    for (const VkDescriptorImageInfo& image : images)
        resources.push_back(imageResource(image.sampler, image.imageView));
    resources.push_back(bufferResource(VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, inputs.handle(), bytes));
    resources.push_back(bufferResource(VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, outputs.handle(), bytes));
    const uint32_t push[2] = {static_cast<uint32_t>(lookups.size()), layer};
    dispatchCompute(device, "lut_lookup.comp", resources, push, push[0]);

    std::vector<glm::vec3> results(lookups.size());
    const auto* out = static_cast<const glm::vec4*>(outputs.mapped());
    for (size_t i = 0; i < results.size(); ++i) results[i] = glm::vec3(out[i]);
    return results;
}

// Largest difference between the 2x2 texels a bilinear lookup at uv blends, per table axis
// (x: along u, y: along v), over the three channels.
glm::vec2 texelSpread(const LutTable& table, glm::vec2 uv) {
    auto pair = [](double coordinate, int size) {
        const double t = std::clamp(coordinate * size - 0.5, 0.0, double(size - 1));
        const int i0 = static_cast<int>(std::floor(t));
        return std::array<int, 2>{i0, std::min(i0 + 1, size - 1)};
    };
    const auto xs = pair(uv.x, table.width());
    const auto ys = pair(uv.y, table.height());
    glm::vec2 spread(0.0f);
    for (int j = 0; j < 2; ++j) {
        const glm::vec3 a = table.texel(xs[0], ys[j]);
        const glm::vec3 b = table.texel(xs[1], ys[j]);
        const glm::vec3 c = table.texel(xs[j], ys[0]);
        const glm::vec3 e = table.texel(xs[j], ys[1]);
        for (int ch = 0; ch < 3; ++ch) {
            spread.x = std::max(spread.x, std::abs(a[ch] - b[ch]));
            spread.y = std::max(spread.y, std::abs(c[ch] - e[ch]));
        }
    }
    return spread;
}

class LutGpu : public GpuTest {};

TEST_F(LutGpu, GlslLookupsMatchCpuLookups) {
    const LutSet& luts = LutSet::loadDefault();
    const float curvatureMax = float(luts.settings().curvatureMaxPerMm);
    const float thicknessMax = float(luts.transmittanceMaxMm());
    const float referenceWidth = float(luts.penumbraReferenceWidthMm());

    // Axis ends, values just inside and outside them, and far out of range.
    const std::vector<float> NoLs = {-1e6f, -1.5f, -1.0f, -0.999f, -0.75f, -0.5f,  -0.2f, -1e-3f, 0.0f, 1e-3f,
                                     0.1f,  0.3f,  0.5f,  0.7071f, 0.9f,   0.999f, 1.0f,  1.001f, 2.0f, 1e6f};
    const std::vector<float> curvatures = {-1.0f,
                                           0.0f,
                                           1e-5f,
                                           1e-3f,
                                           0.01f,
                                           0.05f,
                                           0.1f,
                                           0.2f,
                                           0.3333f,
                                           0.5f,
                                           0.75f * curvatureMax,
                                           0.999f * curvatureMax,
                                           curvatureMax,
                                           1.001f * curvatureMax,
                                           3.0f * curvatureMax,
                                           1e6f};
    const std::vector<float> shadows = {-1.0f, -1e-3f, 0.0f,  1e-3f,    0.00135f, 0.01f, 0.1f,   0.3f, 0.5f,
                                        0.7f,  0.9f,   0.99f, 0.99865f, 0.999f,   1.0f,  1.001f, 2.0f};
    const std::vector<float> widths = {-1.0f,
                                       0.0f,
                                       1e-4f,
                                       0.01f,
                                       0.1f * referenceWidth,
                                       0.5f * referenceWidth,
                                       referenceWidth,
                                       2.0f * referenceWidth,
                                       10.0f * referenceWidth,
                                       100.0f * referenceWidth,
                                       1e4f,
                                       1e7f};
    const std::vector<float> thicknesses = {-1.0f,
                                            0.0f,
                                            1e-4f,
                                            0.01f,
                                            0.05f,
                                            0.1f,
                                            0.25f,
                                            0.5f,
                                            1.0f,
                                            2.0f,
                                            0.5f * thicknessMax,
                                            0.999f * thicknessMax,
                                            thicknessMax,
                                            1.001f * thicknessMax,
                                            10.0f * thicknessMax,
                                            1e6f};

    std::vector<Lookup> lookups;
    for (float n : NoLs)
        for (float c : curvatures) lookups.push_back({kDiffuse, n, c});
    for (float s : shadows)
        for (float w : widths) lookups.push_back({kPenumbra, s, w});
    for (float c : curvatures)
        for (int band = 0; band < 3; ++band) lookups.push_back({kShTransfer, c, float(band)});
    for (float t : thicknesses) lookups.push_back({kTransmittance, t, 0.0f});
    // Plus random in-range inputs, which land between texel centres.
    std::mt19937 rng(20240607u);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (int i = 0; i < 4000; ++i) {
        lookups.push_back({kDiffuse, 2.0f * unit(rng) - 1.0f, curvatureMax * unit(rng)});
        lookups.push_back({kPenumbra, unit(rng), 4.0f * referenceWidth * unit(rng)});
    }
    for (int i = 0; i < 1000; ++i) {
        lookups.push_back({kShTransfer, curvatureMax * unit(rng), float(i % 3)});
        lookups.push_back({kTransmittance, thicknessMax * unit(rng), 0.0f});
    }

    const LutSet larger = LutSet::bake(DiffusionProfile::burley({0.8, 0.5, 0.4}, {1.0, 0.4, 0.25}),
                                       LutBakeSettings::withSize(luts.diffuse().width() + 44));
    const vk::Device& device = ContextAccess::core(context());
    for (const bool padded : {false, true}) {
        SCOPED_TRACE(padded ? "layer 1, padded" : "one layer");
        const std::vector<glm::vec3> gpuResults =
            padded ? runOnGpu(device, {&larger, &luts}, 1, lookups) : runOnGpu(device, {&luts}, 0, lookups);
        const uint32_t bits = device.properties().limits.subTexelPrecisionBits;
        ASSERT_GE(bits, 4u) << "Vulkan requires at least 4 sub-texel precision bits";
        const double weightStep = std::ldexp(1.0, -int(bits));

        const char* names[] = {"diffuse", "penumbra", "SH transfer", "transmittance"};
        std::array<int, 4> failures{};
        std::array<double, 4> worst{};         // largest |GPU - CPU|
        std::array<double, 4> worstRatio{};    // largest |GPU - CPU| / tolerance
        std::array<double, 4> largestValue{};  // to show the errors are not vacuous
        std::string firstFailures;
        for (size_t i = 0; i < lookups.size(); ++i) {
            const Lookup& l = lookups[i];
            glm::vec3 cpu;
            glm::vec2 spread;
            switch (l.table) {
            case kDiffuse:
                cpu = luts.lookupDiffuse(l.a, l.b);
                spread = texelSpread(luts.diffuse(), luts.diffuseUv(l.a, l.b));
                break;
            case kPenumbra:
                cpu = luts.lookupPenumbra(l.a, l.b);
                spread = texelSpread(luts.penumbra(), luts.penumbraUv(l.a, l.b));
                break;
            case kShTransfer: {
                const int band = static_cast<int>(l.b);
                cpu = luts.lookupShTransfer(l.a)[size_t(band)];
                // The table holds A_l relative to Lambert's coefficient; the lookup multiplies it back.
                spread = texelSpread(luts.shTransfer(), luts.shTransferUv(l.a, band)) * kLambertBands[band];
                break;
            }
            default:
                cpu = luts.lookupTransmittance(l.a);
                spread = texelSpread(luts.transmittance(), luts.transmittanceUv(l.a));
                break;
            }
            const glm::vec3 got = gpuResults[i];
            const double magnitude =
                std::max({1.0, double(std::abs(cpu.r)), double(std::abs(cpu.g)), double(std::abs(cpu.b))});
            const double tolerance = weightStep * double(spread.x + spread.y) + 2e-6 * magnitude;
            double error = 0.0;
            for (int c = 0; c < 3; ++c) error = std::max(error, double(std::abs(got[c] - cpu[c])));
            const auto t = size_t(l.table);
            worst[t] = std::max(worst[t], error);
            worstRatio[t] = std::max(worstRatio[t], error / tolerance);
            largestValue[t] = std::max(largestValue[t], double(std::max({cpu.r, cpu.g, cpu.b})));
            if (!(error <= tolerance) && failures[t]++ < 5)
                firstFailures += std::string(names[t]) + "(" + std::to_string(l.a) + ", " + std::to_string(l.b) +
                    "): GPU (" + std::to_string(got.r) + ", " + std::to_string(got.g) + ", " + std::to_string(got.b) +
                    ") CPU (" + std::to_string(cpu.r) + ", " + std::to_string(cpu.g) + ", " + std::to_string(cpu.b) +
                    "), tolerance " + std::to_string(tolerance) + "\n";
        }
        for (size_t t = 0; t < 4; ++t) {
            EXPECT_EQ(failures[t], 0) << names[t] << ": " << failures[t] << " lookups outside tolerance";
            EXPECT_GT(largestValue[t], 0.5) << names[t] << ": the grid should reach large table values";
            std::printf(
                "[ lut gpu  ] %s %-13s worst |GPU - CPU| %.3g, worst error / tolerance %.3f (%u sub-texel bits)\n",
                padded ? "padded layer" : "one layer   ", names[t], worst[t], worstRatio[t], bits);
        }
        EXPECT_TRUE(firstFailures.empty()) << firstFailures;
    }
}

}  // namespace
}  // namespace preskin::test
