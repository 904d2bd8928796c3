// Skin SH ambient on a sphere (no lights) against a brute-force CPU integration over the
// environment's texels:
//   E_c(N) = sum over texels of L_c(w) D_c(N . w, curvature) dOmega,
// with D_c the diffuse response on the sphere computed here from the profile's Gaussians (own
// quadrature of the profile over the sphere times the clamped cosine; neither the LUT nor the
// library's integrator). The GPU instead projects the environment onto
// L2 SH and scales the bands by the SH transfer LUT A_l(curvature); the two agree exactly when
// the environment holds nothing above band 2, so the synthetic environment is a positive
// polynomial of degree 2 in the direction (structure in bands 0, 1 and 2, a different one per
// channel). Expected pixel: albedo / pi * E_c(N) * (1 - envBrdf) + envBrdf * E_Lambert(R) / pi,
// the second term being the shader's specular ambient (Karis' analytic environment BRDF,
// F0 = 0 here as specularIntensity = 0, so it is a few thousandths of the total and included
// anyway). Tolerance: 2% per channel on every interior pixel. The test also checks it can tell:
// Lambert's transfer in place of the skin's must miss 2% somewhere.
#include "support/GpuTest.h"
#include "support/ImageCompare.h"
#include "support/SkinTestSupport.h"
#include "support/TestScenes.h"

#include <preskin/LutSet.h>
#include <preskin/Renderer.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

namespace preskin::test {
namespace {

constexpr double kPiD = 3.14159265358979323846;

// D(theta) of one channel on a uniform theta grid (thetaSteps + 1 values over [0, pi]) on a
// sphere of curvature curvaturePerMm: the profile over the sphere times max(n_y . L, 0), by the
// midpoint rule in the angle psi between x and y on a fine uniform grid (the kernel's narrowest
// scale, sigma / r, spans many steps) and the closed-form azimuthal integral of the clamped
// cosine, normalised by the profile's integral over the sphere.
std::vector<double> sphereScatterTable(const DiffusionProfile& profile, int channel, double curvaturePerMm,
                                       int thetaSteps) {
    const double r = 1.0 / curvaturePerMm;
    const int n = 16384;
    const double h = kPiD / n;
    std::vector<double> kernel(n), cosPsi(n), sinPsi(n);
    double total = 0.0;
    for (int j = 0; j < n; ++j) {
        const double psi = h * (j + 0.5);
        const double u = 2.0 * r * std::sin(0.5 * psi);
        double p = 0.0;
        for (const GaussianTerm& t : profile.gaussians())
            p += t.weight[channel] * std::exp(-u * u / (2.0 * t.varianceMm2)) / (2.0 * kPiD * t.varianceMm2);
        cosPsi[size_t(j)] = std::cos(psi);
        sinPsi[size_t(j)] = std::sin(psi);
        kernel[size_t(j)] = p * sinPsi[size_t(j)];
        total += 2.0 * kPiD * kernel[size_t(j)];
    }
    std::vector<double> table(size_t(thetaSteps) + 1);
    for (int k = 0; k <= thetaSteps; ++k) {
        const double theta = kPiD * k / thetaSteps;
        double sum = 0.0;
        for (int j = 0; j < n; ++j) {
            const double A = std::cos(theta) * cosPsi[size_t(j)], B = std::sin(theta) * sinPsi[size_t(j)];
            double azimuthal = 0.0;  // int_0^2pi max(A + B cos(phi), 0) dphi
            if (A >= B)
                azimuthal = 2.0 * kPiD * A;
            else if (A > -B) {
                const double phi0 = std::acos(-A / B);
                azimuthal = 2.0 * (A * phi0 + B * std::sin(phi0));
            }
            sum += kernel[size_t(j)] * azimuthal;
        }
        table[size_t(k)] = sum / total;
    }
    return table;
}

double interpolateTheta(const std::vector<double>& table, double mu) {
    const double t = std::acos(std::clamp(mu, -1.0, 1.0)) / kPiD * double(table.size() - 1);
    const size_t i = std::min(static_cast<size_t>(t), table.size() - 2);
    const double f = t - double(i);
    return table[i] * (1.0 - f) + table[i + 1] * f;
}

// Karis' analytic fit of the split-sum environment BRDF ("Physically Based Shading on Mobile",
// 2014): F0 * A + B.
double environmentBrdf(double F0, double roughness, double NoV) {
    const double c0[4] = {-1.0, -0.0275, -0.572, 0.022};
    const double c1[4] = {1.0, 0.0425, 1.04, -0.04};
    double r[4];
    for (int i = 0; i < 4; ++i) r[i] = roughness * c0[i] + c1[i];
    const double a004 = std::min(r[0] * r[0], std::exp2(-9.28 * NoV)) * r[0] + r[1];
    const double A = -1.04 * a004 + r[2];
    const double B = 1.04 * a004 + r[3];
    return F0 * A + B;
}

class SkinShAmbient : public GpuTest {};

TEST_F(SkinShAmbient, SphereMatchesBruteForceIntegrationWithSkinTransfer) {
    const LutSet& luts = LutSet::loadDefault();
    ASSERT_EQ(luts.profile().kind(), DiffusionProfile::Kind::SumOfGaussians);
    const double radiusM = 1.0;
    // Profile curvature 1/m * 0.001 / 0.002 = 0.5 / mm: a sphere scattering like one of radius 2 mm.
    SkinMaterial skin;
    skin.scatterScale = 0.002f;
    skin.specularIntensity = 0.0f;
    const double curvaturePerMm = 1.0 / radiusM * 0.001 / double(skin.scatterScale);
    const glm::dvec3 albedo(0.8, 0.55, 0.45);
    const double roughness = 1.0;
    Material material;
    material.baseColorFactor = glm::vec4(glm::vec3(albedo), 1.0f);
    material.metallicFactor = 0.0f;
    material.roughnessFactor = float(roughness);
    material.skin = skin;

    // Degree-2 polynomial radiance, positive everywhere (>= 0.2 of its base), different per channel.
    const glm::vec3 base(0.9f, 0.75f, 0.6f);
    const glm::vec3 linear[3] = {{0.2f, 0.35f, -0.15f}, {0.1f, 0.4f, 0.1f}, {-0.2f, 0.3f, 0.2f}};
    const Environment environment = makeEnvironment(64, [&](const glm::vec3& d) {
        glm::vec3 l;
        for (int c = 0; c < 3; ++c)
            l[c] = base[c] * (1.0f + glm::dot(linear[c], d) + 0.3f * d.x * d.z + 0.2f * (d.x * d.x - d.y * d.y));
        return l;
    });

    Primitive sphere = makeSphere(float(radiusM), 192, 96);
    sphere.material = 0;
    Scene scene = makeScene({{sphere, glm::mat4(1.0f)}}, {material});
    RenderSettings settings;
    settings.shadows = false;
    settings.environmentLights = 0;  // the whole environment stays in the SH
    settings.specularIbl = false;    // the specular term modelled here is the SH one
    Renderer renderer(context(), scene, environment, &luts, settings);
    const uint32_t size = 128;
    const glm::mat4 worldFromView =
        glm::inverse(glm::lookAt(glm::vec3(-0.8f, 1.1f, 3.3f), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f)));
    const View view = perspectiveView(worldFromView, 0.75f, 1.0f, 0.1f, 10.0f);
    const RenderedImage image = renderer.render(view, size, size, OutputEncoding::LinearFloat);
    dumpImage("skin_sh_ambient_sphere", image);

    // The environment's texels as the GPU saw them: direction, radiance times solid angle.
    const EquirectImage& env = environment.image();
    ASSERT_GT(env.width, 0u);
    struct Texel {
        glm::dvec3 direction;
        glm::dvec3 weightedRadiance;
    };
    std::vector<Texel> texels;
    for (uint32_t y = 0; y < env.height; ++y) {
        const double solidAngle =
            2.0 * kPiD / env.width * (std::cos(kPiD * y / env.height) - std::cos(kPiD * (y + 1) / env.height));
        for (uint32_t x = 0; x < env.width; ++x) {
            const glm::vec3 d =
                EquirectImage::directionAt((float(x) + 0.5f) / float(env.width), (float(y) + 0.5f) / float(env.height));
            texels.push_back({glm::dvec3(d), glm::dvec3(env.texel(x, y)) * solidAngle});
        }
    }
    std::array<std::vector<double>, 3> D;
    for (int c = 0; c < 3; ++c) D[size_t(c)] = sphereScatterTable(luts.profile(), c, curvaturePerMm, 512);

    const std::vector<SphereHit> hits = traceSphere(view, size, size, glm::dvec3(0.0), radiusM);
    const glm::dvec3 eye(view.eye().positionWs);
    size_t interior = 0;
    size_t within = 0;
    double worst = 0.0;
    double worstLambert = 0.0;
    for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 0; x < size; ++x) {
            const SphereHit& h = hits[size_t(y) * size + x];
            if (!h.interior) continue;
            const glm::dvec3 N = glm::normalize(h.positionWs);
            const glm::dvec3 V = glm::normalize(eye - h.positionWs);
            const glm::dvec3 R = 2.0 * glm::dot(N, V) * N - V;
            glm::dvec3 skinIrradiance(0.0);
            glm::dvec3 lambertIrradiance(0.0);
            glm::dvec3 reflectedIrradiance(0.0);
            for (const Texel& t : texels) {
                const double mu = glm::dot(N, t.direction);
                for (int c = 0; c < 3; ++c)
                    skinIrradiance[c] += t.weightedRadiance[c] * interpolateTheta(D[size_t(c)], mu);
                lambertIrradiance += t.weightedRadiance * std::max(mu, 0.0);
                reflectedIrradiance += t.weightedRadiance * std::max(glm::dot(R, t.direction), 0.0);
            }
            const double envBrdf = environmentBrdf(0.0, roughness, std::max(glm::dot(N, V), 1e-4));
            const glm::dvec3 specular = envBrdf * reflectedIrradiance / kPiD;
            const glm::dvec3 expected = albedo / kPiD * skinIrradiance * (1.0 - envBrdf) + specular;
            const glm::dvec3 lambert = albedo / kPiD * lambertIrradiance * (1.0 - envBrdf) + specular;
            const glm::dvec3 got = pixelLinear(image, x, y);
            double error = 0.0;
            double lambertError = 0.0;
            for (int c = 0; c < 3; ++c) {
                error = std::max(error, std::abs(got[c] - expected[c]) / expected[c]);
                lambertError = std::max(lambertError, std::abs(lambert[c] - expected[c]) / expected[c]);
            }
            worst = std::max(worst, error);
            worstLambert = std::max(worstLambert, lambertError);
            ++interior;
            if (error <= 0.02) ++within;
        }
    std::printf(
        "[ skin     ] SH ambient: %zu of %zu interior pixels within 2%% (worst %.3f%%); Lambert transfer "
        "would be off by up to %.2f%%\n",
        within, interior, 100.0 * worst, 100.0 * worstLambert);
    ASSERT_GT(interior, size_t(size * size / 4)) << "the sphere should cover a good part of the image";
    EXPECT_EQ(within, interior) << "worst relative error " << worst;
    EXPECT_GT(worstLambert, 0.04) << "Lambert's transfer should miss the 2% bound, or the test cannot tell them apart";
}

}  // namespace
}  // namespace preskin::test
