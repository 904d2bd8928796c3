// A sphere under one directional light with the standard material, rendered on the GPU, against
// an independent CPU evaluation of the glTF 2.0 metal-rough BRDF (specification Appendix B) at
// the analytic ray-sphere hit of every pixel centre.
#include "support/GpuTest.h"
#include "support/ImageCompare.h"
#include "support/TestScenes.h"

#include <preskin/Renderer.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace preskin::test {
namespace {

struct BrdfInputs {
    glm::dvec3 baseColor;
    double metallic;
    double roughness;
};

// Reflected radiance for unit vectors N, V, L and irradiance E (normal to the light).
glm::dvec3 referenceBrdf(const BrdfInputs& m, glm::dvec3 N, glm::dvec3 V, glm::dvec3 L, glm::dvec3 E) {
    const double NoL = glm::dot(N, L);
    if (NoL <= 0.0) return glm::dvec3(0.0);
    const double NoV = std::max(glm::dot(N, V), 1e-4);
    const glm::dvec3 H = glm::normalize(L + V);
    const double NoH = std::clamp(glm::dot(N, H), 0.0, 1.0);
    const double VoH = std::clamp(glm::dot(V, H), 0.0, 1.0);
    const double alpha = std::max(m.roughness * m.roughness, 1e-3);
    const double a2 = alpha * alpha;
    const double pi = 3.14159265358979323846;
    const double dDenom = NoH * NoH * (a2 - 1.0) + 1.0;
    const double D = a2 / (pi * dDenom * dDenom);
    const double Vis =
        0.5 / (NoL * std::sqrt(NoV * NoV * (1.0 - a2) + a2) + NoV * std::sqrt(NoL * NoL * (1.0 - a2) + a2));
    const glm::dvec3 F0 = glm::mix(glm::dvec3(0.04), m.baseColor, m.metallic);
    const glm::dvec3 F = F0 + (glm::dvec3(1.0) - F0) * std::pow(1.0 - VoH, 5.0);
    const glm::dvec3 diffuse = (glm::dvec3(1.0) - F) * m.baseColor * (1.0 - m.metallic) / pi;
    return (diffuse + F * D * Vis) * NoL * E;
}

class StandardBrdf : public GpuTest {};

TEST_F(StandardBrdf, SphereMatchesCpuReference) {
    const BrdfInputs inputs{{0.8, 0.45, 0.3}, 0.0, 0.45};
    Material material;
    material.baseColorFactor = glm::vec4(glm::vec3(inputs.baseColor), 1.0f);
    material.metallicFactor = float(inputs.metallic);
    material.roughnessFactor = float(inputs.roughness);
    Scene scene = makeScene({{makeSphere(1.0f, 256, 128), glm::mat4(1.0f)}}, {material});
    scene.meshes[0].primitives[0].material = 0;
    Light light;
    light.type = LightType::Directional;
    light.directionWs = glm::normalize(glm::vec3(-0.45f, -0.5f, -0.74f));
    light.color = glm::vec3(1.0f, 0.95f, 0.9f);
    light.intensity = 2.2f;
    scene.lights = {light};

    RenderSettings settings;
    settings.shadows = false;
    Renderer renderer(context(), scene, Environment::constant(glm::vec3(0.0f)), nullptr, settings);
    const uint32_t size = 160;
    const glm::mat4 worldFromView =
        glm::inverse(glm::lookAt(glm::vec3(0.3f, 0.4f, 3.6f), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f)));
    const View view = perspectiveView(worldFromView, 0.7f, 1.0f, 0.1f, 10.0f);
    const RenderedImage image = renderer.render(view, size, size, OutputEncoding::LinearFloat);
    dumpImage("standard_brdf_sphere", image);

    const glm::dmat4 worldFromClip = glm::inverse(glm::dmat4(view.eye().clipFromWorld()));
    const glm::dvec3 eye(view.eye().positionWs);
    auto hit = [&](double px, double py, glm::dvec3& p) {
        const glm::dvec2 ndc(px / size * 2.0 - 1.0, py / size * 2.0 - 1.0);
        glm::dvec4 farPoint = worldFromClip * glm::dvec4(ndc, 0.5, 1.0);
        const glm::dvec3 dir = glm::normalize(glm::dvec3(farPoint) / farPoint.w - eye);
        const double b = glm::dot(eye, dir);
        const double c = glm::dot(eye, eye) - 1.0;
        const double disc = b * b - c;
        if (disc <= 0.0) return false;
        p = eye + dir * (-b - std::sqrt(disc));
        return true;
    };
    const glm::dvec3 L = -glm::normalize(glm::dvec3(light.directionWs));
    const glm::dvec3 E = glm::dvec3(light.color) * double(light.intensity);
    size_t interior = 0;
    size_t within = 0;
    double worst = 0.0;
    for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 0; x < size; ++x) {
            glm::dvec3 p;
            bool inside = true;
            for (int dy = -1; dy <= 2 && inside; ++dy)  // every corner of the pixel and its neighbours
                for (int dx = -1; dx <= 2 && inside; ++dx) inside = hit(double(x) + dx, double(y) + dy, p);
            if (!inside || !hit(x + 0.5, y + 0.5, p)) continue;
            const glm::dvec3 N = glm::normalize(p);
            const glm::dvec3 V = glm::normalize(eye - p);
            const glm::dvec3 expected = referenceBrdf(inputs, N, V, L, E);
            const float* got = &image.rgba32f[(size_t(y) * size + x) * 4];
            double diff = 0.0;
            for (int c = 0; c < 3; ++c) diff = std::max(diff, std::abs(srgb255(got[c]) - srgb255(expected[c])));
            worst = std::max(worst, diff);
            ++interior;
            if (diff <= 2.0) ++within;
        }
    ASSERT_GT(interior, size_t(size * size / 4)) << "the sphere should cover a good part of the image";
    EXPECT_GE(double(within), 0.999 * double(interior))
        << within << " of " << interior << " interior pixels within 2/255; worst " << worst << "/255";
}

}  // namespace
}  // namespace preskin::test
