// `preskin bench`, the light loop: clustered against brute force at each --counts N, the light
// grid's build (CPU and compute, its share of the frame) and lights listed per pixel against the
// exact count.
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

void BenchRun::lightLoopSection(const std::vector<uint32_t>& counts) {
    // Clustered vs brute force, per-pixel counts, and the other build.
    struct Row {
        uint32_t lights;
        Measurement clustered;
        std::optional<Measurement> brute;
        std::optional<Measurement> otherBuild;
        std::optional<PerPixel> perPixel;
    };
    std::vector<Row> rows;
    std::vector<std::pair<double, double>> bruteHistory;
    std::vector<std::pair<double, double>> clusteredHistory;
    std::vector<std::pair<double, double>> otherHistory;
    const ClusterBuild otherBuild = [&] {
        // Which build the main measurement uses shows in its frame stats; the first frame tells.
        RenderSettings probe = base;
        renderer.setSettings(probe);
        renderer.render(view, 16, 16, OutputEncoding::DisplaySrgb8);
        return renderer.frameStats().clusterBuildGpu ? ClusterBuild::Cpu : ClusterBuild::Gpu;
    }();
    for (uint32_t n : counts) {
        CommonOptions withLights = common;
        withLights.lights = n;
        withLights.seed = o.seed;
        const std::vector<Light> lights = sceneLights(scene, withLights);
        Row row{n, {}, {}, {}, {}};
        std::vector<Config> configs;
        RenderSettings clustered = base;
        clustered.lightLoop = LightLoop::Clustered;
        configs.push_back(
            {&renderer, clustered, fmt::format("{} lights, clustered", n), predictFrameMs(clusteredHistory, n)});
        if (!o.noBuildCompare) {
            RenderSettings other = clustered;
            other.clusters.build = otherBuild;
            configs.push_back(
                {&renderer, other,
                 fmt::format("{} lights, clustered, {} build", n, otherBuild == ClusterBuild::Gpu ? "gpu" : "cpu"),
                 predictFrameMs(otherHistory, n)});
        }
        if (!o.noBrute) {
            RenderSettings brute = base;
            brute.lightLoop = LightLoop::All;
            configs.push_back(
                {&renderer, brute, fmt::format("{} lights, brute force", n), predictFrameMs(bruteHistory, n)});
        }
        std::vector<Measurement> measured = bench.measure(configs, lights);
        size_t next = 0;
        row.clustered = std::move(measured[next++]);
        clusteredHistory.emplace_back(n, row.clustered.wallMs());
        if (!o.noBuildCompare) {
            row.otherBuild = std::move(measured[next++]);
            otherHistory.emplace_back(n, row.otherBuild->wallMs());
        }
        if (!o.noBrute) {
            row.brute = std::move(measured[next++]);
            bruteHistory.emplace_back(n, row.brute->wallMs());
        }
        if (!o.noPerPixel) {
            const RenderedImage counted = lightCountImage(renderer, clustered, view, o.width, o.height, lights);
            row.perPixel = countPerPixel(counted, view.eye(), lights);
            reportValidation(context);
        }
        rows.push_back(std::move(row));
    }

    j.key("light_loop");
    j.beginArray();
    for (const Row& row : rows) {
        j.beginObject();
        j.field("lights", row.lights);
        j.key("clustered");
        writeMeasurement(j, row.clustered);
        if (row.brute) {
            j.key("brute_force");
            writeMeasurement(j, *row.brute);
            j.field("speedup", row.brute->wallMs() / row.clustered.wallMs());
            j.field("speedup_gpu", row.brute->gpuMs() / row.clustered.gpuMs());
        }
        j.field("cluster_build_share", row.clustered.buildMs() / row.clustered.wallMs());
        if (row.perPixel) {
            const PerPixel& p = *row.perPixel;
            j.key("per_pixel");
            j.beginObject();
            j.field("pixels", p.pixels);
            j.field("listed_mean", p.listedMean);
            j.field("exact_mean", p.exactMean);
            j.field("listed_over_exact", p.exactMean > 0.0 ? p.listedMean / p.exactMean : std::nan(""));
            j.field("listed_max", p.listedMax);
            j.field("exact_max", p.exactMax);
            j.field("pixels_listed_below_exact", p.listedBelowExact);
            j.endObject();
        }
        j.endObject();
    }
    j.endArray();

    if (!o.noBuildCompare) {
        j.key("cluster_build");
        j.beginArray();
        for (const Row& row : rows) {
            if (!row.otherBuild) continue;
            const Measurement& cpu = row.clustered.buildGpu() ? *row.otherBuild : row.clustered;
            const Measurement& gpu = row.clustered.buildGpu() ? row.clustered : *row.otherBuild;
            j.beginObject();
            j.field("lights", row.lights);
            for (const auto& [name, m] : {std::pair<const char*, const Measurement*>{"cpu", &cpu}, {"gpu", &gpu}}) {
                j.key(name);
                j.beginObject();
                j.field("build_ms", m->buildMs());
                j.field("build_cpu_ms", m->buildCpuMs());
                j.field("clusters_pass_gpu_ms", m->passMs("clusters"));
                j.field("frame_wall_ms", m->wallMs());
                j.field("frames", m->frames.size());
                j.endObject();
            }
            j.endObject();
        }
        j.endArray();
    }

    for (const Row& row : rows) {
        if (row.brute && (row.lights == 256 || row.lights == 1024))
            goal(fmt::format("clustered speedup over brute force at {} lights >= {}", row.lights,
                             row.lights == 256 ? 16 : 30),
                 row.brute->wallMs() / row.clustered.wallMs(), row.lights == 256 ? 16.0 : 30.0, false);
    }
    for (const Row& row : rows)
        if (row.perPixel && row.perPixel->exactMean > 0.0)
            goal(fmt::format("lights listed per pixel / exact at {} lights <= 1.5", row.lights),
                 row.perPixel->listedMean / row.perPixel->exactMean, 1.5, true);
    for (const Row& row : rows)
        if (row.lights == 1024 || row.lights == 65536)
            goal(fmt::format("cluster build share of the frame at {} lights <= 0.10", row.lights),
                 row.clustered.buildMs() / row.clustered.wallMs(), 0.10, true);
}

}  // namespace preskin::cli::bench
