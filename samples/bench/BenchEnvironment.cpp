// `preskin bench`, the environment: the frame with the prefiltered specular and the environment as
// background against the frame with neither (SH specular, cleared background), interleaved with
// the scene's lights, and the environment's update (Renderer::setEnvironment).
#include "BenchSections.h"

#include <preskin/Environment.h>
#include <preskin/LutSet.h>
#include <preskin/ProfileLibrary.h>
#include <preskin/Scene.h>

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace preskin::cli::bench {

void BenchRun::environmentSection() {
    const std::vector<Light> lights = sceneLights(scene, common);
    RenderSettings full = base, noBackground = base, neither = base;
    full.background.mode = BackgroundMode::Environment;
    neither.specularIbl = false;
    const std::vector<Measurement> measured =
        bench.measure({{&renderer, full, "specular IBL and background", 0.0},
                       {&renderer, noBackground, "specular IBL, cleared background", 0.0},
                       {&renderer, neither, "SH specular, cleared background", 0.0}},
                      lights);
    std::vector<double> updateMs;
    for (int i = 0; i < 3; ++i) {
        const auto start = Clock::now();
        renderer.setEnvironment(environment);
        updateMs.push_back(secondsSince(start) * 1000.0);
    }
    std::sort(updateMs.begin(), updateMs.end());
    j.key("environment");
    j.beginObject();
    j.field("method",
            "frames with the prefiltered specular and the environment as background, with the prefiltered "
            "specular alone and with neither (SH specular, cleared background), interleaved; the update: "
            "Renderer::setEnvironment (dominant lights, upload, GGX prefiltering), median of 3");
    j.field("image_width", environment.image().width);
    j.key("ibl_and_background");
    writeMeasurement(j, measured[0]);
    j.key("ibl");
    writeMeasurement(j, measured[1]);
    j.key("neither");
    writeMeasurement(j, measured[2]);
    j.field("ibl_and_background_share_of_frame", (measured[0].wallMs() - measured[2].wallMs()) / measured[0].wallMs());
    j.field("ibl_and_background_share_of_forward_gpu",
            (measured[0].passMs("forward") - measured[2].passMs("forward")) / measured[0].passMs("forward"));
    j.field("update_ms", updateMs[1]);
    j.endObject();
    goal("specular IBL and background / frame <= 0.08",
         (measured[0].wallMs() - measured[2].wallMs()) / measured[0].wallMs(), 0.08, true);
    goal("environment update (dominant lights, upload, prefiltering) <= 1000 ms", updateMs[1], 1000.0, true);
}

}  // namespace preskin::cli::bench
