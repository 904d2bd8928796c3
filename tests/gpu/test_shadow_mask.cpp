// Alpha-masked materials in the shadow map: a quad whose texture is transparent on its left half
// (alpha 0, cutoff 0.5) and opaque on its right half, 0.5 m above a floor, under a shadowed
// directional light from the upper left. The floor where the transparent half's shadow would fall
// is lit like open floor; where the opaque half's falls it is dark. Before the shadow pass read the
// mask, the whole quad cast a square shadow. Opaque and blended quads are the controls.
#include "support/GpuTest.h"
#include "support/TestLights.h"
#include "support/TestScenes.h"

#include <preskin/Environment.h>
#include <preskin/Renderer.h>
#include <preskin/View.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cstdio>
#include <cstdlib>
#include <string>

namespace preskin::test {
namespace {

class ShadowMask : public GpuTest {};

constexpr uint32_t kSize = 96;

// Mean linear green of the floor pixels around world point (x, 0, z) (a 3x3 pixel block).
double floorAt(const RenderedImage& image, const View& view, float x, float z) {
    const glm::vec4 clip = view.eyes[0].clipFromWorld() * glm::vec4(x, 0.0f, z, 1.0f);
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    const int px = int((ndc.x * 0.5f + 0.5f) * kSize), py = int((ndc.y * 0.5f + 0.5f) * kSize);
    double sum = 0.0;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
            sum += double(image.rgba32f[(size_t(py + dy) * kSize + size_t(px + dx)) * 4 + 1]);
    return sum / 9.0;
}

TEST_F(ShadowMask, TransparentTexelsCastNoShadow) {
    Image halves;
    halves.name = "left half transparent";
    halves.width = halves.height = 16;
    for (uint32_t y = 0; y < 16; ++y)
        for (uint32_t x = 0; x < 16; ++x)
            halves.rgba8.insert(halves.rgba8.end(), {255, 255, 255, uint8_t(x < 8 ? 0 : 255)});

    for (const AlphaMode mode : {AlphaMode::Mask, AlphaMode::Opaque}) {
        Material floor;
        floor.baseColorFactor = glm::vec4(0.8f, 0.8f, 0.8f, 1.0f);
        floor.roughnessFactor = 1.0f;
        floor.metallicFactor = 0.0f;
        Material caster = floor;
        caster.alphaMode = mode;
        caster.alphaCutoff = 0.5f;
        caster.doubleSided = true;
        const glm::mat4 flat = glm::rotate(glm::mat4(1.0f), -1.5707963f, glm::vec3(1.0f, 0.0f, 0.0f));
        Scene scene = makeScene({{makeQuad(6.0f, 1), flat},
                                 {makeQuad(1.0f, 1), glm::translate(glm::mat4(1.0f), {0.0f, 0.5f, 0.0f}) * flat}},
                                {floor, caster});
        scene.meshes[0].primitives[0].material = 0;
        scene.meshes[1].primitives[0].material = 1;
        scene.images.push_back(halves);
        scene.materials[1].baseColor.image = 0;
        scene.lights = {shadowedDirectionalLight({2.0f, -1.0f, 0.0f}, 3.0f)};  // a shadow 1 m right of its caster
        const View view =
            perspectiveView(glm::inverse(glm::lookAt(glm::vec3(0.5f, 4.0f, 0.0f), glm::vec3(0.5f, 0.0f, 0.0f),
                                                     glm::vec3(0.0f, 0.0f, -1.0f))),
                            0.9f, 1.0f, 0.1f, 20.0f);
        RenderSettings settings;
        settings.specular = false;
        Renderer renderer(context(), scene, Environment::constant(glm::vec3(0.0f)), nullptr, settings);
        const RenderedImage image = renderer.render(view, kSize, kSize, OutputEncoding::LinearFloat);
        if (const char* dump = std::getenv("PRESKIN_TEST_DUMP"))
            writeImage(std::string(dump) + (mode == AlphaMode::Mask ? "_mask.exr" : "_opaque.exr"), image);
        const double open = floorAt(image, view, -1.0f, 0.0f);         // no caster above
        const double underClear = floorAt(image, view, 0.75f, 0.0f);   // the transparent half's shadow
        const double underOpaque = floorAt(image, view, 1.25f, 0.0f);  // the opaque half's shadow
        std::printf("[ mask     ] %s: open floor %.4f, behind the transparent half %.4f, behind the opaque half %.4f\n",
                    mode == AlphaMode::Mask ? "masked" : "opaque", open, underClear, underOpaque);
        ASSERT_GT(open, 0.05);
        EXPECT_LT(underOpaque, 0.05 * open);
        if (mode == AlphaMode::Mask)
            EXPECT_NEAR(underClear, open, 0.02 * open);
        else
            EXPECT_LT(underClear, 0.05 * open);
    }
}

}  // namespace
}  // namespace preskin::test
