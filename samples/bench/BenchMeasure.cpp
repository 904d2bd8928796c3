// The measurement behind `preskin bench`; see BenchMeasure.h.
#include "BenchMeasure.h"

#include <time.h>

#include <cmath>

namespace preskin::cli::bench {

double processCpuMs() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

std::string reportedPath(const std::filesystem::path& path) {
    const std::filesystem::path relative = path.lexically_relative(dataDir());
    return !relative.empty() && *relative.begin() != ".." ? relative.generic_string() : path.string();
}

double median(std::vector<double> v) {
    if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void writeMeasurement(JsonWriter& j, const Measurement& m) {
    j.beginObject();
    j.field("warmup_frames", m.warmup);
    j.field("frames", m.frames.size());
    j.field("wall_ms", m.wallMs());
    j.field("cpu_ms", m.cpuMs());
    j.field("gpu_ms", m.gpuMs());
    j.key("gpu_pass_ms");
    j.beginObject();
    if (!m.frames.empty())
        for (const PassTime& p : m.frames.front().passes) j.field(p.name, m.passMs(p.name));
    j.endObject();
    j.field("cluster_build_cpu_ms", m.buildCpuMs());
    j.field("cluster_build_ms", m.buildMs());
    j.field("cluster_build", m.buildGpu() ? "gpu" : "cpu");
    j.field("record_cpu_ms", m.recordCpuMs());
    if (!m.frames.empty()) {
        j.field("eyes", m.frames.back().eyes);
        j.field("eye_drawing",
                m.frames.back().eyeDrawing == EyeDrawing::InstancedLayers ? "instanced layers" : "multiview");
    }
    j.field("overflowed_clusters", m.overflows());
    if (!m.frames.empty() && m.frames.back().clusterTileSizePx > 0) {
        j.field("cluster_grid_bytes", m.frames.back().clusterGridBytes);
        j.field("cluster_tile_px", m.frames.back().clusterTileSizePx);
        j.field("cluster_slices", m.frames.back().clusterDims.z);
    }
    if (!m.frames.empty() && m.frames.back().diffusionPasses > 0) {
        j.field("diffusion_passes", m.frames.back().diffusionPasses);
        j.field("diffusion_targets", m.frames.back().diffusionTargets);
        j.field("diffusion_target_bytes", m.frames.back().diffusionTargetBytes);
    }
    j.key("wall_ms_each");
    j.beginArray();
    for (const FrameStats& s : m.frames) j.number(s.wallMs);
    j.endArray();
    j.endObject();
}

double predictFrameMs(const std::vector<std::pair<double, double>>& points, double n) {
    if (points.empty()) return 0.0;
    if (points.size() == 1) return points.back().second * std::max(1.0, n / std::max(points.back().first, 1.0));
    const auto [n0, t0] = points[points.size() - 2];
    const auto [n1, t1] = points.back();
    const double slope = n1 > n0 ? std::max((t1 - t0) / (n1 - n0), 0.0) : 0.0;
    return t1 + slope * (n - n1);
}

}  // namespace preskin::cli::bench
