// Transmission through thin parts: a 3 mm skin slab and a 50 mm skin block side by side, lit only
// from behind by the shadowed directional light (no environment), seen from the front. The
// slab's front must glow red: every channel as the CPU predicts from the transmittance LUT at the
// slab's thickness (3 mm: measured from 2 profile-mm inside, plus those 2 mm along the light),
// times the far face's cosine saturate(-NoL) = 1, albedo / pi and the irradiance (a flat slab
// has no osculating sphere to subtract); red well above green and blue. The block's front must
// stay dark (T(50 mm) is nothing), and with transmission off the slab goes dark too.
#include "support/GpuTest.h"
#include "support/ImageCompare.h"
#include "support/SkinTestSupport.h"
#include "support/TestScenes.h"

#include <preskin/LutSet.h>
#include <preskin/Renderer.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdio>

namespace preskin::test {
namespace {

// Mean linear colour of a square of pixels around the projection of a world point.
glm::dvec3 meanAround(const RenderedImage& image, const View& view, const glm::vec3& pointWs, int halfSize) {
    const glm::vec4 clip = view.eye().clipFromWorld() * glm::vec4(pointWs, 1.0f);
    const int cx = static_cast<int>(std::floor((clip.x / clip.w * 0.5f + 0.5f) * float(image.width)));
    const int cy = static_cast<int>(std::floor((clip.y / clip.w * 0.5f + 0.5f) * float(image.height)));
    glm::dvec3 sum(0.0);
    int n = 0;
    for (int y = cy - halfSize; y <= cy + halfSize; ++y)
        for (int x = cx - halfSize; x <= cx + halfSize; ++x) {
            sum += pixelLinear(image, uint32_t(x), uint32_t(y));
            ++n;
        }
    return sum / double(n);
}

class SkinTransmission : public GpuTest {};

TEST_F(SkinTransmission, ThinSlabGlowsRedThickBlockStaysDark) {
    const LutSet& luts = LutSet::loadDefault();
    SkinMaterial skin;
    skin.scatterScale = 1.0f;
    Material material;
    material.baseColorFactor = glm::vec4(0.8f, 0.6f, 0.5f, 1.0f);
    material.metallicFactor = 0.0f;
    material.roughnessFactor = 0.6f;
    material.skin = skin;

    const float slabThicknessM = 0.003f;
    const float blockThicknessM = 0.05f;
    Primitive slab = makeBox(glm::vec3(0.08f, 0.08f, slabThicknessM));
    slab.material = 0;
    Primitive block = makeBox(glm::vec3(0.08f, 0.08f, blockThicknessM));
    block.material = 0;
    // Both front faces at z = 0, facing the camera.
    const glm::vec3 slabCenter(-0.06f, 0.0f, -0.5f * slabThicknessM);
    const glm::vec3 blockCenter(0.06f, 0.0f, -0.5f * blockThicknessM);
    Scene scene = makeScene(
        {{slab, glm::translate(glm::mat4(1.0f), slabCenter)}, {block, glm::translate(glm::mat4(1.0f), blockCenter)}},
        {material});
    Light light;
    light.type = LightType::Directional;
    light.directionWs = glm::vec3(0.0f, 0.0f, 1.0f);  // from behind, towards the camera
    light.intensity = 3.0f;
    light.castsShadow = true;
    scene.lights = {light};

    RenderSettings settings;
    Renderer renderer(context(), scene, Environment::constant(glm::vec3(0.0f)), &luts, settings);
    const uint32_t size = 128;
    const glm::mat4 worldFromView =
        glm::inverse(glm::lookAt(glm::vec3(0.0f, 0.0f, 0.35f), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f)));
    const View view = perspectiveView(worldFromView, 0.6f, 1.0f, 0.05f, 2.0f);
    const RenderedImage on = renderer.render(view, size, size, OutputEncoding::LinearFloat);
    RenderSettings noTransmission = settings;
    noTransmission.skin.transmission = false;
    noTransmission.skin.opposingLight = false;  // it carries the far side's light through thin parts too
    renderer.setSettings(noTransmission);
    const RenderedImage off = renderer.render(view, size, size, OutputEncoding::LinearFloat);
    dumpImage("skin_transmission_on", on);
    dumpImage("skin_transmission_off", off);

    const glm::vec3 slabFront(slabCenter.x, 0.0f, 0.0f);
    const glm::vec3 blockFront(blockCenter.x, 0.0f, 0.0f);
    const glm::dvec3 slabOn = meanAround(on, view, slabFront, 8);
    const glm::dvec3 blockOn = meanAround(on, view, blockFront, 8);
    const glm::dvec3 slabOff = meanAround(off, view, slabFront, 8);

    // What the shader should see: the slab's thickness in profile mm (measured from 2 profile-mm
    // inside, plus those 2 mm back along the light, which crosses the slab at normal incidence).
    const double shrinkMm = 2.0;
    const double thicknessMm = (double(slabThicknessM) * 1000.0 - shrinkMm / double(skin.scatterScale)) *
            double(skin.thicknessScale) * double(skin.scatterScale) +
        shrinkMm;
    const glm::dvec3 T(luts.lookupTransmittance(float(thicknessMm)));
    const double wrap = 1.0;  // saturate(-NoL), NoL = -1 on the front face
    const glm::dvec3 expected = T * wrap * double(skin.transmission) * glm::dvec3(skin.transmissionColor) *
        glm::dvec3(material.baseColorFactor) / 3.14159265358979323846 * double(light.intensity);
    std::printf(
        "[ skin     ] transmission: slab (%.4f, %.4f, %.4f), expected (%.4f, %.4f, %.4f); block (%.5f, %.5f, "
        "%.5f); slab without transmission (%.5f, %.5f, %.5f)\n",
        slabOn.r, slabOn.g, slabOn.b, expected.r, expected.g, expected.b, blockOn.r, blockOn.g, blockOn.b, slabOff.r,
        slabOff.g, slabOff.b);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(slabOn[c], expected[c], 0.05 * expected.r) << "channel " << c;
    EXPECT_GT(slabOn.r, 0.03) << "the thin slab should glow";
    EXPECT_GT(slabOn.r, 4.0 * slabOn.g) << "the glow should be red";
    EXPECT_GT(slabOn.r, 10.0 * slabOn.b) << "the glow should be red";
    EXPECT_LT(srgbDifference(blockOn, glm::dvec3(0.0)), 1.0) << "the thick block should stay dark";
    EXPECT_LT(srgbDifference(slabOff, glm::dvec3(0.0)), 1.0) << "without transmission the slab's front is unlit";
}

}  // namespace
}  // namespace preskin::test
