// `preskin bench`, skin: the skin material against the standard glTF material on the same mesh,
// textures and lights (and the skin shader with every technique off), and what each skin
// technique costs (the all-on frame minus the frame with that technique off).
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

void BenchRun::skinSection(const std::vector<uint32_t>& skinCounts) {
    // Skin vs standard material, same lights.
    struct SkinRow {
        uint32_t lights;
        Measurement skin, standard, featuresOff;
    };
    std::vector<SkinRow> skinRows;
    if (!skinCounts.empty() && hasSkin) {
        Renderer standardRenderer(context, standardScene, environment, profiles, base);
        for (uint32_t n : skinCounts) {
            CommonOptions withLights = common;
            withLights.lights = n;
            withLights.seed = o.seed;
            const std::vector<Light> lights = sceneLights(scene, withLights);
            RenderSettings off = base;
            off.skin = SkinFeatures::none();
            std::vector<Measurement> measured =
                bench.measure({{&renderer, base, fmt::format("{} lights, skin", n), 0.0},
                               {&standardRenderer, base, fmt::format("{} lights, standard material", n), 0.0},
                               {&renderer, off, fmt::format("{} lights, skin techniques off", n), 0.0}},
                              lights);
            skinRows.push_back({n, std::move(measured[0]), std::move(measured[1]), std::move(measured[2])});
        }
        j.key("skin_vs_standard");
        j.beginArray();
        for (const SkinRow& row : skinRows) {
            j.beginObject();
            j.field("lights", row.lights);
            j.key("skin");
            writeMeasurement(j, row.skin);
            j.key("standard_material");
            writeMeasurement(j, row.standard);
            j.key("skin_features_off");
            writeMeasurement(j, row.featuresOff);
            j.field("skin_over_standard", row.skin.wallMs() / row.standard.wallMs());
            j.field("skin_over_standard_gpu", row.skin.gpuMs() / row.standard.gpuMs());
            j.field("skin_over_standard_cpu", row.skin.cpuMs() / row.standard.cpuMs());
            j.field("skin_over_features_off", row.skin.wallMs() / row.featuresOff.wallMs());
            j.endObject();
        }
        j.endArray();

        // What each technique costs: the skin frame with one technique off at a time, beside the
        // frame with all on, the standard material and all off, interleaved (first skin count).
        if (!o.noTechniques) {
            const uint32_t n = skinCounts.front();
            CommonOptions withLights = common;
            withLights.lights = n;
            withLights.seed = o.seed;
            const std::vector<Light> lights = sceneLights(scene, withLights);
            struct Technique {
                const char* name;
                bool SkinFeatures::*flag;
            };
            const Technique techniques[] = {{"lut_diffuse", &SkinFeatures::lutDiffuse},
                                            {"normal_prefilter", &SkinFeatures::normalPrefilter},
                                            {"penumbra", &SkinFeatures::penumbra},
                                            {"sh_ambient", &SkinFeatures::shAmbient},
                                            {"transmission", &SkinFeatures::transmission},
                                            {"dual_specular", &SkinFeatures::dualSpecular},
                                            {"opposing_light", &SkinFeatures::opposingLight},
                                            {"normal_map_levels", &SkinFeatures::normalMapLevels},
                                            {"wide_penumbra", &SkinFeatures::widePenumbra},
                                            {"lut_shadow_light", &SkinFeatures::lutShadowLight},
                                            {"full_shadow_filter", &SkinFeatures::fullShadowFilter},
                                            {"lut_other_lights", &SkinFeatures::lutOtherLights},
                                            {"light_curvature", &SkinFeatures::lightCurvature}};
            std::vector<Config> configs{{&renderer, base, fmt::format("{} lights, skin", n), 0.0},
                                        {&standardRenderer, base, fmt::format("{} lights, standard material", n), 0.0}};
            for (const Technique& t : techniques) {
                // Off in turn; an addition to the default (lutOtherLights) on instead.
                RenderSettings without = base;
                without.skin.*t.flag = !(base.skin.*t.flag);
                configs.push_back(
                    {&renderer, without,
                     fmt::format("{} lights, skin {} {}", n, base.skin.*t.flag ? "without" : "with", t.name), 0.0});
            }
            // The quality tiers below high (every skin material at that tier), in the same rounds.
            const std::pair<const char*, SkinQuality> tiers[] = {{"medium", SkinQuality::Medium},
                                                                 {"low", SkinQuality::Low}};
            for (const auto& [name, quality] : tiers) {
                RenderSettings tier = base;
                tier.skinQuality = quality;
                configs.push_back({&renderer, tier, fmt::format("{} lights, skin at the {} tier", n, name), 0.0});
            }
            // Both frames without the depth prepass (RenderSettings::depthPrepass), in the same rounds.
            const size_t noPrepass = configs.size();
            for (const auto& [r, name] :
                 {std::pair{&renderer, "skin"}, std::pair{&standardRenderer, "standard material"}}) {
                RenderSettings without = base;
                without.depthPrepass = false;
                configs.push_back({r, without, fmt::format("{} lights, {}, no depth prepass", n, name), 0.0});
            }
            const std::vector<Measurement> measured = bench.measure(configs, lights);
            j.key("skin_techniques");
            j.beginObject();
            j.field("lights", n);
            j.field("method",
                    "each technique's cost: the default skin frame minus the frame with that technique off (its "
                    "standard fallback on), or for an addition to the default (lut_other_lights) its frame minus "
                    "the default, interleaved; wall, process CPU and forward-pass GPU ms");
            j.key("skin");
            writeMeasurement(j, measured[0]);
            j.key("standard_material");
            writeMeasurement(j, measured[1]);
            // What `heavier` takes beyond `lighter`, in each measure.
            auto writeDifference = [&](const char* key, const Measurement& heavier, const Measurement& lighter) {
                j.key(key);
                j.beginObject();
                j.field("wall", heavier.wallMs() - lighter.wallMs());
                j.field("cpu", heavier.cpuMs() - lighter.cpuMs());
                j.field("forward_gpu", heavier.passMs("forward") - lighter.passMs("forward"));
                j.endObject();
            };
            j.key("cost_ms");
            j.beginObject();
            for (size_t i = 0; i < std::size(techniques); ++i) {
                // What the technique adds to the frame it is in: for an addition, its frame less the default.
                const Measurement& with = base.skin.*techniques[i].flag ? measured[0] : measured[2 + i];
                const Measurement& without = base.skin.*techniques[i].flag ? measured[2 + i] : measured[0];
                writeDifference(techniques[i].name, with, without);
            }
            j.endObject();
            j.field("skin_over_standard", measured[0].wallMs() / measured[1].wallMs());
            j.field("skin_over_standard_gpu", measured[0].gpuMs() / measured[1].gpuMs());
            j.field("skin_over_standard_cpu", measured[0].cpuMs() / measured[1].cpuMs());
            j.key("tiers");
            j.beginObject();
            for (size_t i = 0; i < std::size(tiers); ++i) {
                const Measurement& m = measured[2 + std::size(techniques) + i];
                j.key(tiers[i].first);
                j.beginObject();
                j.key("frame");
                writeMeasurement(j, m);
                j.field("over_standard", m.wallMs() / measured[1].wallMs());
                j.field("over_standard_gpu", m.gpuMs() / measured[1].gpuMs());
                j.endObject();
            }
            j.endObject();
            // What the depth prepass saves each frame: the frame without it less the frame with it.
            j.key("depth_prepass_saves_ms");
            j.beginObject();
            writeDifference("skin", measured[noPrepass], measured[0]);
            writeDifference("standard_material", measured[noPrepass + 1], measured[1]);
            j.endObject();
            j.endObject();
        }
    } else if (!skinCounts.empty()) {
        fmt::print(stderr, "preskin bench: the scene has no skin material; skipping skin vs standard\n");
    }

    // Skin against standard: <= 1.3 on a software device (wall time: lavapipe shades on the same
    // cores the host runs on), <= 1.10 on a GPU (its timestamps, the frame's GPU time).
    const bool software = context.isSoftwareDevice();
    for (const SkinRow& row : skinRows)
        goal(fmt::format("skin frame / standard frame at {} lights <= {} ({})", row.lights, software ? "1.3" : "1.10",
                         software ? "wall time" : "GPU timestamps"),
             software ? row.skin.wallMs() / row.standard.wallMs() : row.skin.gpuMs() / row.standard.gpuMs(),
             software ? 1.3 : 1.10, true);
}

}  // namespace preskin::cli::bench
