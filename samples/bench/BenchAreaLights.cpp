// `preskin bench`, area lights: the scene's lights plus 64 scattered lights as points and spots,
// and the same 64 as sphere, tube, rectangle and disc lights (--light-shape's sizes), against the
// scene's lights alone, interleaved: what one light of each shape costs the forward pass, over
// what one point light costs it.
#include "BenchSections.h"

#include <fmt/core.h>

#include <algorithm>
#include <string>
#include <vector>

namespace preskin::cli::bench {

void BenchRun::areaLightsSection() {
    constexpr uint32_t kLights = 64;
    const char* shapes[] = {"point", "sphere", "tube", "rectangle", "disc"};
    CommonOptions none = common;
    none.lights = 0;
    const std::vector<Light> sceneOnly = sceneLights(scene, none);
    std::vector<std::vector<Light>> sets;
    for (const char* shape : shapes) {
        CommonOptions withLights = common;
        withLights.lights = kLights;
        withLights.seed = o.seed;
        withLights.lightShape = shape;
        sets.push_back(sceneLights(scene, withLights));
    }
    RenderSettings clustered = base;
    clustered.lightLoop = LightLoop::Clustered;
    std::vector<Config> configs;
    configs.push_back({&renderer, clustered, "scene lights only", 0.0, nullptr, 0, 0, &sceneOnly});
    for (size_t i = 0; i < sets.size(); ++i)
        configs.push_back(
            {&renderer, clustered, fmt::format("{} {} lights", kLights, shapes[i]), 0.0, nullptr, 0, 0, &sets[i]});
    const std::vector<Measurement> measured = bench.measure(configs, sceneOnly);

    const double forwardNone = measured[0].passMs("forward");
    const double perPoint = (measured[1].passMs("forward") - forwardNone) / kLights;
    double worst = 0.0;
    j.key("area_lights");
    j.beginObject();
    j.field("method",
            fmt::format("the scene's lights plus {} scattered lights (--lights {} --light-shape SHAPE), each shape's "
                        "frames interleaved with the others' and with the scene's lights alone; per light: (forward "
                        "pass GPU ms - the scene's lights alone) / {}",
                        kLights, kLights, kLights));
    j.field("lights", kLights);
    j.key("scene_lights_only");
    writeMeasurement(j, measured[0]);
    for (size_t i = 0; i < sets.size(); ++i) {
        const double perLight = (measured[i + 1].passMs("forward") - forwardNone) / kLights;
        j.key(shapes[i]);
        j.beginObject();
        j.key("frame");
        writeMeasurement(j, measured[i + 1]);
        j.field("forward_ms_per_light", perLight);
        j.field("per_light_over_point", perPoint > 0.0 ? perLight / perPoint : 0.0);
        j.endObject();
        if (i > 0 && perPoint > 0.0) worst = std::max(worst, perLight / perPoint);
    }
    j.endObject();
    if (perPoint > 0.0) goal("forward cost of an area light / a point light's <= 2 (worst shape)", worst, 2.0, true);
}

}  // namespace preskin::cli::bench
