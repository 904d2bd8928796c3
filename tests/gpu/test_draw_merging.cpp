// Draw submission: consecutive primitives of one instance that share a material become one draw
// (render/GpuScene), and the picture is the same as with one draw per primitive. The reference
// splits the runs with a second material of identical values, so each primitive is drawn alone.
#include "support/GpuTest.h"
#include "support/TestScenes.h"

#include "render/GpuScene.h"

#include <preskin/Renderer.h>

#include <glm/gtc/matrix_transform.hpp>

namespace preskin::test {
namespace {

class DrawMerging : public GpuTest {};

// A mesh of `count` quads in a row, one primitive each; primitive i uses materialOf(i).
Scene rowOfQuads(uint32_t count, const std::vector<Material>& materials, int (*materialOf)(uint32_t)) {
    Scene scene = makeScene({}, materials);
    Mesh mesh;
    for (uint32_t i = 0; i < count; ++i) {
        Primitive quad = makeQuad(0.5f, 2);
        for (Vertex& v : quad.vertices) v.positionOs.x += 0.6f * (float(i) - 0.5f * float(count - 1));
        quad.boundsOs = Bounds{};
        for (const Vertex& v : quad.vertices) quad.boundsOs.extend(v.positionOs);
        quad.material = materialOf(i);
        mesh.primitives.push_back(quad);
    }
    scene.meshes.push_back(mesh);
    scene.instances.push_back({0, glm::mat4(1.0f), "row"});
    scene.instances.push_back({0, glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.7f, -0.2f)), "row above"});
    Light light;
    light.type = LightType::Directional;
    light.directionWs = glm::normalize(glm::vec3(-0.3f, -0.4f, -1.0f));
    light.intensity = 2.0f;
    scene.lights = {light};
    return scene;
}

TEST_F(DrawMerging, RunsOfOneMaterialAreOneDrawAndLookTheSame) {
    Material red;
    red.baseColorFactor = glm::vec4(0.8f, 0.2f, 0.1f, 1.0f);
    red.roughnessFactor = 0.5f;
    Material blended = red;
    blended.alphaMode = AlphaMode::Blend;
    blended.baseColorFactor.a = 0.5f;
    constexpr uint32_t kQuads = 6;
    // Merged: quads 0-2 red, 3 blended, 4-5 red: per instance draws {0-2}, {3}, {4-5}.
    const Scene merged = rowOfQuads(kQuads, {red, blended}, [](uint32_t i) { return i == 3 ? 1 : 0; });
    // Reference: materials 0 and 2 alternate (identical values), so no two neighbours merge.
    const Scene reference =
        rowOfQuads(kQuads, {red, blended, red}, [](uint32_t i) { return i == 3 ? 1 : int(i % 2) * 2; });

    {
        const GpuScene gpu(ContextAccess::core(context()), merged);
        ASSERT_EQ(gpu.draws.size(), 6u);  // 3 per instance
        EXPECT_EQ(gpu.draws[0].indexCount, 3u * 24u);
        EXPECT_EQ(gpu.draws[1].indexCount, 24u);
        EXPECT_EQ(gpu.draws[2].indexCount, 2u * 24u);
        EXPECT_EQ(gpu.draws[3].instance, 1u);
        const GpuScene separate(ContextAccess::core(context()), reference);
        EXPECT_EQ(separate.draws.size(), 2u * kQuads);
    }

    RenderSettings settings;
    settings.shadows = false;
    const glm::mat4 worldFromView = glm::inverse(
        glm::lookAt(glm::vec3(0.2f, 0.3f, 3.0f), glm::vec3(0.0f, 0.3f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f)));
    const View view = perspectiveView(worldFromView, 0.9f, 1.5f, 0.1f, 10.0f);
    const Environment ambient = Environment::constant(glm::vec3(0.2f));
    Renderer mergedRenderer(context(), merged, ambient, nullptr, settings);
    Renderer referenceRenderer(context(), reference, ambient, nullptr, settings);
    const RenderedImage a = mergedRenderer.render(view, 96, 64, OutputEncoding::LinearFloat);
    const RenderedImage b = referenceRenderer.render(view, 96, 64, OutputEncoding::LinearFloat);
    ASSERT_EQ(a.rgba32f.size(), b.rgba32f.size());
    size_t covered = 0;
    for (size_t i = 0; i < a.rgba32f.size(); ++i) {
        ASSERT_EQ(a.rgba32f[i], b.rgba32f[i]) << "value " << i;
        if (i % 4 == 0 && a.rgba32f[i] > 0.1f) ++covered;
    }
    EXPECT_GT(covered, size_t(96 * 64 / 8)) << "the quads should cover a good part of the image";
}

}  // namespace
}  // namespace preskin::test
