// L2 SH projection of analytic environments against closed-form coefficients.
#include <preskin/Environment.h>

#include <gtest/gtest.h>

#include <cmath>

namespace preskin::test {
namespace {

EquirectImage filled(uint32_t w, uint32_t h, glm::vec3 value) {
    EquirectImage img;
    img.width = w;
    img.height = h;
    img.rgb.resize(size_t(w) * h * 3);
    for (size_t i = 0; i < size_t(w) * h; ++i) {
        img.rgb[i * 3] = value.r;
        img.rgb[i * 3 + 1] = value.g;
        img.rgb[i * 3 + 2] = value.b;
    }
    return img;
}

TEST(ShProjection, ConstantEnvironmentHasOnlyTheDcTerm) {
    const glm::vec3 c(0.7f, 1.3f, 2.0f);
    const ShRgb sh = projectEquirect(filled(256, 128, c));
    // integral of c * Y00 over the sphere = c * 0.282095 * 4 pi = c * 2 sqrt(pi)
    const glm::vec3 expected = c * 2.0f * std::sqrt(kPi);
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(sh.c[0][ch], expected[ch], 1e-4f * expected[ch]);
    for (int i = 1; i < 9; ++i)
        for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(sh.c[size_t(i)][ch], 0.0f, 2e-3f) << "coefficient " << i;
    // Lambert-convolved: irradiance pi * c everywhere.
    for (glm::vec3 n : {glm::vec3(0, 1, 0), glm::vec3(1, 0, 0), glm::normalize(glm::vec3(-1, -2, 3))}) {
        const glm::vec3 e = evaluateSh(sh, n, kLambertBands);
        for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(e[ch], kPi * c[ch], 2e-3f * kPi * c[ch]);
    }
    const Environment env = Environment::constant(c);
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(env.radianceSh().c[0][ch], expected[ch], 1e-5f * expected[ch]);
}

TEST(ShProjection, SingleBrightDirectionGivesItsBasisValues) {
    // One lit texel of radiance L0: a near-delta of power Phi = L0 * solid angle; c_lm = Phi Y_lm(d).
    const uint32_t w = 512, h = 256;
    const uint32_t x0 = 371, y0 = 77;
    EquirectImage img = filled(w, h, glm::vec3(0.0f));
    const float L0 = 1000.0f;
    img.rgb[(size_t(y0) * w + x0) * 3 + 0] = L0;
    img.rgb[(size_t(y0) * w + x0) * 3 + 1] = 0.5f * L0;
    const ShRgb sh = projectEquirect(img);
    const double theta0 = M_PI * y0 / h, theta1 = M_PI * (y0 + 1) / h;
    const double solidAngle = 2.0 * M_PI / w * (std::cos(theta0) - std::cos(theta1));
    const glm::vec3 d = EquirectImage::directionAt((x0 + 0.5f) / float(w), (y0 + 0.5f) / float(h));
    // Independent basis: Ramamoorthi & Hanrahan 2001, eq. 3 constants written out here.
    const double x = double(d.x), y = double(d.y), z = double(d.z);
    const double basis[9] = {0.282095,
                             0.488603 * y,
                             0.488603 * z,
                             0.488603 * x,
                             1.092548 * x * y,
                             1.092548 * y * z,
                             0.315392 * (3 * z * z - 1),
                             1.092548 * x * z,
                             0.546274 * (x * x - y * y)};
    for (int i = 0; i < 9; ++i) {
        const double expected = double(L0) * solidAngle * basis[i];
        EXPECT_NEAR(double(sh.c[size_t(i)].r), expected, 5e-3 * double(L0) * solidAngle) << "coefficient " << i;
        EXPECT_NEAR(double(sh.c[size_t(i)].g), 0.5 * expected, 5e-3 * double(L0) * solidAngle) << "coefficient " << i;
        EXPECT_NEAR(double(sh.c[size_t(i)].b), 0.0, 1e-9) << "coefficient " << i;
    }
}

TEST(ShProjection, EquirectDirectionConvention) {
    // u = 0.5 looks along +X, v = 0 is +Y (up), u = 0.75 is +Z.
    const glm::vec3 a = EquirectImage::directionAt(0.5f, 0.5f);
    EXPECT_NEAR(a.x, 1.0f, 1e-6f);
    const glm::vec3 b = EquirectImage::directionAt(0.3f, 0.0f);
    EXPECT_NEAR(b.y, 1.0f, 1e-6f);
    const glm::vec3 c = EquirectImage::directionAt(0.75f, 0.5f);
    EXPECT_NEAR(c.z, 1.0f, 1e-6f);
}

}  // namespace
}  // namespace preskin::test

namespace preskin {
namespace {

TEST(ShProjection, RotationTurnsTheLightAboutY) {
    // A lit texel at +X turned by +90 degrees must light from -Z (right-handed about +Y).
    const uint32_t w = 256, h = 128;
    EquirectImage img;
    img.width = w;
    img.height = h;
    img.rgb.assign(size_t(w) * h * 3, 0.0f);
    const uint32_t x0 = w / 2, y0 = h / 2;  // u = 0.5 (+X) on the horizon
    for (int c = 0; c < 3; ++c) img.rgb[(size_t(y0) * w + x0) * 3 + size_t(c)] = 100.0f;
    const ShRgb turned = projectEquirect(img, 0.5f * kPi);
    const glm::vec3 d = rotateY(EquirectImage::directionAt((x0 + 0.5f) / float(w), (y0 + 0.5f) / float(h)), 0.5f * kPi);
    EXPECT_NEAR(d.z, -1.0f, 1e-3f);
    // The irradiance is largest facing the turned direction and zero facing away.
    const float towards = evaluateSh(turned, glm::vec3(0, 0, -1), kLambertBands).r;
    const float away = evaluateSh(turned, glm::vec3(0, 0, 1), kLambertBands).r;
    const float side = evaluateSh(turned, glm::vec3(1, 0, 0), kLambertBands).r;
    EXPECT_GT(towards, 5.0f * std::abs(away));
    EXPECT_GT(towards, side);
}

}  // namespace
}  // namespace preskin
