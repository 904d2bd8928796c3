// `preskin reference`: ground-truth diffuse radiance of a scene (DiffusionReference: the surface
// integral of the diffusion profile times the ray-traced irradiance) for the same view and
// image size as `preskin render`, written as a linear float EXR (alpha: 1 where a surface is
// visible) with the masks and the key `preskin compare --reference` reads (writeReferenceImage).
#include "Commands.h"
#include "Options.h"  // samples/common
#include "ReferenceOptions.h"

#include <preskin/Error.h>
#include <preskin/Renderer.h>

#include <fmt/core.h>

#include <chrono>
#include <memory>
#include <string>

namespace preskin::cli {

namespace {

struct Options {
    std::string scene;
    std::string out = "reference.exr";
    ViewOptions view;
    CommonOptions common;
    ReferenceOptions reference;
};

void run(const Options& o) {
    const std::filesystem::path outPath(o.out);
    if (encodingFor(outPath) != OutputEncoding::LinearFloat)
        throw Error(fmt::format("{}: --out: the reference is linear radiance: write it as .exr", o.out));
    checkOutputPath(outPath, OutputEncoding::LinearFloat);
    checkViewOptions(o.view);
    const std::filesystem::path scenePath = o.scene.empty() ? defaultScenePath() : std::filesystem::path(o.scene);
    Scene scene = loadScene(scenePath, o.common);
    for (const std::string& warning : scene.warnings) fmt::print(stderr, "preskin: warning: {}\n", warning);
    applySkinOption(scene, o.common);
    const View view = makeView(scene, scenePath, o.view);
    const Environment environment = loadEnvironment(scene, o.common);
    const LutSet luts = loadLuts(o.common);

    const auto start = std::chrono::steady_clock::now();
    const auto reference = makeReference(scene, environment, luts, o.common, o.reference);
    const ReferenceImage image = renderReference(*reference, view, o.view, o.common.exposure, o.reference);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    writeReferenceImage(outPath, image, referenceKey(scenePath, scene, o.view, o.common, o.reference, luts));
    fmt::print("preskin: wrote {} ({}x{})\n", outPath.string(), image.width, image.height);
    fmt::print("preskin: reference of '{}' in {:.1f} s: reach {:.2f} profile mm, {} irradiance samples\n",
               luts.profile().name(), seconds, reference->reachMm(), image.irradianceSamples);
}

}  // namespace

void addReferenceCommand(CLI::App& app) {
    auto options = std::make_shared<Options>();
    CLI::App* cmd = app.add_subcommand(
        "reference", "Ground-truth diffuse radiance (diffusion profile integrated over the surface) to a linear EXR");
    cmd->add_option("scene", options->scene, "glTF scene (.gltf or .glb); default: the bundled head scene");
    cmd->add_option("--out,-o", options->out, "Output image (.exr, linear)")->capture_default_str();
    addViewOptions(*cmd, options->view);
    addSceneOptions(*cmd, options->common);
    addLutOptions(*cmd, options->common);
    addReferenceOptions(*cmd, options->reference);
    cmd->callback([options] { run(*options); });
}

}  // namespace preskin::cli
