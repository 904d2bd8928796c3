// Skin direct lighting on a sphere of known radius under one directional light, with per-vertex
// curvature recomputed from the mesh (computeVertexCurvature): every interior pixel against a CPU
// evaluation at the analytic hit point of
//   (1 - F) * albedo / pi * D(NoL, curvature) * E  +  dual-lobe GGX specular * NoL * E,
// D from LutSet::lookupDiffuse at the analytic curvature 1/r converted to profile units
// (1/m * 0.001 / scatterScale), F Schlick's with F0 = 0.028, and the specular written here from
// the GGX / height-correlated Smith / Schlick formulas. No shadows, no environment, no normal map.
// The test also checks that it can tell: Lambert in place of D must miss the 2/255 bound on many
// pixels.
#include "support/GpuTest.h"
#include "support/ImageCompare.h"
#include "support/SkinTestSupport.h"
#include "support/TestScenes.h"

#include <preskin/LutSet.h>
#include <preskin/Renderer.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace preskin::test {
namespace {

constexpr double kPiD = 3.14159265358979323846;

glm::dvec3 schlick(double F0, double VoH) {
    return glm::dvec3(F0 + (1.0 - F0) * std::pow(1.0 - std::clamp(VoH, 0.0, 1.0), 5.0));
}

// GGX D * height-correlated Smith V * Schlick F for perceptual roughness r.
glm::dvec3 ggxLobe(double F0, double r, double NoL, double NoV, double NoH, double VoH) {
    const double alpha = std::max(r * r, 1e-3);
    const double a2 = alpha * alpha;
    const double denom = NoH * NoH * (a2 - 1.0) + 1.0;
    const double D = a2 / (kPiD * denom * denom);
    const double Vis = 0.5 / (NoL * std::sqrt(NoV * NoV * (1.0 - a2) + a2) + NoV * std::sqrt(NoL * NoL * (1.0 - a2) + a2));
    return D * Vis * schlick(F0, VoH);
}

class SkinDiffuse : public GpuTest {};

TEST_F(SkinDiffuse, SphereWithVertexCurvatureMatchesLutAtAnalyticCurvature) {
    const LutSet& luts = LutSet::loadDefault();
    const double radiusM = 1.0;
    // A 1 m sphere scattering like a 5 mm one: profile curvature 1/m * 0.001 / 0.005 = 0.2 / mm.
    SkinMaterial skin;
    skin.scatterScale = 0.005f;
    const double curvaturePerMm = 1.0 / radiusM * 0.001 / double(skin.scatterScale);
    const glm::dvec3 albedo(0.76, 0.52, 0.42);
    const double roughness = 0.5;
    Material material;
    material.baseColorFactor = glm::vec4(glm::vec3(albedo), 1.0f);
    material.metallicFactor = 0.0f;
    material.roughnessFactor = float(roughness);
    material.skin = skin;

    Primitive sphere = makeSphere(float(radiusM), 256, 128);
    recomputeCurvature(sphere);
    float minCurvature = 1e30f;
    float maxCurvature = 0.0f;
    for (const Vertex& v : sphere.vertices) {
        minCurvature = std::min(minCurvature, v.curvaturePerM);
        maxCurvature = std::max(maxCurvature, v.curvaturePerM);
    }
    sphere.material = 0;
    Scene scene = makeScene({{sphere, glm::mat4(1.0f)}}, {material});
    Light light;
    light.type = LightType::Directional;
    light.directionWs = glm::normalize(glm::vec3(-0.8f, -0.35f, 0.3f));  // the terminator crosses the view
    light.color = glm::vec3(1.0f, 0.96f, 0.92f);
    light.intensity = 3.0f;
    scene.lights = {light};

    RenderSettings settings;
    settings.shadows = false;
    Renderer renderer(context(), scene, Environment::constant(glm::vec3(0.0f)), &luts, settings);
    const uint32_t size = 160;
    const glm::mat4 worldFromView = glm::inverse(glm::lookAt(glm::vec3(0.3f, 0.4f, 3.6f), glm::vec3(0.0f),
                                                             glm::vec3(0.0f, 1.0f, 0.0f)));
    const View view = perspectiveView(worldFromView, 0.7f, 1.0f, 0.1f, 10.0f);
    const RenderedImage image = renderer.render(view, size, size, OutputEncoding::LinearFloat);
    dumpImage("skin_diffuse_sphere", image);

    const std::vector<SphereHit> hits = traceSphere(view, size, size, glm::dvec3(0.0), radiusM);
    const glm::dvec3 L = -glm::normalize(glm::dvec3(light.directionWs));
    const glm::dvec3 E = glm::dvec3(light.color) * double(light.intensity);
    const glm::dvec3 eye(view.eye().positionWs);
    const double F0 = 0.028 * double(skin.specularIntensity);
    size_t interior = 0;
    size_t within = 0;
    size_t lambertWithin = 0;
    double worst = 0.0;
    for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 0; x < size; ++x) {
            const SphereHit& h = hits[size_t(y) * size + x];
            if (!h.interior) continue;
            const glm::dvec3 N = glm::normalize(h.positionWs);
            const glm::dvec3 V = glm::normalize(eye - h.positionWs);
            const glm::dvec3 H = glm::normalize(L + V);
            const double NoL = glm::dot(N, L);
            const double VoH = glm::dot(V, H);
            const glm::dvec3 D = glm::dvec3(luts.lookupDiffuse(float(NoL), float(curvaturePerMm)));
            const glm::dvec3 diffuseScale = (glm::dvec3(1.0) - schlick(F0, VoH)) * albedo / kPiD * E;
            glm::dvec3 specular(0.0);
            if (NoL > 0.0) {
                const double NoV = std::max(glm::dot(N, V), 1e-4);
                const double NoH = std::clamp(glm::dot(N, H), 0.0, 1.0);
                const glm::dvec3 lobe0 = ggxLobe(F0, std::clamp(roughness * double(skin.lobeRoughness0), 0.03, 1.0), NoL, NoV, NoH, VoH);
                const glm::dvec3 lobe1 = ggxLobe(F0, std::clamp(roughness * double(skin.lobeRoughness1), 0.03, 1.0), NoL, NoV, NoH, VoH);
                specular = glm::mix(lobe0, lobe1, double(skin.lobeMix)) * NoL * E;
            }
            const glm::dvec3 expected = diffuseScale * D + specular;
            const glm::dvec3 lambert = diffuseScale * std::clamp(NoL, 0.0, 1.0) + specular;
            const glm::dvec3 got = pixelLinear(image, x, y);
            const double diff = srgbDifference(got, expected);
            worst = std::max(worst, diff);
            ++interior;
            if (diff <= 2.0) ++within;
            if (srgbDifference(got, lambert) <= 2.0) ++lambertWithin;
        }
    std::printf("[ skin     ] sphere diffuse: %zu of %zu interior pixels within 2/255 (worst %.2f/255); "
                "Lambert reference: %zu within; vertex curvature %.4f..%.4f 1/m (analytic %.4f)\n",
                within, interior, worst, lambertWithin, double(minCurvature), double(maxCurvature), 1.0 / radiusM);
    ASSERT_GT(interior, size_t(size * size / 4)) << "the sphere should cover a good part of the image";
    EXPECT_GE(double(within), 0.999 * double(interior))
        << within << " of " << interior << " interior pixels within 2/255; worst " << worst << "/255";
    EXPECT_LT(double(lambertWithin), 0.9 * double(interior))
        << "Lambert in place of the LUT should miss the bound on many pixels, or the test cannot tell them apart";
}

}  // namespace
}  // namespace preskin::test
