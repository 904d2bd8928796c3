// Tests of the LUT texture layout and mapping: LutTable::sample follows Vulkan's LINEAR +
// CLAMP_TO_EDGE rule (checked against a bilinear filter written here), axis node values sit on
// texel centres through the shared mapping functions of shaders/shared/lut_mapping.h, the
// LutMapping layout, the tables' channel planes (each channel a plane of its own, gathered 2x2
// texels at a time and filtered by hand, as shaders/preskin/lut.glsl reads them), and
// bake-settings validation.
#include "shared/lut_mapping.h"

#include <preskin/Error.h>
#include <preskin/LutSet.h>

#include "skin/Half.h"

#include <gtest/gtest.h>

#include <random>

namespace preskin::test {
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
    return (1 - ay) * ((1 - ax) * at(x0, y0) + ax * at(x0 + 1, y0)) +
        ay * ((1 - ax) * at(x0, y0 + 1) + ax * at(x0 + 1, y0 + 1));
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
        for (int ix = 0; ix < 5; ++ix)
            EXPECT_EQ(t.sample({(static_cast<float>(ix) + 0.5f) / 5.0f, (static_cast<float>(iy) + 0.5f) / 3.0f}),
                      t.texel(ix, iy));
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

// Plane texel (c W + x, y) holds channel c of texel (x, y); filtering by hand from the 2x2 texels
// a gather returns, with lut.glsl's axis clamp (the pair (x0, x0 + 1) kept inside the plane),
// equals Vulkan's LINEAR filter of the table with CLAMP_TO_EDGE.
TEST(LutMapping, PlanesFilterLikeTheTable) {
    LutTable t;
    t.x.size = 7;
    t.y.size = 4;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> value(0.0f, 1.0f);
    t.rgb.resize(7 * 4 * 3);
    for (float& f : t.rgb) f = skin::roundToHalf(value(rng));
    const std::vector<float> planes = t.planes();
    ASSERT_EQ(planes.size(), size_t(3 * 7 * 4));
    auto texel = [&](int column, int y) { return double(planes[size_t(y) * 21 + size_t(column)]); };
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 7; ++x)
            for (int c = 0; c < 3; ++c) EXPECT_EQ(texel(c * 7 + x, y), t.texel(x, y)[c]);
    auto axis = [](double u, double size) {  // preskinLutAxis
        const double x = std::clamp(u * size - 0.5, 0.0, size - 1.0);
        const double x0 = std::max(std::min(std::floor(x), size - 2.0), 0.0);
        return std::pair{int(x0), x - x0};
    };
    std::uniform_real_distribution<double> uv(-0.2, 1.2);
    for (int i = 0; i < 1000; ++i) {
        const double u = uv(rng), v = uv(rng);
        const glm::dvec3 want = referenceBilinear(t, u, v);
        const auto [x0, fx] = axis(u, 7.0);
        const auto [y0, fy] = axis(v, 4.0);
        for (int c = 0; c < 3; ++c) {
            const int column = c * 7 + x0;  // the gather's 2x2 texels: columns x0, x0 + 1 of plane c
            const double near = (1 - fx) * texel(column, y0) + fx * texel(column + 1, y0);
            const double far = (1 - fx) * texel(column, y0 + 1) + fx * texel(column + 1, y0 + 1);
            ASSERT_NEAR((1 - fy) * near + fy * far, want[c], 1e-9) << u << ", " << v;
        }
    }
    EXPECT_THROW(lutPlanes(std::vector<uint16_t>(10), 7, 4), Error);
}

void expectNodesOnTexelCentres(const LutTable& table, const std::function<glm::vec2(double)>& uvOfValue, bool alongX) {
    const LutAxis& axis = alongX ? table.x : table.y;
    for (int i = 0; i < axis.size; ++i) {
        const double value = axis.valueAt(i);
        EXPECT_NEAR(axis.nodeCoordinate(value), i, 1e-9) << table.name << " node " << i;
        if (std::isinf(value)) continue;
        const glm::vec2 uv = uvOfValue(value);
        EXPECT_NEAR(alongX ? uv.x : uv.y, (i + 0.5) / axis.size, 2e-6)
            << table.name << " node " << i << " value " << value;
    }
}

TEST(LutMapping, AxisNodesSitOnTexelCentres) {
    const LutSet& luts = LutSet::loadDefault();
    const gpu::LutMapping m = lutMapping(luts);
    expectNodesOnTexelCentres(
        luts.diffuse(), [&](double v) { return gpu::preskinDiffuseLutUv(m, static_cast<float>(v), 0.0f); }, true);
    expectNodesOnTexelCentres(
        luts.diffuse(), [&](double v) { return gpu::preskinDiffuseLutUv(m, 0.0f, static_cast<float>(v)); }, false);
    expectNodesOnTexelCentres(
        luts.penumbra(), [&](double v) { return gpu::preskinPenumbraLutUv(m, static_cast<float>(v), 0.0f); }, true);
    const double reference = luts.penumbraReferenceWidthMm();
    expectNodesOnTexelCentres(
        luts.penumbra(),
        [&](double v) { return gpu::preskinPenumbraLutUv(m, 0.0f, static_cast<float>(v * reference)); }, false);
    expectNodesOnTexelCentres(
        luts.shTransfer(), [&](double v) { return gpu::preskinShTransferLutUv(m, static_cast<float>(v), 0); }, true);
    for (int band = 0; band < 3; ++band)
        EXPECT_FLOAT_EQ(gpu::preskinShTransferLutUv(m, 0.3f, band).y, (static_cast<float>(band) + 0.5f) / 3.0f);
    expectNodesOnTexelCentres(
        luts.transmittance(), [&](double v) { return gpu::preskinTransmittanceLutUv(m, static_cast<float>(v)); }, true);
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
    EXPECT_EQ(rgba[3], 0x3c00u);  // alpha 1.0
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
}  // namespace preskin::test
