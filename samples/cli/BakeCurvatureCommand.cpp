// `preskin bake-curvature`: bakes a signed curvature map per skin material of a scene
// (<preskin/CurvatureBake.h>) and writes each as a 16-bit PNG with a JSON beside it holding its
// scale and the PRESKIN_materials_skin fields that read it:
//   preskin bake-curvature [SCENE] --out DIR [--size N] [--dilation N] [--skin NAME|all]
// Files: DIR/<material>_curvature.png and .json (the name's characters other than letters,
// digits, '-' and '_' as '_'; the material index when names repeat). Every output is checked
// before anything is baked.
#include "CommandLine.h"  // samples/common
#include "Commands.h"
#include "Options.h"  // samples/common

#include <preskin/CurvatureBake.h>
#include <preskin/Error.h>
#include <preskin/OutputFile.h>
#include <preskin/Scene.h>

#include <fmt/core.h>

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <set>
#include <string>

namespace preskin::cli {
namespace {

struct BakeCurvatureOptions {
    std::string scene;
    std::string out;
    uint32_t size = 0;
    int dilation = 16;
    double rangeQuantile = 1.0;
    std::string skin;
};

std::string fileStem(const std::string& name) {
    std::string stem;
    for (char c : name) {
        const auto u = static_cast<unsigned char>(c);
        stem += std::isalnum(u) || c == '-' || c == '_' ? c : '_';
    }
    return stem.empty() ? "material" : stem;
}

void run(const BakeCurvatureOptions& o) {
    const std::filesystem::path scenePath = o.scene.empty() ? defaultScenePath() : std::filesystem::path(o.scene);
    Scene scene = Scene::load(scenePath);
    for (const std::string& w : scene.warnings) std::fprintf(stderr, "preskin: warning: %s\n", w.c_str());
    if (!o.skin.empty()) scene.makeSkin(o.skin);
    CurvatureBakeSettings settings;
    settings.size = o.size;
    settings.dilationTexels = o.dilation;
    settings.rangeQuantile = o.rangeQuantile;
    std::vector<CurvatureMap> maps = bakeCurvatureMaps(scene, settings);
    if (maps.empty())
        throw Error(
            fmt::format("{}: materials: no skin material is drawn (make materials skin with --skin NAME or all)",
                        scenePath.string()));
    std::set<std::string> stems;
    std::vector<std::filesystem::path> paths;
    for (const CurvatureMap& map : maps) {
        std::string stem = fileStem(map.materialName);
        if (!stems.insert(stem).second) stem += "_" + std::to_string(map.material);
        stems.insert(stem);
        paths.push_back(std::filesystem::path(o.out) / (stem + "_curvature.png"));
        checkOutputFile(paths.back());
        checkOutputFile(std::filesystem::path(paths.back()).replace_extension(".json"));
    }
    for (size_t i = 0; i < maps.size(); ++i) {
        writeCurvatureMap(maps[i], paths[i]);
        if (maps[i].skippedTriangles > 0)
            std::fprintf(
                stderr,
                "preskin: warning: %s: material '%s': %d triangles span more than the texture in UV; not baked\n",
                scenePath.string().c_str(), maps[i].materialName.c_str(), maps[i].skippedTriangles);
        if (maps[i].warnedInstances > 0)
            std::fprintf(stderr,
                         "preskin: warning: %s: material '%s' is drawn at %d other scales; the map has the first\n",
                         scenePath.string().c_str(), maps[i].materialName.c_str(), maps[i].warnedInstances);
        std::fprintf(stderr, "preskin: wrote %s (%ux%u, scale %.1f 1/m, bias 0.5)\n", paths[i].string().c_str(),
                     maps[i].width, maps[i].height, double(maps[i].scalePerM));
    }
}

}  // namespace

void addBakeCurvatureCommand(CLI::App& app) {
    auto o = std::make_shared<BakeCurvatureOptions>();
    CLI::App* cmd = app.add_subcommand("bake-curvature", "Bake a signed curvature map per skin material of a scene");
    cmd->add_option("scene", o->scene, "glTF scene (default: the bundled head)");
    cmd->add_option("--out", o->out, "output folder (created if missing)")->required();
    cmd->add_option("--size", o->size,
                    "map width and height, 16..8192 (default: the material's largest texture, 1024 without one)")
        ->check(wholeNumberIn(16, 8192));
    cmd->add_option("--dilation", o->dilation, "texel rings filled around the UV charts, 0..1024 (default 16)");
    cmd->add_option(
        "--range-quantile", o->rangeQuantile,
        "quantile of |curvature| the 16-bit range reaches, 0.5..1 (default 1: the largest; beyond it values clamp)");
    cmd->add_option("--skin", o->skin, "also make this material (or all) skin before baking");
    cmd->callback([o] { run(*o); });
}

}  // namespace preskin::cli
