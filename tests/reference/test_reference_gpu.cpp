// The diffusion reference against the renderer where both must agree: a flat textured skin
// plane lit by a shadowed directional light, a point light and uniform ambient, rendered on the
// GPU with the Lambert path (skin techniques off, specular off) and by the reference for the
// same view. On a plane the profile integrates to one and the irradiance varies slowly, so the
// reference is Lambert: any difference is a convention the two disagree on (pixel centres and
// rays, V axis of textures, sRGB decoding, light falloff, SH ambient, exposure). Without the
// texture (base colour factor only) they agree within 1e-3.
#include "support/GpuTest.h"
#include "support/ImageCompare.h"
#include "support/TestScenes.h"

#include <preskin/DiffusionReference.h>
#include <preskin/LutSet.h>
#include <preskin/Renderer.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdio>

namespace preskin::test {
namespace {

class ReferenceGpu : public GpuTest {
protected:
    // Largest relative difference per pixel and channel between the Lambert render and the
    // reference of the plane, with or without the base colour texture.
    double planeDifference(bool textured);
};

double ReferenceGpu::planeDifference(bool textured) {
    // A smooth colour ramp (texels change little, so GPU and CPU filtering agree), not symmetric
    // in v, so a flipped V axis shows.
    Image ramp;
    ramp.name = "ramp";
    ramp.width = 32;
    ramp.height = 32;
    for (uint32_t y = 0; y < ramp.height; ++y)
        for (uint32_t x = 0; x < ramp.width; ++x)
            for (uint8_t v : {uint8_t(90 + 4 * x), uint8_t(60 + 5 * y), uint8_t(140), uint8_t(255)})
                ramp.rgba8.push_back(v);
    Material material;
    material.baseColorFactor = glm::vec4(1.0f);
    material.metallicFactor = 0.0f;
    if (textured)
        material.baseColor.image = 0;
    else
        material.baseColorFactor = glm::vec4(0.55f, 0.35f, 0.3f, 1.0f);
    material.skin = SkinMaterial{};
    Primitive plane = makeQuad(0.3f, 4);
    plane.material = 0;
    Scene scene = makeScene({{plane, glm::mat4(1.0f)}}, {material});
    scene.images.push_back(ramp);
    Light key;
    key.type = LightType::Directional;
    key.directionWs = glm::normalize(glm::vec3(0.3f, -0.4f, -0.87f));
    key.intensity = 2.0f;
    key.castsShadow = true;
    Light point;
    point.type = LightType::Point;
    point.positionWs = glm::vec3(-0.05f, 0.04f, 0.25f);
    point.intensity = 0.08f;
    point.color = glm::vec3(1.0f, 0.8f, 0.6f);
    scene.lights = {key, point};
    const Environment environment = Environment::constant(glm::vec3(0.2f, 0.22f, 0.25f));

    const uint32_t size = 24;
    const View view = perspectiveView(
        glm::inverse(glm::lookAt(glm::vec3(0.01f, -0.02f, 0.3f), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f))), 0.7f,
        1.0f, 0.05f, 2.0f);
    RenderSettings settings;
    settings.skin = SkinFeatures::none();
    settings.specular = false;
    settings.exposure = 1.3f;
    const LutSet& luts = LutSet::loadDefault();
    Renderer renderer(context(), scene, environment, &luts, settings);
    const RenderedImage lambert = renderer.render(view, size, size, OutputEncoding::LinearFloat);
    const DiffusionReference reference(scene, scene.lights, environment.radianceSh(), luts.profile());
    const ReferenceImage ref = reference.render(view.eye(), size, size, settings.exposure);

    double worst = 0.0;
    size_t compared = 0;
    for (size_t i = 0; i < size_t(size) * size; ++i) {
        EXPECT_EQ(ref.rgba32f[4 * i + 3], 1.0f) << "the plane fills the view";
        for (size_t c = 0; c < 3; ++c) {
            const double r = ref.rgba32f[4 * i + c], g = lambert.rgba32f[4 * i + c];
            worst = std::max(worst, std::abs(g - r) / r);
        }
        ++compared;
    }
    std::printf("[ reference] flat plane%s: largest relative difference to the Lambert render %.2e over %zu pixels\n",
                textured ? " (textured)" : "", worst, compared);
    return worst;
}

TEST_F(ReferenceGpu, FlatPlaneMatchesLambertRender) {
    EXPECT_LT(planeDifference(false), 1e-3);
    // Lavapipe decodes sRGB texels with an approximation (0.7 % high at code 70, 0.2 % at 140,
    // measured); the reference decodes exactly. A flipped V axis or a wrong light term would be
    // off by far more.
    EXPECT_LT(planeDifference(true), 1e-2);
}

}  // namespace
}  // namespace preskin::test
