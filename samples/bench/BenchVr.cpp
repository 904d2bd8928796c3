// `preskin bench`, VR: a stereo frame against the two mono frames of its eyes, CPU recording
// stereo against mono, the light grid built once for both eyes against a grid per eye, and MSAA
// 4x against 1x.
#include "BenchPerPixel.h"
#include "BenchSections.h"

#include <preskin/Environment.h>
#include <preskin/LutSet.h>
#include <preskin/ProfileLibrary.h>
#include <preskin/Scene.h>

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace preskin::cli::bench {

void BenchRun::vrSection() {
    // VR: a stereo frame against the two mono frames of its eyes, the light grid built for both
    // eyes (one grid through the cluster camera) against a grid per eye, and MSAA 4x against 1x.
    struct VrRun {
        Measurement stereo, left, right;
        std::optional<Measurement> msaa1, msaa4;
        Measurement recordStereo, recordMono;
        double combinedBuildMs = 0.0, perEyeBuildMs = 0.0;
        uint32_t eyeMsaa = 1;
        PerPixel perPixel[2];
    };
    std::optional<VrRun> vr;
    if (!o.noVr) {
        CommonOptions withLights = common;
        withLights.lights = o.vrLights;
        withLights.seed = o.seed;
        const std::vector<Light> lights = sceneLights(scene, withLights);
        const View stereo =
            stereoFromMono(frameBoundsView(scene.worldBounds(), float(o.vrWidth) / float(o.vrHeight)), o.ipdM);
        const View left(stereo.eyes[0]);
        const View right(stereo.eyes[1]);
        VrRun run;
        // One renderer per eye count and sample count, as an application keeps them: a renderer
        // resizes its attachments when either changes.
        // The eyes' frames at --vr-msaa samples where the device offers them (else 1).
        const std::vector<uint32_t> offered = renderer.msaaSampleCounts();
        RenderSettings eyeSettings = base;
        if (std::find(offered.begin(), offered.end(), o.vrMsaa) != offered.end()) eyeSettings.msaaSamples = o.vrMsaa;
        run.eyeMsaa = eyeSettings.msaaSamples;
        Renderer stereoRenderer(context, scene, environment, profiles, eyeSettings);
        Renderer monoRenderer(context, scene, environment, profiles, eyeSettings);
        std::vector<Measurement> eyes =
            bench.measure({{&stereoRenderer, eyeSettings,
                            fmt::format("{} lights, stereo {}x{} per eye, MSAA {}x", o.vrLights, o.vrWidth, o.vrHeight,
                                        eyeSettings.msaaSamples),
                            0.0, &stereo, o.vrWidth, o.vrHeight},
                           {&monoRenderer, eyeSettings, "left eye mono", 0.0, &left, o.vrWidth, o.vrHeight},
                           {&monoRenderer, eyeSettings, "right eye mono", 0.0, &right, o.vrWidth, o.vrHeight}},
                          lights);
        run.stereo = std::move(eyes[0]);
        run.left = std::move(eyes[1]);
        run.right = std::move(eyes[2]);
        // CPU recording alone (Renderer::record without the light-grid build): ~0.1 ms, so many
        // small interleaved frames; recording does not depend on the image size.
        {
            BenchOptions many = o;
            many.reps = std::max<uint32_t>(o.reps, 1) * 12;
            many.warmup = 3;
            Bench recordBench(many, context, stereo);
            std::vector<Measurement> recorded =
                recordBench.measure({{&stereoRenderer, base, "recording: stereo, 32x36 per eye", 0.0, &stereo, 32, 36},
                                     {&monoRenderer, base, "recording: left eye mono, 32x36", 0.0, &left, 32, 36}},
                                    lights);
            run.recordStereo = std::move(recorded[0]);
            run.recordMono = std::move(recorded[1]);
        }
        if (std::find(offered.begin(), offered.end(), 4u) != offered.end()) {
            RenderSettings four = base;
            four.msaaSamples = 4;
            Renderer msaaRenderer(context, scene, environment, profiles, four);
            std::vector<Measurement> msaa =
                bench.measure({{&renderer, base, fmt::format("{} lights, MSAA 1x", o.vrLights), 0.0},
                               {&msaaRenderer, four, fmt::format("{} lights, MSAA 4x", o.vrLights), 0.0}},
                              lights);
            run.msaa1 = std::move(msaa[0]);
            run.msaa4 = std::move(msaa[1]);
        }
        // Grid layouts, CPU builds interleaved: one grid for both eyes vs one grid per eye.
        std::vector<double> combined, perEye;
        ClusterGrid eyeGrids[2];
        for (uint32_t r = 0; r < std::max<uint32_t>(o.reps, 1) + 1; ++r) {
            auto t0 = Clock::now();
            const ClusterGrid both =
                buildClusterGrid(base.clusters, stereo, o.vrWidth, o.vrHeight, scene.worldBounds(), lights);
            auto t1 = Clock::now();
            for (uint32_t e = 0; e < 2; ++e)
                eyeGrids[e] = buildClusterGrid(base.clusters, View(stereo.eyes[e]), o.vrWidth, o.vrHeight,
                                               scene.worldBounds(), lights);
            auto t2 = Clock::now();
            if (r == 0) continue;  // warm-up
            combined.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
            perEye.push_back(std::chrono::duration<double, std::milli>(t2 - t1).count());
        }
        run.combinedBuildMs = median(combined);
        run.perEyeBuildMs = median(perEye);
        if (!o.noPerPixel) {
            const RenderedImage counted = lightCountImage(stereoRenderer, base, stereo, o.vrWidth, o.vrHeight, lights);
            for (uint32_t e = 0; e < 2; ++e)
                run.perPixel[e] = countPerPixel(eyeImage(counted, e), stereo.eyes[e], lights, &eyeGrids[e]);
            reportValidation(context);
        }
        vr = std::move(run);

        j.key("vr");
        j.beginObject();
        j.field("lights", o.vrLights);
        j.field("eye_width", o.vrWidth);
        j.field("eye_height", o.vrHeight);
        j.field("ipd_m", o.ipdM);
        j.field("msaa_samples", vr->eyeMsaa);
        j.key("stereo");
        writeMeasurement(j, vr->stereo);
        j.key("left_mono");
        writeMeasurement(j, vr->left);
        j.key("right_mono");
        writeMeasurement(j, vr->right);
        j.field("stereo_over_two_mono", vr->stereo.wallMs() / (vr->left.wallMs() + vr->right.wallMs()));
        j.field("stereo_over_two_mono_gpu", vr->stereo.gpuMs() / (vr->left.gpuMs() + vr->right.gpuMs()));
        j.field("grid_build_stereo_over_mono", vr->stereo.buildMs() / vr->left.buildMs());
        j.field("record_cpu_stereo_ms", vr->recordStereo.recordCpuMs());
        j.field("record_cpu_mono_ms", vr->recordMono.recordCpuMs());
        j.field("record_cpu_frames", vr->recordStereo.frames.size());
        j.field("record_cpu_stereo_over_mono", vr->recordStereo.recordCpuMs() / vr->recordMono.recordCpuMs());
        if (vr->msaa1) {
            j.key("msaa");
            j.beginObject();
            j.field("samples", 4);
            j.key("msaa_1x");
            writeMeasurement(j, *vr->msaa1);
            j.key("msaa_4x");
            writeMeasurement(j, *vr->msaa4);
            j.field("msaa4_over_msaa1", vr->msaa4->wallMs() / vr->msaa1->wallMs());
            j.field("msaa4_over_msaa1_gpu", vr->msaa4->gpuMs() / vr->msaa1->gpuMs());
            j.endObject();
        }
        j.key("grid_layout");
        j.beginObject();
        j.field("combined_build_cpu_ms", vr->combinedBuildMs);
        j.field("per_eye_build_cpu_ms", vr->perEyeBuildMs);
        if (!o.noPerPixel) {
            const PerPixel& a = vr->perPixel[0];
            const PerPixel& b = vr->perPixel[1];
            const double pixels = double(a.pixels + b.pixels);
            auto mean = [&](double PerPixel::*field) {
                return pixels > 0.0 ? (a.*field * double(a.pixels) + b.*field * double(b.pixels)) / pixels
                                    : std::nan("");
            };
            j.field("pixels", a.pixels + b.pixels);
            j.field("exact_mean", mean(&PerPixel::exactMean));
            j.field("combined_listed_mean", mean(&PerPixel::listedMean));
            j.field("per_eye_listed_mean", mean(&PerPixel::otherListedMean));
            j.field("combined_pixels_listed_below_exact", a.listedBelowExact + b.listedBelowExact);
        }
        j.endObject();
        j.endObject();
    }

    if (vr) {
        goal("stereo frame / (left mono + right mono frames) <= 0.85",
             vr->stereo.wallMs() / (vr->left.wallMs() + vr->right.wallMs()), 0.85, true);
        goal("light-grid build stereo / mono <= 1.3", vr->stereo.buildMs() / vr->left.buildMs(), 1.3, true);
        goal("CPU recording stereo / mono <= 1.1", vr->recordStereo.recordCpuMs() / vr->recordMono.recordCpuMs(), 1.1,
             true);
        if (vr->msaa1) goal("MSAA 4x frame / 1x frame <= 1.6", vr->msaa4->wallMs() / vr->msaa1->wallMs(), 1.6, true);
    }
}

}  // namespace preskin::cli::bench
