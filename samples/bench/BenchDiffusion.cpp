// `preskin bench`, diffusion methods: preskin's pre-integrated skin against the baselines it
// replaces, screen-space separable and texture-space diffusion (RenderSettings::diffusion), and
// against Lambert skin (every technique off), on the scene's lights: mono at the bench size, and
// stereo with MSAA 4x at the VR size; each baseline's extra passes, targets and bytes from its
// frames' statistics.
#include "BenchSections.h"

#include <fmt/core.h>

#include <algorithm>
#include <string>
#include <vector>

namespace preskin::cli::bench {

void BenchRun::diffusionSection() {
    if (!hasSkin) return;
    const std::vector<Light> lights = sceneLights(scene, common);
    RenderSettings screen = base;
    screen.diffusion = Diffusion::ScreenSpace;
    RenderSettings texture = base;
    texture.diffusion = Diffusion::TextureSpace;
    RenderSettings lambert = base;
    lambert.skin = SkinFeatures::none();
    struct Row {
        std::string name;
        Measurement preIntegrated, screenSpace, textureSpace, lambertSkin;
    };
    std::vector<Row> rows;
    {
        Renderer screenRenderer(context, scene, environment, profiles, screen);
        Renderer textureRenderer(context, scene, environment, profiles, texture);
        std::vector<Measurement> m =
            bench.measure({{&renderer, base, fmt::format("mono {}x{}: pre-integrated", o.width, o.height), 0.0},
                           {&screenRenderer, screen, "mono: screen-space", 0.0},
                           {&textureRenderer, texture, "mono: texture-space", 0.0},
                           {&renderer, lambert, "mono: Lambert skin", 0.0}},
                          lights);
        rows.push_back({"mono", std::move(m[0]), std::move(m[1]), std::move(m[2]), std::move(m[3])});
    }
    const std::vector<uint32_t> offered = renderer.msaaSampleCounts();
    if (std::find(offered.begin(), offered.end(), 4u) != offered.end()) {
        const View stereo =
            stereoFromMono(frameBoundsView(scene.worldBounds(), float(o.vrWidth) / float(o.vrHeight)), o.ipdM);
        RenderSettings pre4 = base, screen4 = screen, texture4 = texture, lambert4 = lambert;
        pre4.msaaSamples = screen4.msaaSamples = texture4.msaaSamples = lambert4.msaaSamples = 4;
        Renderer preRenderer(context, scene, environment, profiles, pre4);
        Renderer screenRenderer(context, scene, environment, profiles, screen4);
        Renderer textureRenderer(context, scene, environment, profiles, texture4);
        std::vector<Measurement> m = bench.measure(
            {{&preRenderer, pre4, fmt::format("stereo {}x{} per eye, MSAA 4x: pre-integrated", o.vrWidth, o.vrHeight),
              0.0, &stereo, o.vrWidth, o.vrHeight},
             {&screenRenderer, screen4, "stereo MSAA 4x: screen-space", 0.0, &stereo, o.vrWidth, o.vrHeight},
             {&textureRenderer, texture4, "stereo MSAA 4x: texture-space", 0.0, &stereo, o.vrWidth, o.vrHeight},
             {&preRenderer, lambert4, "stereo MSAA 4x: Lambert skin", 0.0, &stereo, o.vrWidth, o.vrHeight}},
            lights);
        rows.push_back({"stereo_msaa4", std::move(m[0]), std::move(m[1]), std::move(m[2]), std::move(m[3])});
    }
    reportValidation(context);

    j.key("diffusion_methods");
    j.beginObject();
    for (const Row& row : rows) {
        j.key(row.name);
        j.beginObject();
        j.key("preintegrated");
        writeMeasurement(j, row.preIntegrated);
        j.key("screen");
        writeMeasurement(j, row.screenSpace);
        j.key("texture");
        writeMeasurement(j, row.textureSpace);
        j.key("lambert");
        writeMeasurement(j, row.lambertSkin);
        const double wall = row.preIntegrated.wallMs() / row.screenSpace.wallMs();
        j.field("preintegrated_over_screen", wall);
        j.field("preintegrated_over_screen_cpu", row.preIntegrated.cpuMs() / row.screenSpace.cpuMs());
        j.field("preintegrated_over_screen_gpu", row.preIntegrated.gpuMs() / row.screenSpace.gpuMs());
        j.field("preintegrated_over_texture", row.preIntegrated.wallMs() / row.textureSpace.wallMs());
        j.field("preintegrated_over_texture_cpu", row.preIntegrated.cpuMs() / row.textureSpace.cpuMs());
        j.field("screen_over_lambert", row.screenSpace.wallMs() / row.lambertSkin.wallMs());
        j.field("texture_over_lambert", row.textureSpace.wallMs() / row.lambertSkin.wallMs());
        j.field("preintegrated_over_lambert", row.preIntegrated.wallMs() / row.lambertSkin.wallMs());
        j.endObject();
        goal(fmt::format("diffusion {}: pre-integrated frame / screen-space frame (wall)", row.name), wall, 0.7, true);
    }
    j.endObject();
}

}  // namespace preskin::cli::bench
