// FrameStats::passes: every pass of the frame has its GPU time, in the order the frame records
// them, and the times add up to the frame's (gpuMs, first to last timestamp), for preskin's own
// diffusion and both baselines. The wide shadow map's reduction, which only skin needs, is a pass
// of its own beside the shadow map's drawing.
#include "support/GpuTest.h"

#include <preskin/Environment.h>
#include <preskin/LutSet.h>
#include <preskin/Renderer.h>
#include <preskin/Scene.h>
#include <preskin/View.h>

#include <cmath>
#include <string>
#include <vector>

namespace preskin::test {
namespace {

class FramePasses : public GpuTest {};

std::vector<std::string> names(const FrameStats& s) {
    std::vector<std::string> out;
    for (const PassTime& p : s.passes) out.push_back(p.name);
    return out;
}

TEST_F(FramePasses, EveryPassIsTimedAndTheTimesAddUpToTheFrame) {
    const Scene scene = Scene::load(std::string(PRESKIN_SOURCE_DIR) + "/samples/assets/head/head.gltf");
    const LutSet& luts = LutSet::loadDefault();
    Renderer renderer(context(), scene, Environment::constant(glm::vec3(0.2f)), &luts, RenderSettings{});
    const View view = frameBoundsView(scene.worldBounds(), 1.0f);
    const std::vector<std::string> base = {"deform", "curvature", "shadow", "shadow reduction", "clusters"};
    struct Case {
        Diffusion diffusion;
        std::vector<std::string> after;  // the passes after the light grid
    };
    for (const Case& c : {Case{Diffusion::PreIntegrated, {"forward"}},
                          Case{Diffusion::ScreenSpace, {"forward", "diffusion rows", "diffusion columns"}},
                          Case{Diffusion::TextureSpace, {"texture irradiance", "texture blur", "forward"}}}) {
        RenderSettings settings;
        settings.diffusion = c.diffusion;
        renderer.setSettings(settings);
        renderer.render(view, 48, 48, OutputEncoding::LinearFloat);
        const FrameStats s = renderer.frameStats();
        std::vector<std::string> expected = base;
        expected.insert(expected.end(), c.after.begin(), c.after.end());
        ASSERT_EQ(names(s), expected) << "diffusion " << int(c.diffusion);
        double sum = 0.0;
        for (const PassTime& p : s.passes) {
            EXPECT_TRUE(std::isfinite(p.gpuMs) && p.gpuMs >= 0.0) << p.name << ": " << p.gpuMs;
            sum += p.gpuMs;
        }
        EXPECT_GT(s.gpuMs, 0.0);
        EXPECT_NEAR(sum, s.gpuMs, 1e-6 * s.gpuMs + 1e-9) << "diffusion " << int(c.diffusion);
    }
}

}  // namespace
}  // namespace preskin::test
