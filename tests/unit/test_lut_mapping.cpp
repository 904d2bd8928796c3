// Tests of the LUT texture layout and mapping: LutTable::sample follows Vulkan's LINEAR +
// CLAMP_TO_EDGE rule (checked against a bilinear filter written here), axis node values sit on
// texel centres through the shared mapping functions of shaders/shared/lut_mapping.h, the
// LutMapping layout, the diffuse table's bilinear footprints (one texel per channel holds the
// 2x2 texels a bilinear lookup needs, as shaders/preskin/lut.glsl reads them), and bake-settings
// validation.
#include "shared/lut_mapping.h"

#include <preskin/Error.h>
#include <preskin/LutSet.h>

#include "skin/Half.h"

#include <gtest/gtest.h>

#include <random>

namespace preskin {
namespace {

// Vulkan spec, texel filtering: u' = u * size - 0.5, i0 = floor(u'), alpha = frac(u'),
// indices clamped to the edge. In double, for comparison.
glm::dvec3 referenceBilinear(const LutTable& t, double u, double v) {
    const double x = u * t.width() - 0.5;
    const double y = v * t.height() - 0.5;
    const double x0 = std::floor(x), y0 = std::floor(y);
    const double ax = x - x0, ay = y - y0;
    auto at = [&](double ix, double iy) {
        const int cx = std::clamp(static_cast<int>(ix), 0, t.width() - 1);
        const int cy = std::clamp(static_cast<int>(iy), 0, t.height() - 1);
        return glm::dvec3(t.texel(cx, cy));
    };
    return (1 - ay) * ((1 - ax) * at(x0, y0) + ax * at(x0 + 1, y0)) + ay * ((1 - ax) * at(x0, y0 + 1) + ax * at(x0 + 1, y0 + 1));
}

TEST(LutMapping, SamplerFollowsTheVulkanRule) {
    LutTable t;
    t.x.size = 5;
    t.y.size = 3;
    std::mt19937 rng(2);
    std::uniform_real_distribution<float> value(-1.0f, 2.0f);
    t.rgb.resize(5 * 3 * 3);
    for (float& f : t.rgb) f = value(rng);
    // Texel centres return the texel; corners and outside clamp to the edge texels.
    for (int iy = 0; iy < 3; ++iy)
        for (int ix = 0; ix < 5; ++ix) EXPECT_EQ(t.sample({(static_cast<float>(ix) + 0.5f) / 5.0f, (static_cast<float>(iy) + 0.5f) / 3.0f}), t.texel(ix, iy));
    EXPECT_EQ(t.sample({0.0f, 0.0f}), t.texel(0, 0));
    EXPECT_EQ(t.sample({-3.0f, 7.0f}), t.texel(0, 2));
    EXPECT_EQ(t.sample({1.0f, 1.0f}), t.texel(4, 2));
    std::uniform_real_distribution<double> uv(-0.2, 1.2);
    for (int i = 0; i < 1000; ++i) {
        const double u = uv(rng), v = uv(rng);
        const glm::vec3 got = t.sample({static_cast<float>(u), static_cast<float>(v)});
        const glm::dvec3 want = referenceBilinear(t, static_cast<float>(u), static_cast<float>(v));
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(got[c], want[c], 2e-6) << u << ", " << v;
    }
}

// Footprint texel (c W + x, y) holds channel c of (x, y), (x + 1, y), (x, y + 1), (x + 1, y + 1),
// clamped; filtering by hand from it, as lut.glsl does, equals Vulkan's LINEAR filter of the table.
TEST(LutMapping, FootprintsFilterLikeTheTable) {
    LutTable t;
    t.x.size = 7;
    t.y.size = 4;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> value(0.0f, 1.0f);
    t.rgb.resize(7 * 4 * 3);
    for (float& f : t.rgb) f = skin::roundToHalf(value(rng));
    const std::vector<uint16_t> footprints = t.footprintsRgba16f();
    ASSERT_EQ(footprints.size(), size_t(3 * 7 * 4 * 4));
    auto corner = [&](int c, int x, int y, int k) {
        return double(skin::halfBitsToFloat(footprints[(size_t(y) * 21 + size_t(c) * 7 + size_t(x)) * 4 + size_t(k)]));
    };
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 7; ++x)
            for (int c = 0; c < 3; ++c) {
                EXPECT_EQ(corner(c, x, y, 0), t.texel(x, y)[c]);
                EXPECT_EQ(corner(c, x, y, 1), t.texel(std::min(x + 1, 6), y)[c]);
                EXPECT_EQ(corner(c, x, y, 2), t.texel(x, std::min(y + 1, 3))[c]);
                EXPECT_EQ(corner(c, x, y, 3), t.texel(std::min(x + 1, 6), std::min(y + 1, 3))[c]);
            }
    std::uniform_real_distribution<double> uv(-0.2, 1.2);
    for (int i = 0; i < 1000; ++i) {
        const double u = uv(rng), v = uv(rng);
        const glm::dvec3 want = referenceBilinear(t, u, v);
        const double y = v * 4 - 0.5, y0 = std::clamp(std::floor(y), 0.0, 3.0), fy = std::clamp(y - y0, 0.0, 1.0);
        const double x = u * 7 - 0.5, x0 = std::clamp(std::floor(x), 0.0, 6.0), fx = std::clamp(x - x0, 0.0, 1.0);
        for (int c = 0; c < 3; ++c) {
            const int ix = int(x0), iy = int(y0);
            const double near = (1 - fx) * corner(c, ix, iy, 0) + fx * corner(c, ix, iy, 1);
            const double far = (1 - fx) * corner(c, ix, iy, 2) + fx * corner(c, ix, iy, 3);
            ASSERT_NEAR((1 - fy) * near + fy * far, want[c], 1e-9) << u << ", " << v;
        }
    }
    EXPECT_THROW(lutFootprints(std::vector<uint16_t>(10), 7, 4), Error);
}

void expectNodesOnTexelCentres(const LutTable& table, const std::function<glm::vec2(double)>& uvOfValue, bool alongX) {
    const LutAxis& axis = alongX ? table.x : table.y;
    for (int i = 0; i < axis.size; ++i) {
        const double value = axis.valueAt(i);
        EXPECT_NEAR(axis.nodeCoordinate(value), i, 1e-9) << table.name << " node " << i;
        if (std::isinf(value)) continue;
        const glm::vec2 uv = uvOfValue(value);
        EXPECT_NEAR(alongX ? uv.x : uv.y, (i + 0.5) / axis.size, 2e-6) << table.name << " node " << i << " value " << value;
    }
}

TEST(LutMapping, AxisNodesSitOnTexelCentres) {
    const LutSet& luts = LutSet::loadDefault();
    const gpu::LutMapping m = lutMapping(luts);
    expectNodesOnTexelCentres(luts.diffuse(), [&](double v) { return gpu::preskinDiffuseLutUv(m, static_cast<float>(v), 0.0f); }, true);
    expectNodesOnTexelCentres(luts.diffuse(), [&](double v) { return gpu::preskinDiffuseLutUv(m, 0.0f, static_cast<float>(v)); }, false);
    expectNodesOnTexelCentres(luts.penumbra(), [&](double v) { return gpu::preskinPenumbraLutUv(m, static_cast<float>(v), 0.0f); }, true);
    const double reference = luts.penumbraReferenceWidthMm();
    expectNodesOnTexelCentres(
        luts.penumbra(), [&](double v) { return gpu::preskinPenumbraLutUv(m, 0.0f, static_cast<float>(v * reference)); }, false);
    expectNodesOnTexelCentres(luts.shTransfer(), [&](double v) { return gpu::preskinShTransferLutUv(m, static_cast<float>(v), 0); }, true);
    for (int band = 0; band < 3; ++band)
        EXPECT_FLOAT_EQ(gpu::preskinShTransferLutUv(m, 0.3f, band).y, (static_cast<float>(band) + 0.5f) / 3.0f);
    expectNodesOnTexelCentres(luts.transmittance(), [&](double v) { return gpu::preskinTransmittanceLutUv(m, static_cast<float>(v)); }, true);
    EXPECT_EQ(luts.diffuse().x.valueAt(luts.diffuse().width() / 2), 0.0);  // NoL = 0 is a texel centre
}

TEST(LutMapping, LookupsAtNodesReturnTexels) {
    const LutSet& luts = LutSet::loadDefault();
    for (int iy : {0, 1, 17, 128, 255}) {
        for (int ix : {0, 3, 127, 128, 129, 255}) {
            const glm::vec3 got = luts.lookupDiffuse(static_cast<float>(luts.diffuse().x.valueAt(ix)),
                                                     static_cast<float>(luts.diffuse().y.valueAt(iy)));
            const glm::vec3 want = luts.diffuse().texel(ix, iy);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], 1e-4) << ix << ", " << iy;
        }
    }
    // Curvature beyond the range clamps to the last row on either side.
    const float max = static_cast<float>(luts.settings().curvatureMaxPerMm);
    EXPECT_EQ(luts.lookupDiffuse(0.0f, 50.0f), luts.lookupDiffuse(0.0f, max));
    EXPECT_EQ(luts.lookupDiffuse(0.5f, -50.0f), luts.lookupDiffuse(0.5f, -max));
}

TEST(LutMapping, SharedStructLayout) {
    EXPECT_EQ(sizeof(gpu::LutMapping), 128u);
    EXPECT_EQ(offsetof(gpu::LutMapping, transmittance), 112u);
    const gpu::LutMapping m = lutMapping(LutSet::loadDefault());
    EXPECT_FLOAT_EQ(m.shLambert.x, 3.14159265f);
    EXPECT_FLOAT_EQ(m.diffuseNoL.x, 128.5f / 256.0f);
}

TEST(LutMapping, RgbaHalfExport) {
    const LutTable& table = LutSet::loadDefault().diffuse();
    const std::vector<uint16_t> rgba = table.rgba16f();
    ASSERT_EQ(rgba.size(), static_cast<size_t>(table.width() * table.height() * 4));
    EXPECT_EQ(rgba[3], 0x3c00u);                      // alpha 1.0
    const size_t flat = size_t(table.height() / 2) * size_t(table.width()) * 4;
    EXPECT_EQ(rgba[flat + 4 * size_t(table.width() - 1)], 0x3c00u);  // flat row, NoL = 1: 1.0
    EXPECT_EQ(rgba[flat], 0u);                                       // flat row, NoL = -1: 0
}

TEST(LutBakeSettingsTest, AbsurdSizesAreRefused) {
    for (int size : {0, -5, 15, 4097, 1000000000}) {
        try {
            LutBakeSettings::withSize(size).validate();
            FAIL() << size;
        } catch (const Error& e) {
            EXPECT_EQ(std::string(e.what()),
                      "LutBakeSettings: diffuseNoLSize: must be an integer in [16, 4096], got " + std::to_string(size));
        }
        EXPECT_THROW(LutSet::bake(DiffusionProfile::deonLuebke(), LutBakeSettings::withSize(size)), Error);
    }
    LutBakeSettings s;
    s.curvatureMaxPerMm = 0.0;
    EXPECT_THROW(s.validate(), Error);
    s.curvatureMaxPerMm = std::nan("");
    EXPECT_THROW(s.validate(), Error);
    EXPECT_NO_THROW(LutBakeSettings{}.validate());
}

TEST(LutBakeSettingsTest, ProgressIsMonotoneAndEndsAtOne) {
    std::vector<double> seen;
    LutSet::bake(DiffusionProfile::deonLuebke(), LutBakeSettings::withSize(16), [&](double f) { seen.push_back(f); });
    ASSERT_FALSE(seen.empty());
    for (size_t i = 1; i < seen.size(); ++i) EXPECT_GE(seen[i], seen[i - 1]);
    EXPECT_EQ(seen.back(), 1.0);
}

}  // namespace
}  // namespace preskin
