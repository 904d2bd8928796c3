// `preskin bench`, animation: the deformation and curvature passes against the whole frame of an
// animated scene, and the GPU curvature pass against recomputing curvature on the CPU.
#include "BenchSections.h"

#include <preskin/Animation.h>
#include <preskin/Curvature.h>
#include <preskin/Environment.h>
#include <preskin/LutSet.h>
#include <preskin/ProfileLibrary.h>
#include <preskin/Scene.h>

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace preskin::cli::bench {

void BenchRun::animationSection() {
    // Animation: the deformation and curvature passes against the whole frame, for an animated
    // scene at its animation's middle (posed once: both passes run every frame whatever the pose),
    // and the GPU curvature pass against recomputing curvature on the CPU (updateMeshCurvature of
    // the CPU-deformed meshes, what a renderer without the pass would do per frame).
    struct AnimationRun {
        Measurement frame;
        double cpuCurvatureMs = 0.0;
        uint64_t deformedVertices = 0;
    };
    std::optional<AnimationRun> animation;
    if (!o.noAnimation) {
        const std::filesystem::path animatedPath = !o.animatedScene.empty() ? std::filesystem::path(o.animatedScene)
            : !scene.animations.empty()                                     ? scenePath
                                                                            : defaultAnimatedScenePath();
        const Scene animated = animatedPath == scenePath ? scene : loadScene(animatedPath, common);
        if (animated.animations.empty()) {
            fmt::print(stderr, "preskin bench: {} has no animation; skipping animation\n", animatedPath.string());
        } else {
            const Animation& clip = animated.animations.front();
            const float timeS = 0.5f * (clip.startS() + clip.endS());
            const ScenePose pose = posedScene(animated, animationNodePose(animated, clip, timeS));
            const View animatedView = frameBoundsView(animated.worldBounds(), float(o.width) / float(o.height));
            CommonOptions withLights = common;
            withLights.lights = o.vrLights;
            withLights.seed = o.seed;
            Renderer animatedRenderer(context, animated, environment, &luts, base);
            animatedRenderer.setPose(pose);
            Bench animatedBench(o, context, animatedView);
            AnimationRun run;
            run.frame = std::move(animatedBench.measure(
                {{&animatedRenderer, base,
                  fmt::format("{} lights, animated ({} at {:.2f} s)", o.vrLights, clip.name, timeS), 0.0}},
                sceneLights(animated, withLights))[0]);
            // The CPU recompute over the same deformed meshes, interleaved repetitions (with the
            // CPU deformation only).
            std::vector<Mesh> deformed;
            for (size_t i = 0; o.cpuDeform && i < animated.instances.size(); ++i) {
                const MeshInstance& instance = animated.instances[i];
                Mesh mesh = animated.meshes[size_t(instance.mesh)];
                bool morphs = false;
                for (const Primitive& p : mesh.primitives) morphs = morphs || !p.targets.empty();
                if (instance.skin < 0 && !morphs) continue;
                for (Primitive& p : mesh.primitives) {
                    std::vector<Vertex> out;
                    o.cpuDeform(p, pose.instances[i], out);
                    p.vertices = std::move(out);
                    run.deformedVertices += p.vertices.size();
                }
                deformed.push_back(std::move(mesh));
            }
            std::vector<double> cpuMs;
            for (uint32_t r = 0; o.cpuDeform && r < std::max<uint32_t>(o.reps, 1) + 1; ++r) {
                const auto t0 = Clock::now();
                for (Mesh& mesh : deformed) updateMeshCurvature(mesh);
                if (r > 0) cpuMs.push_back(secondsSince(t0) * 1000.0);  // the first is a warm-up
            }
            run.cpuCurvatureMs = o.cpuDeform ? median(cpuMs) : std::numeric_limits<double>::quiet_NaN();
            if (o.cpuDeform)
                fmt::print(stderr, "preskin bench:   curvature on the CPU: {:.2f} ms median\n", run.cpuCurvatureMs);
            animation = std::move(run);

            j.key("animation");
            j.beginObject();
            j.field("scene", reportedPath(animatedPath));
            j.field("animation", clip.name);
            j.field("time_s", timeS);
            j.field("lights", o.vrLights);
            j.field("deformed_vertices", animation->deformedVertices);
            j.key("frame");
            writeMeasurement(j, animation->frame);
            const double deformMs = animation->frame.passMs("deform");
            const double curvatureMs = animation->frame.passMs("curvature");
            j.field("deform_gpu_ms", deformMs);
            j.field("curvature_gpu_ms", curvatureMs);
            j.field("deform_and_curvature_share_gpu", (deformMs + curvatureMs) / animation->frame.gpuMs());
            j.field("deform_and_curvature_share_wall", (deformMs + curvatureMs) / animation->frame.wallMs());
            if (o.cpuDeform) {
                j.field("curvature_cpu_ms", animation->cpuCurvatureMs);
                j.field("curvature_cpu_over_gpu", animation->cpuCurvatureMs / curvatureMs);
            }
            j.endObject();
        }
    }

    if (animation) {
        const double passesMs = animation->frame.passMs("deform") + animation->frame.passMs("curvature");
        goal("deformation + curvature recompute / animated frame <= 0.10", passesMs / animation->frame.gpuMs(), 0.10,
             true);
        if (o.cpuDeform)
            goal("CPU curvature recompute / GPU curvature pass >= 10",
                 animation->cpuCurvatureMs / animation->frame.passMs("curvature"), 10.0, false);
    }
}

}  // namespace preskin::cli::bench
