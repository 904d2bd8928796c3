// `preskin compare`: how close skin comes to true diffusion. Renders the scene three ways for
// the same view and size: the skin path (every technique on), Lambert (the standard path,
// RenderSettings::skin = none) and the diffusion reference (DiffusionReference), all without
// specular (RenderSettings::specular = false; the reference models diffuse light only) and
// without normal maps (the reference shades the smooth surface), then reports per region the
// RMSE of skin and of Lambert against the reference and their ratio, as JSON (every field:
// docs/reference.md), plus a side-by-side PNG with error heat maps. The JSON holds no timings,
// so a run on the same machine and driver reproduces it exactly. `--diffusion screen` adds the
// screen-space baseline (RenderSettings::diffusion) to every region, beside skin and Lambert.
#include "CommandLine.h"  // samples/common
#include "Commands.h"
#include "CompareMetrics.h"
#include "ComparePicture.h"
#include "JsonWriter.h"
#include "Options.h"  // samples/common
#include "ReferenceOptions.h"

#include <preskin/Error.h>
#include <preskin/OutputFile.h>
#include <preskin/Renderer.h>

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <limits>
#include <memory>
#include <string>

namespace preskin::cli {

namespace {

struct Options {
    std::string scene;
    std::string json = "compare.json";
    std::string image = "compare.png";
    std::string referenceFile;  // reused when it holds this run's reference, else written
    std::string renders;        // prefix of the skin and Lambert renders' EXRs
    double curvatureClassPerMm = 0.01;
    std::vector<std::string> baselines;  // --diffusion: methods besides preskin's own
    ViewOptions view;
    CommonOptions common;
    ReferenceOptions reference;
};

void rgb(JsonWriter& j, std::string_view key, const glm::dvec3& v) {
    j.key(key);
    j.beginArray();
    for (int c = 0; c < 3; ++c) j.number(v[c]);
    j.endArray();
}

void stats(JsonWriter& j, std::string_view key, const ErrorStats& s) {
    j.key(key);
    j.beginObject();
    rgb(j, "rmse", s.rmse);
    j.field("rmsePooled", s.rmsePooled);
    rgb(j, "meanError", s.meanError);
    j.endObject();
}

double ratio(double a, double b) { return b > 0.0 ? a / b : (a > 0.0 ? std::numeric_limits<double>::infinity() : 1.0); }

// Scene edits that make the three images comparable: no normal maps anywhere.
uint32_t removeNormalMaps(Scene& scene) {
    uint32_t removed = 0;
    for (Material& m : scene.materials) {
        if (m.normal.valid()) ++removed;
        m.normal = TextureRef{};
        if (m.skin) {
            if (m.skin->detailNormalTexture.valid()) ++removed;
            m.skin->detailNormalTexture = SkinTextureRef{};
        }
    }
    return removed;
}

void run(const Options& o) {
    const std::filesystem::path jsonPath(o.json), imagePath(o.image);
    if (jsonPath.extension() != ".json") throw Error(fmt::format("{}: --json: the report is written as .json", o.json));
    checkOutputFile(jsonPath);
    if (imagePath.extension() != ".png")
        throw Error(fmt::format("{}: --image: the picture is written as .png", o.image));
    checkOutputPath(imagePath, OutputEncoding::DisplaySrgb8);
    checkViewOptions(o.view);
    const std::filesystem::path scenePath = o.scene.empty() ? defaultScenePath() : std::filesystem::path(o.scene);
    Scene scene = loadScene(scenePath, o.common);
    for (const std::string& warning : scene.warnings) fmt::print(stderr, "preskin: warning: {}\n", warning);
    applySkinOption(scene, o.common);
    const uint32_t normalMapsRemoved = removeNormalMaps(scene);
    const View view = makeView(scene, scenePath, o.view);
    const Environment environment = loadEnvironment(scene, o.common);
    const LutSet luts = loadLuts(o.common);
    const uint32_t width = o.view.width, height = o.view.height;

    const std::filesystem::path referencePath(o.referenceFile);
    std::error_code ec;
    const bool reuseReference = !o.referenceFile.empty() && std::filesystem::exists(referencePath, ec);
    if (!o.referenceFile.empty() && !reuseReference) checkOutputPath(referencePath, OutputEncoding::LinearFloat);
    const std::filesystem::path skinRenderPath = o.renders + ".skin.exr",
                                lambertRenderPath = o.renders + ".lambert.exr";
    std::vector<std::string> baselines;  // each once, in the order given
    for (const std::string& b : o.baselines)
        if (std::find(baselines.begin(), baselines.end(), b) == baselines.end()) baselines.push_back(b);
    if (!o.renders.empty()) {
        checkOutputPath(skinRenderPath, OutputEncoding::LinearFloat);
        checkOutputPath(lambertRenderPath, OutputEncoding::LinearFloat);
        for (const std::string& b : baselines)
            checkOutputPath(o.renders + "." + b + ".exr", OutputEncoding::LinearFloat);
    }
    const ReferenceKey key = referenceKey(scenePath, scene, o.view, o.common, o.reference, luts);
    // A reference file is read and checked before anything is rendered: a stale one stops the run at once.
    ReferenceImage ref;
    const auto start = std::chrono::steady_clock::now();
    if (reuseReference) {
        ReferenceKey made;
        ref = readReferenceImage(referencePath, made);
        for (const auto& field : key) {
            auto it = std::find_if(made.begin(), made.end(), [&](const auto& kv) { return kv.first == field.first; });
            const std::string was = it == made.end() ? std::string("(not recorded)") : it->second;
            if (was != field.second)
                throw Error(
                    fmt::format("{}: --reference: {}: the file was made for '{}', this run needs '{}' (remove "
                                "the file to compute it again)",
                                o.referenceFile, field.first, was, field.second));
        }
    }
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    auto context = Context::create(contextDesc(o.common));
    checkMsaaOption(*context, o.common.msaa);
    RenderSettings settings = renderSettings(o.common);  // the skin technique switches hold
    settings.specular = false;
    settings.debugView = DebugView::None;
    Renderer renderer(*context, scene, environment, &luts, settings);
    applyLightOptions(renderer, scene, o.common);
    const RenderedImage skin = renderer.render(view, width, height, OutputEncoding::LinearFloat);
    settings.skin = SkinFeatures::none();
    renderer.setSettings(settings);
    const RenderedImage lambert = renderer.render(view, width, height, OutputEncoding::LinearFloat);
    std::vector<RenderedImage> baselineImages;
    for (const std::string& b : baselines) {
        RenderSettings baseline = renderSettings(o.common);
        baseline.specular = false;
        baseline.debugView = DebugView::None;
        baseline.diffusion = diffusionMethod(b);
        renderer.setSettings(baseline);
        baselineImages.push_back(renderer.render(view, width, height, OutputEncoding::LinearFloat));
    }
    reportValidation(*context);

    if (!reuseReference) {
        const auto computeStart = std::chrono::steady_clock::now();
        const auto reference = makeReference(scene, environment, luts, o.common, o.reference);
        ref = renderReference(*reference, view, o.view, o.common.exposure, o.reference);
        seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - computeStart).count();
    }

    const std::vector<Region> regions = compareRegions(ref, o.curvatureClassPerMm);
    JsonWriter j;
    j.beginObject();
    j.field("scene", scenePath.string());
    j.field("width", width);
    j.field("height", height);
    j.field("view",
            !o.view.camera.empty()      ? "camera " + o.view.camera
                : !o.view.orbit.empty() ? "orbit " + o.view.orbit
                                        : std::string("default framing"));
    j.field("device", context->deviceName());
    j.field("profile", luts.profile().name());
    j.field("exposure", o.common.exposure);
    j.field("shadows", !o.common.noShadows);
    j.field("shadowMapSize", o.common.shadowMapSize);
    j.field("shadowSoftnessTexels", o.common.shadowSoftness);
    j.field("normalMapsRemoved", normalMapsRemoved);
    j.field("curvatureClassPerMm", o.curvatureClassPerMm);
    j.key("reference");
    j.beginObject();
    j.field("tailFraction", o.reference.settings.tailFraction);
    j.field("leafRatio", o.reference.settings.leafRatio);
    j.field("finestLeafRatio", o.reference.settings.finestLeafRatio);
    j.field("momentTolerance", o.reference.settings.momentTolerance);
    j.field("reachMm", luts.profile().reachMm(o.reference.settings.tailFraction));
    j.field("shadowEdgeRadiusMm", o.reference.settings.shadowEdgeWidths * luts.profile().maxWidthMm());
    j.field("terminatorClearanceMm", o.reference.settings.terminatorClearanceMm);
    j.endObject();
    j.key("regions");
    j.beginObject();
    fmt::print("preskin: compare on {} ({}x{}), RMSE against the reference (linear radiance):\n", context->deviceName(),
               width, height);
    fmt::print("  {:<13} {:>7}  {:>30}  {:>30}  {:>14}\n", "region", "pixels", "skin rmse r, g, b (pooled)",
               "lambert rmse r, g, b (pooled)", "skin / lambert");
    for (const Region& region : regions) {
        if (region.pixels == 0) {  // nothing to measure: no figures, not zeros and ratios of 1
            j.key(region.name);
            j.beginObject();
            j.field("pixels", region.pixels);
            j.endObject();
            fmt::print("  {:<13} {:>7}  no pixels\n", region.name, region.pixels);
            continue;
        }
        const ErrorStats s = measureError(skin.rgba32f, ref, region);
        const ErrorStats l = measureError(lambert.rgba32f, ref, region);
        j.key(region.name);
        j.beginObject();
        j.field("pixels", region.pixels);
        rgb(j, "referenceMean", regionMean(ref, region));
        stats(j, "skin", s);
        stats(j, "lambert", l);
        rgb(j, "ratioToLambert",
            glm::dvec3(ratio(s.rmse.r, l.rmse.r), ratio(s.rmse.g, l.rmse.g), ratio(s.rmse.b, l.rmse.b)));
        j.field("ratioToLambertPooled", ratio(s.rmsePooled, l.rmsePooled));
        fmt::print("  {:<13} {:>7}  {:.4f} {:.4f} {:.4f} ({:.4f})  {:.4f} {:.4f} {:.4f} ({:.4f})  {:>14.3f}\n",
                   region.name, region.pixels, s.rmse.r, s.rmse.g, s.rmse.b, s.rmsePooled, l.rmse.r, l.rmse.g, l.rmse.b,
                   l.rmsePooled, ratio(s.rmsePooled, l.rmsePooled));
        // Each baseline: its error, its ratio to Lambert's, and skin's ratio to its own.
        for (size_t b = 0; b < baselines.size(); ++b) {
            const ErrorStats e = measureError(baselineImages[b].rgba32f, ref, region);
            j.key(baselines[b]);
            j.beginObject();
            rgb(j, "rmse", e.rmse);
            j.field("rmsePooled", e.rmsePooled);
            rgb(j, "meanError", e.meanError);
            j.field("ratioToLambertPooled", ratio(e.rmsePooled, l.rmsePooled));
            j.field("skinRatioPooled", ratio(s.rmsePooled, e.rmsePooled));
            j.endObject();
            fmt::print("  {:<13} {:>7}  {:<8} {:.4f} {:.4f} {:.4f} ({:.4f}), / lambert {:.3f}, skin / {} {:.3f}\n", "",
                       "", baselines[b], e.rmse.r, e.rmse.g, e.rmse.b, e.rmsePooled, ratio(e.rmsePooled, l.rmsePooled),
                       baselines[b], ratio(s.rmsePooled, e.rmsePooled));
        }
        j.endObject();
    }
    j.endObject();
    j.endObject();
    // Written in this order, each removed again if a later one fails: nothing half done is left
    // behind (a reference that was computed is kept: it is complete and costly).
    std::vector<std::filesystem::path> written;
    try {
        if (!o.referenceFile.empty() && !reuseReference) writeReferenceImage(referencePath, ref, key);
        writeComparePicture(imagePath, scenePath.filename().string(), ref, skin.rgba32f, lambert.rgba32f, regions);
        written.push_back(imagePath);
        if (!o.renders.empty()) {
            writeImage(skinRenderPath, skin);
            written.push_back(skinRenderPath);
            writeImage(lambertRenderPath, lambert);
            written.push_back(lambertRenderPath);
            for (size_t b = 0; b < baselines.size(); ++b) {
                const std::filesystem::path path = o.renders + "." + baselines[b] + ".exr";
                writeImage(path, baselineImages[b]);
                written.push_back(path);
            }
        }
        writeTextFile(jsonPath, j.text() + "\n");
    } catch (...) {
        for (const auto& path : written) std::filesystem::remove(path, ec);
        throw;
    }
    fmt::print("preskin: wrote {} and {} (reference {} {:.1f} s)\n", jsonPath.string(), imagePath.string(),
               reuseReference ? "read in" : "computed in", seconds);
}

}  // namespace

void addCompareCommand(CLI::App& app) {
    auto options = std::make_shared<Options>();
    CLI::App* cmd = app.add_subcommand(
        "compare", "RMSE of skin and of Lambert against the diffusion reference (no specular), JSON and PNG");
    cmd->add_option("scene", options->scene, "glTF scene (.gltf or .glb); default: the bundled head scene");
    cmd->add_option("--json", options->json, "Report (.json)")->capture_default_str();
    cmd->add_option("--image", options->image, "Side-by-side picture with error heat maps (.png)")
        ->capture_default_str();
    cmd->add_option("--curvature-class", options->curvatureClassPerMm,
                    "Signed mean curvature (profile 1/mm) beyond which skin counts as convex or concave")
        ->check(numberIn(0.0, 100.0))
        ->capture_default_str();
    cmd->add_option("--reference", options->referenceFile,
                    "Reference image (.exr): read when it holds this run's reference (same scene, view, size, "
                    "lighting and quadrature), else computed and written there");
    cmd->add_option("--diffusion", options->baselines,
                    "Also measure these methods that preskin replaces, beside skin and Lambert: screen (the "
                    "screen-space separable baseline), texture (the texture-space baseline); several may be given")
        ->check(oneOf({"screen", "texture"}))
        ->delimiter(',');
    cmd->add_option("--renders", options->renders,
                    "Also write the skin and Lambert renders (and each --diffusion method's) as PREFIX.skin.exr, "
                    "PREFIX.lambert.exr (and PREFIX.screen.exr, PREFIX.texture.exr), linear");
    addViewOptions(*cmd, options->view);
    addSceneOptions(*cmd, options->common);
    addDeviceOptions(*cmd, options->common);
    addSkinTechniqueOptions(*cmd, options->common);
    addShadowMapOptions(*cmd, options->common);
    addDiffusionOptions(*cmd, options->common);
    addLutOptions(*cmd, options->common);
    addReferenceOptions(*cmd, options->reference);
    cmd->callback([options] { run(*options); });
}

}  // namespace preskin::cli
