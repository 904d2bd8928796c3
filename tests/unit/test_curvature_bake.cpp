// Curvature maps (<preskin/CurvatureBake.h>), against analytic curvature:
//  - a UV sphere of radius r (curvature estimated from its vertex normals, as at load), drawn at
//    twice its size: the map reads 1 / 2r within 2 % away from the UV seam and the poles;
//  - a torus whose tube radius is two thirds of its ring radius: positive on the outside,
//    negative on the inside, each texel within 5 % of the analytic mean curvature
//    (R + 2 r cos v) / (2 r (R + r cos v)) (of the larger magnitude) away from the sign change;
//  - a chart covering part of the texture: the rings around it take its values (dilation), the
//    texels beyond stay empty; the 16-bit encoding decodes back to the curvature.
#include "support/SkinTestSupport.h"
#include "support/TestScenes.h"

#include <preskin/CurvatureBake.h>
#include <preskin/Error.h>
#include <preskin/Scene.h>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <numbers>

namespace preskin::test {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

Scene oneSkinPrimitive(const Primitive& primitive, const glm::mat4& worldFromObject) {
    Primitive p = primitive;
    p.material = 0;
    return makeScene({{p, worldFromObject}}, {skinMaterial(glm::vec3(0.8f))});
}

double texel(const CurvatureMap& map, double u, double v) {
    const auto x = std::min(uint32_t(u * map.width), map.width - 1),
               y = std::min(uint32_t(v * map.height), map.height - 1);
    return double(map.curvaturePerM[size_t(y) * map.width + x]);
}

TEST(CurvatureBake, SphereReadsOneOverRadius) {
    const float radius = 0.02f;
    Primitive sphere = makeSphere(radius, 96, 48);
    recomputeCurvature(sphere);
    const Scene scene = oneSkinPrimitive(sphere, glm::scale(glm::mat4(1.0f), glm::vec3(2.0f)));
    CurvatureBakeSettings settings;
    settings.size = 256;
    const std::vector<CurvatureMap> maps = bakeCurvatureMaps(scene, settings);
    ASSERT_EQ(maps.size(), 1u);
    const CurvatureMap& map = maps[0];
    EXPECT_EQ(map.width, 256u);
    const double expected = 1.0 / (2.0 * double(radius));
    double worst = 0.0;
    for (double v = 0.15; v <= 0.85; v += 0.01)
        for (double u = 0.05; u <= 0.95; u += 0.01)
            worst = std::max(worst, std::abs(texel(map, u, v) / expected - 1.0));
    std::printf("[ curvature] sphere map: worst relative error %.4f away from the seam and poles\n", worst);
    EXPECT_LT(worst, 0.02);
    // The encoding: value = 0.5 + k / scale, 16 bits.
    const std::vector<uint16_t> encoded = map.encoded();
    const size_t i = size_t(128) * map.width + 128;
    const double scale = double(map.scalePerM);
    EXPECT_NEAR((encoded[i] / 65535.0 - double(map.bias)) * scale, double(map.curvaturePerM[i]), scale / 65535.0);
}

Primitive makeTorus(float ringRadius, float tubeRadius, uint32_t segments, uint32_t sides) {
    Primitive p;
    for (uint32_t i = 0; i <= segments; ++i) {
        const float u = 2.0f * kPi * float(i) / float(segments);
        for (uint32_t j = 0; j <= sides; ++j) {
            const float v = 2.0f * kPi * float(j) / float(sides);
            Vertex vertex;
            vertex.normalOs = glm::vec3(std::cos(v) * std::cos(u), std::sin(v), std::cos(v) * std::sin(u));
            vertex.positionOs =
                glm::vec3((ringRadius + tubeRadius * std::cos(v)) * std::cos(u), tubeRadius * std::sin(v),
                          (ringRadius + tubeRadius * std::cos(v)) * std::sin(u));
            vertex.uv0 = glm::vec2(float(i) / float(segments), float(j) / float(sides));
            p.vertices.push_back(vertex);
        }
    }
    for (uint32_t i = 0; i < segments; ++i)
        for (uint32_t j = 0; j < sides; ++j) {
            const uint32_t a = i * (sides + 1) + j, b = a + sides + 1;
            p.indices.insert(p.indices.end(), {a, a + 1, b, a + 1, b + 1, b});
        }
    return p;
}

TEST(CurvatureBake, TorusHasBothSigns) {
    const double R = 0.03, r = 0.02;
    Primitive torus = makeTorus(float(R), float(r), 192, 96);
    recomputeCurvature(torus);
    CurvatureBakeSettings settings;
    settings.size = 256;
    const std::vector<CurvatureMap> maps = bakeCurvatureMaps(oneSkinPrimitive(torus, glm::mat4(1.0f)), settings);
    ASSERT_EQ(maps.size(), 1u);
    size_t positive = 0, negative = 0;
    double worst = 0.0;
    for (double tv = 0.02; tv <= 0.98; tv += 0.01) {
        const double v = 2.0 * std::numbers::pi * tv;
        const double analytic = (R + 2.0 * r * std::cos(v)) / (2.0 * r * (R + r * std::cos(v)));
        if (std::abs(analytic) < 0.2 / r) continue;  // near the sign change
        for (double tu = 0.05; tu <= 0.95; tu += 0.05) {
            const double k = texel(maps[0], tu, tv);
            (analytic > 0.0 ? positive : negative) += (k > 0.0) == (analytic > 0.0);
            worst = std::max(worst, std::abs(k - analytic) / std::abs(analytic));
        }
    }
    std::printf("[ curvature] torus map: %zu convex and %zu concave texels of the right sign, worst error %.4f\n",
                positive, negative, worst);
    EXPECT_GT(positive, 100u);
    EXPECT_GT(negative, 100u);
    EXPECT_LT(worst, 0.05);
}

TEST(CurvatureBake, ChartsAreDilatedAndTheRestStaysEmpty) {
    Primitive quad = makeQuad(0.1f, 4);
    for (Vertex& v : quad.vertices) {
        v.uv0 = glm::vec2(0.25f) + 0.5f * v.uv0;
        v.curvaturePerM = -5.0f;
    }
    CurvatureBakeSettings settings;
    settings.size = 64;
    settings.dilationTexels = 4;
    const std::vector<CurvatureMap> maps = bakeCurvatureMaps(oneSkinPrimitive(quad, glm::mat4(1.0f)), settings);
    ASSERT_EQ(maps.size(), 1u);
    const CurvatureMap& map = maps[0];
    size_t covered = 0, dilated = 0, empty = 0;
    for (uint32_t y = 0; y < 64; ++y)
        for (uint32_t x = 0; x < 64; ++x) {
            const size_t i = size_t(y) * 64 + x;
            // The chart spans texels 16..47; four rings around it are filled.
            const bool inside = x >= 16 && x < 48 && y >= 16 && y < 48;
            const bool ring = !inside && x >= 12 && x < 52 && y >= 12 && y < 52;
            if (inside) {
                covered += map.covered[i] == 1;
                EXPECT_FLOAT_EQ(map.curvaturePerM[i], -5.0f);
            } else if (ring) {
                dilated += map.covered[i] == 2;
                EXPECT_FLOAT_EQ(map.curvaturePerM[i], -5.0f);
            } else {
                empty += map.covered[i] == 0 && std::isnan(map.curvaturePerM[i]);
            }
        }
    EXPECT_EQ(covered, 32u * 32u);
    EXPECT_EQ(dilated, 40u * 40u - 32u * 32u);
    EXPECT_EQ(empty, 64u * 64u - 40u * 40u);
    EXPECT_EQ(map.encoded()[0], uint16_t(32768));  // an empty texel encodes flat skin
    EXPECT_THROW((void)bakeCurvatureMaps(Scene{}, CurvatureBakeSettings{8, 4}), Error);
}

// Hostile UV layouts: a triangle wider than the texture is skipped and counted; triangles that
// cover the map far more often than any layout does stop the bake with an error, not a hang.
TEST(CurvatureBake, HostileUvLayoutsAreBounded) {
    Primitive p;
    for (const glm::vec2 uv : {glm::vec2(0.0f), glm::vec2(1.0f, 0.0f), glm::vec2(0.0f, 1.0f), glm::vec2(3e30f, 0.0f)}) {
        Vertex v;
        v.positionOs = glm::vec3(uv.x > 2.0f ? 2.0f : uv.x, uv.y, 0.0f);
        v.uv0 = uv;
        v.curvaturePerM = 1.0f;
        p.vertices.push_back(v);
    }
    p.indices = {0, 3, 2};  // spans 3e30 textures in u: skipped, and then nothing is covered
    CurvatureBakeSettings settings;
    settings.size = 16;
    try {
        (void)bakeCurvatureMaps(oneSkinPrimitive(p, glm::mat4(1.0f)), settings);
        ADD_FAILURE() << "a bake that covers nothing succeeded";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("cover no texel centre of the 16x16 map (1 wider than the map in UV)"),
                  std::string::npos)
            << e.what();
    }
    // With a triangle that is baked beside it, the broken one is skipped and counted.
    p.indices = {0, 3, 2, 0, 1, 2};
    std::vector<CurvatureMap> maps = bakeCurvatureMaps(oneSkinPrimitive(p, glm::mat4(1.0f)), settings);
    ASSERT_EQ(maps.size(), 1u);
    EXPECT_EQ(maps[0].skippedTriangles, 1);
    // 400,000 triangles each covering the whole 16 x 16 map: 1e8 texel visits.
    p.indices.clear();
    for (int i = 0; i < 400000; ++i) p.indices.insert(p.indices.end(), {0u, 1u, 2u});
    EXPECT_THROW((void)bakeCurvatureMaps(oneSkinPrimitive(p, glm::mat4(1.0f)), settings), Error);
}

}  // namespace
}  // namespace preskin::test
