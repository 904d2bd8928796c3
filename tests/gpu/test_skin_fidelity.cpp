// The skin render against the diffusion reference (DiffusionReference) where the pre-integrated
// model must hold, on a skin sphere of 10 mm diameter under one shadowed directional light,
// specular off, no ambient:
//  - the unlit side: past the terminator the skin render must carry at least 90 % of the
//    reference's red light (the shadow map must not remove the light the diffuse LUT puts there);
//  - transmission must add no more than 0.5 % where the skin faces the light (the diffuse LUT
//    already holds that light), and through a 3 mm slab lit from behind it must give what the
//    reference gives (the profile's plane integral at the slab's depth).
// Pixels are the sphere's interior pixels (analytic ray-sphere hits); the reference is traced
// through the same pixel centres.
#include "support/GpuTest.h"
#include "support/ImageCompare.h"
#include "support/SkinTestSupport.h"
#include "support/TestScenes.h"

#include <preskin/DiffusionReference.h>
#include <preskin/LutSet.h>
#include <preskin/Renderer.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdio>

namespace preskin::test {
namespace {

class SkinFidelity : public GpuTest {
protected:
    void SetUp() override {
        GpuTest::SetUp();
        Primitive sphere = makeSphere(float(kRadiusM), 64, 32);
        recomputeCurvature(sphere);
        sphere.material = 0;
        Material material;
        material.baseColorFactor = glm::vec4(0.8f, 0.6f, 0.5f, 1.0f);
        material.metallicFactor = 0.0f;
        material.skin = SkinMaterial{};
        scene_ = makeScene({{sphere, glm::mat4(1.0f)}}, {material});
        Light light;
        light.type = LightType::Directional;
        light.directionWs = glm::normalize(glm::vec3(0.8f, -0.35f, -0.5f));
        light.intensity = 3.0f;
        light.castsShadow = true;
        scene_.lights = {light};
        L_ = -glm::dvec3(light.directionWs);
        view_ = orbitView(scene_.worldBounds(), 0.0f, 8.0f, 0.0f, 1.0f);
    }

    RenderedImage render(bool transmission) {
        RenderSettings settings;
        settings.specular = false;
        settings.skin.transmission = transmission;
        Renderer renderer(context(), scene_, Environment::constant(glm::vec3(0.0f)), &LutSet::loadDefault(), settings);
        return renderer.render(view_, kSize, kSize, OutputEncoding::LinearFloat);
    }

    // The ray through pixel (x, y)'s centre, as the rasterizer samples it.
    void pixelRay(uint32_t x, uint32_t y, glm::dvec3& origin, glm::dvec3& direction) const {
        const glm::dmat4 worldFromClip = glm::inverse(glm::dmat4(view_.clipFromWorld()));
        const glm::dvec2 ndc((x + 0.5) / kSize * 2.0 - 1.0, (y + 0.5) / kSize * 2.0 - 1.0);
        const glm::dvec4 a = worldFromClip * glm::dvec4(ndc, 1.0, 1.0);
        const glm::dvec4 b = worldFromClip * glm::dvec4(ndc, 0.5, 1.0);
        origin = glm::dvec3(a) / a.w;
        direction = glm::normalize(glm::dvec3(b) / b.w - origin);
    }

    static constexpr double kRadiusM = 0.005;
    static constexpr uint32_t kSize = 64;
    Scene scene_;
    glm::dvec3 L_{0.0};
    View view_;
};

TEST_F(SkinFidelity, UnlitSideCarriesNinetyPercentOfTheReferenceRed) {
    const RenderedImage skin = render(true);
    const DiffusionReference reference(scene_, scene_.lights, ShRgb{}, LutSet::loadDefault().profile());
    const auto hits = traceSphere(view_, kSize, kSize, glm::dvec3(0.0), kRadiusM);
    double skinRed = 0.0, referenceRed = 0.0;
    int pixels = 0;
    for (uint32_t y = 0; y < kSize; y += 2)
        for (uint32_t x = 0; x < kSize; x += 2) {
            const SphereHit& h = hits[size_t(y) * kSize + x];
            if (!h.interior) continue;
            const double NoL = glm::dot(glm::normalize(h.positionWs), L_);
            if (NoL >= -0.02 || NoL < -0.6) continue;  // the unlit side where light still arrives
            glm::dvec3 origin, direction;
            pixelRay(x, y, origin, direction);
            const auto sample = reference.trace(origin, direction);
            ASSERT_TRUE(sample.has_value());
            skinRed += pixelLinear(skin, x, y).r;
            referenceRed += sample->radiance.r;
            ++pixels;
        }
    const double ratio = skinRed / referenceRed;
    std::printf("[ fidelity ] 10 mm sphere, unlit side (%d pixels): skin red / reference red = %.3f\n", pixels, ratio);
    ASSERT_GT(pixels, 30);
    EXPECT_GE(ratio, 0.9);
    EXPECT_LE(ratio, 1.25) << "and not far brighter either";
}

TEST_F(SkinFidelity, TransmissionAddsAtMostHalfAPercentWhereTheSkinFacesTheLight) {
    const RenderedImage with = render(true);
    const RenderedImage without = render(false);
    const auto hits = traceSphere(view_, kSize, kSize, glm::dvec3(0.0), kRadiusM);
    glm::dvec3 added(0.0), base(0.0);
    double unlitAdded = 0.0;
    for (uint32_t y = 0; y < kSize; ++y)
        for (uint32_t x = 0; x < kSize; ++x) {
            const SphereHit& h = hits[size_t(y) * kSize + x];
            if (!h.interior) continue;
            const double NoL = glm::dot(glm::normalize(h.positionWs), L_);
            const glm::dvec3 d = pixelLinear(with, x, y) - pixelLinear(without, x, y);
            if (NoL > 0.0) {
                added += d;
                base += pixelLinear(without, x, y);
            } else {
                unlitAdded += d.r;
            }
        }
    std::printf("[ fidelity ] 10 mm sphere, lit side: transmission adds (%.4f, %.4f, %.4f) %%; unlit side red %+.4f\n",
                100.0 * added.r / base.r, 100.0 * added.g / base.g, 100.0 * added.b / base.b, unlitAdded);
    for (int c = 0; c < 3; ++c) EXPECT_LE(added[c], 0.005 * base[c]) << "channel " << c;
}

TEST_F(SkinFidelity, ThinSlabTransmissionMatchesTheReference) {
    const float thicknessM = 0.003f;
    Primitive slab = makeBox(glm::vec3(0.08f, 0.08f, thicknessM));
    slab.material = 0;
    Scene scene = makeScene({{slab, glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, -0.5f * thicknessM))}},
                            scene_.materials);
    Light light = scene_.lights[0];
    light.directionWs = glm::vec3(0.0f, 0.0f, 1.0f);  // from behind, towards the camera
    scene.lights = {light};
    const View view = perspectiveView(glm::inverse(glm::lookAt(glm::vec3(0.0f, 0.0f, 0.2f), glm::vec3(0.0f),
                                                               glm::vec3(0.0f, 1.0f, 0.0f))),
                                      0.5f, 1.0f, 0.05f, 1.0f);
    RenderSettings settings;
    settings.specular = false;
    Renderer renderer(context(), scene, Environment::constant(glm::vec3(0.0f)), &LutSet::loadDefault(), settings);
    const RenderedImage image = renderer.render(view, 32, 32, OutputEncoding::LinearFloat);
    const DiffusionReference reference(scene, scene.lights, ShRgb{}, LutSet::loadDefault().profile());
    const auto sample = reference.trace(glm::dvec3(0.0, 0.0, 0.2), glm::dvec3(0.0, 0.0, -1.0));
    ASSERT_TRUE(sample.has_value());
    glm::dvec3 skin(0.0);
    for (uint32_t y = 15; y <= 16; ++y)
        for (uint32_t x = 15; x <= 16; ++x) skin += 0.25 * pixelLinear(image, x, y);
    std::printf("[ fidelity ] 3 mm slab from behind: skin (%.4f, %.5f) reference (%.4f, %.5f) red, green\n", skin.r,
                skin.g, sample->radiance.r, sample->radiance.g);
    EXPECT_NEAR(skin.r, sample->radiance.r, 0.05 * sample->radiance.r);
    EXPECT_NEAR(skin.g, sample->radiance.g, 0.05 * sample->radiance.r);
}

}  // namespace
}  // namespace preskin::test
