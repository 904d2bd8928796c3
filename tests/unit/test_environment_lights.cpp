// The environment's dominant lights (median cut) against the environment they come from: a
// synthetic sky with one small bright disc, integrated texel by texel here.
#include <preskin/Environment.h>
#include <preskin/Error.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace preskin::test {
namespace {

constexpr double kDiscRadius = 1.0 * M_PI / 180.0;  // twice the sun's
const glm::vec3 kDiscRadiance = glm::vec3(1.0f, 0.9f, 0.75f) * 3000.0f;

glm::vec3 skyRadiance(const glm::vec3& d) {
    // Brighter towards the zenith: smooth, as a clear sky is away from its sun, and linear in the
    // direction so that L2 SH hold its irradiance exactly (what is left to test is the light).
    return glm::vec3(0.4f, 0.6f, 1.0f) * (0.7f + 0.5f * d.y);
}

// Direction through the point (x + fx, y + fy) of the image, in texels.
glm::vec3 texelDirection(const EquirectImage& image, uint32_t x, uint32_t y, float fx = 0.5f, float fy = 0.5f) {
    return EquirectImage::directionAt((float(x) + fx) / float(image.width), (float(y) + fy) / float(image.height));
}

// 1024 x 512 sky with the disc of angular radius discRadius around `discDir` (image space), the disc's coverage of each texel
// from 4 x 4 samples.
EquirectImage discSky(const glm::vec3& discDir, double discRadius = kDiscRadius) {
    EquirectImage image;
    image.width = 1024;
    image.height = 512;
    image.rgb.resize(size_t(image.width) * image.height * 3);
    const float cosRadius = float(std::cos(discRadius));
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x) {
            const glm::vec3 center = texelDirection(image, x, y);
            float coverage = 0.0f;
            if (double(glm::dot(center, discDir)) > std::cos(discRadius + 0.02))
                for (int sy = 0; sy < 4; ++sy)
                    for (int sx = 0; sx < 4; ++sx) {
                        const glm::vec3 d =
                            texelDirection(image, x, y, (float(sx) + 0.5f) / 4.0f, (float(sy) + 0.5f) / 4.0f);
                        coverage += glm::dot(d, discDir) >= cosRadius ? 1.0f / 16.0f : 0.0f;
                    }
            const glm::vec3 l = skyRadiance(center) + coverage * kDiscRadiance;
            for (int c = 0; c < 3; ++c) image.rgb[(size_t(y) * image.width + x) * 3 + size_t(c)] = l[c];
        }
    return image;
}

// Irradiance on a surface facing n, summed texel by texel over the image turned by rotationY.
glm::dvec3 trueIrradiance(const EquirectImage& image, float rotationY, const glm::vec3& n) {
    glm::dvec3 sum(0.0);
    for (uint32_t y = 0; y < image.height; ++y) {
        const double omega =
            2.0 * M_PI / image.width * (std::cos(M_PI * y / image.height) - std::cos(M_PI * (y + 1) / image.height));
        for (uint32_t x = 0; x < image.width; ++x) {
            const glm::vec3 d = rotateY(texelDirection(image, x, y), rotationY);
            const double c = double(glm::dot(d, n));
            if (c > 0.0) sum += glm::dvec3(image.texel(x, y)) * (c * omega);
        }
    }
    return sum;
}

TEST(EnvironmentLights, MedianCutFindsASmallBrightDiscWithItsEnergy) {
    const float theta = 0.9f, phi = 0.6f;  // polar angle from +Y, longitude from +X towards +Z
    const glm::vec3 discDir(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
    const float rotationY = 0.7f;
    const EquirectImage image = discSky(discDir);
    const Environment env = Environment::fromImage(image, rotationY);
    const EnvironmentLights found = extractEnvironmentLights(env, 1);
    ASSERT_EQ(found.lights.size(), 1u);
    const EnvironmentLight& light = found.lights[0];
    const glm::vec3 expectedTowards = rotateY(discDir, rotationY);
    const double errorDeg =
        std::acos(std::clamp(double(glm::dot(-light.directionWs, expectedTowards)), -1.0, 1.0)) * 180.0 / M_PI;
    EXPECT_LT(errorDeg, 2.0);
    const double discOmega = 2.0 * M_PI * (1.0 - std::cos(kDiscRadius));
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(double(light.irradiance[c]), double(kDiscRadiance[c]) * discOmega,
                    0.02 * double(kDiscRadiance[c]) * discOmega)
            << "channel " << c;
    EXPECT_LT(light.solidAngleSr, 2.0 * discOmega);

    // The light plus the residual SH give the environment's irradiance in 64 directions.
    for (int i = 0; i < 64; ++i) {
        const float z = 1.0f - (2.0f * float(i) + 1.0f) / 64.0f;  // Fibonacci sphere
        const float r = std::sqrt(1.0f - z * z);
        const float a = float(i) * 2.39996323f;
        const glm::vec3 n(r * std::cos(a), z, r * std::sin(a));
        const glm::dvec3 truth = trueIrradiance(image, rotationY, n);
        const glm::vec3 approx = light.irradiance * std::max(glm::dot(n, -light.directionWs), 0.0f) +
            evaluateSh(found.residualSh, n, kLambertBands);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(approx[c], truth[c], 0.02 * truth[c]) << "direction " << i << " channel " << c;
    }
}

TEST(EnvironmentLights, AngularRadiusIsTheDiscs) {
    // The disc's own radius from its texels' spread (EnvironmentLight::angularRadius), at the
    // sun's twice and at 4 degrees, off the equator where texels are not square.
    const glm::vec3 discDir = glm::normalize(glm::vec3(0.4f, 0.7f, -0.5f));
    for (const double radius : {kDiscRadius, 4.0 * M_PI / 180.0}) {
        const EnvironmentLights found =
            extractEnvironmentLights(Environment::fromImage(discSky(discDir, radius), 0.3f), 1);
        ASSERT_EQ(found.lights.size(), 1u);
        EXPECT_NEAR(double(found.lights[0].angularRadius), radius, 0.08 * radius)
            << "disc of " << radius * 180.0 / M_PI << " degrees";
    }
}

TEST(EnvironmentLights, SmoothOrConstantEnvironmentsHoldNone) {
    EquirectImage image;
    image.width = 256;
    image.height = 128;
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x) {
            const glm::vec3 l = skyRadiance(texelDirection(image, x, y));
            image.rgb.insert(image.rgb.end(), {l.r, l.g, l.b});
        }
    const Environment sky = Environment::fromImage(image);
    const EnvironmentLights none = extractEnvironmentLights(sky, 4);
    EXPECT_TRUE(none.lights.empty());
    for (size_t c = 0; c < 9; ++c) EXPECT_EQ(none.residualSh.c[c], sky.radianceSh().c[c]);
    EXPECT_TRUE(extractEnvironmentLights(Environment::constant(glm::vec3(1.0f)), 4).lights.empty());
    EXPECT_THROW(extractEnvironmentLights(sky, kMaxEnvironmentLights + 1), Error);
}

TEST(EnvironmentLights, SeveralDiscsComeOutStrongestFirst) {
    EquirectImage image = discSky(glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f)));
    // A second, dimmer disc: a quarter of the first's radiance on the other side.
    const EquirectImage second = discSky(glm::normalize(glm::vec3(-1.0f, 0.5f, -1.0f)));
    for (size_t i = 0; i < image.rgb.size(); ++i) image.rgb[i] += 0.25f * second.rgb[i];
    const EnvironmentLights found = extractEnvironmentLights(Environment::fromImage(image), 3);
    ASSERT_GE(found.lights.size(), 2u);
    EXPECT_GT(glm::dot(-found.lights[0].directionWs, glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f))), 0.999f);
    EXPECT_GT(glm::dot(-found.lights[1].directionWs, glm::normalize(glm::vec3(-1.0f, 0.5f, -1.0f))), 0.999f);
    EXPECT_NEAR(found.lights[1].irradiance.r / found.lights[0].irradiance.r, 0.25f, 0.01f);
}

TEST(EnvironmentLights, DownsampledKeepsTheSphereAndTheRadiance) {
    // A 1000 x 500 image (not a power of two) of the disc sky: at most 256 wide is 250 x 125,
    // each texel the mean of the 4 x 4 it covers; the SH stays the original's.
    EquirectImage image = discSky(glm::normalize(glm::vec3(0.3f, 0.8f, -0.5f)));
    EquirectImage odd;
    odd.width = 1000;
    odd.height = 500;
    for (uint32_t y = 0; y < odd.height; ++y)
        for (uint32_t x = 0; x < odd.width; ++x) {
            const glm::vec3 l = image.texel(x, y);
            odd.rgb.insert(odd.rgb.end(), {l.r, l.g, l.b});
        }
    const Environment env = Environment::fromImage(odd, 0.4f);
    const Environment small = env.downsampled(256);
    ASSERT_EQ(small.image().width, 250u);
    ASSERT_EQ(small.image().height, 125u);
    EXPECT_EQ(small.rotationY(), env.rotationY());
    for (size_t c = 0; c < 9; ++c) EXPECT_EQ(small.radianceSh().c[c], env.radianceSh().c[c]);
    for (uint32_t y : {0u, 37u, 124u})
        for (uint32_t x : {0u, 101u, 249u}) {
            glm::dvec3 mean(0.0);
            for (uint32_t sy = 0; sy < 4; ++sy)
                for (uint32_t sx = 0; sx < 4; ++sx) mean += glm::dvec3(odd.texel(4 * x + sx, 4 * y + sy)) / 16.0;
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(double(small.image().texel(x, y)[c]), mean[c], 1e-5 * (1.0 + mean[c]));
        }
    EXPECT_EQ(env.downsampled(4096).image().width, 1000u);  // narrower already: unchanged
}

TEST(EnvironmentLights, FromImageRefusesWhatLoadRefuses) {
    const auto image = [](uint32_t w, uint32_t h, float value) {
        EquirectImage e;
        e.width = w;
        e.height = h;
        e.rgb.assign(size_t(w) * h * 3, value);
        return e;
    };
    EXPECT_THROW(Environment::fromImage(image(0, 0, 1.0f)), Error);
    EXPECT_THROW(Environment::fromImage(image(6, 2, 1.0f)), Error);         // not 2:1
    EXPECT_THROW(Environment::fromImage(image(16384, 8192, 0.0f)), Error);  // beyond 8192 x 4096
    EXPECT_THROW(Environment::fromImage(image(8, 4, std::nanf(""))), Error);
    EXPECT_THROW(Environment::fromImage(image(8, 4, -1.0f)), Error);
    EXPECT_THROW(Environment::fromImage(image(8, 4, 1.0f), std::numeric_limits<float>::infinity()), Error);
    EquirectImage short_ = image(8, 4, 1.0f);
    short_.rgb.pop_back();
    EXPECT_THROW(Environment::fromImage(short_), Error);
    EXPECT_NO_THROW(Environment::fromImage(image(8, 4, 1.0f), 0.5f));
}

}  // namespace
}  // namespace preskin::test
