// `preskin bake-curvature`: bakes a signed curvature map per skin material of a scene
// (<preskin/CurvatureBake.h>) and writes each as a 16-bit PNG with a JSON beside it holding its
// scale and the PRESKIN_materials_skin fields that read it:
//   preskin bake-curvature [SCENE] --out DIR [--size N] [--dilation N] [--skin NAME|all]
//                          [--scene-out FILE.gltf]
// Files: DIR/<material>_curvature.png and .json (the name's characters other than letters,
// digits, '-' and '_' as '_'; the material index when names repeat). With --scene-out, also the
// scene's glTF with each map as its material's curvatureTexture (sceneWithMaps below). Every
// output is checked before anything is baked.
#include "CommandLine.h"  // samples/common
#include "Commands.h"
#include "Options.h"  // samples/common

#include <preskin/CurvatureBake.h>
#include <preskin/Error.h>
#include <preskin/OutputFile.h>
#include <preskin/Scene.h>

#include <fmt/core.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
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
    std::string sceneOut;
};

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

std::string fileStem(const std::string& name) {
    std::string stem;
    for (char c : name) {
        const auto u = static_cast<unsigned char>(c);
        stem += std::isalnum(u) || c == '-' || c == '_' ? c : '_';
    }
    return stem.empty() ? "material" : stem;
}

// A glTF URI as the path it names ('+' a space, %XX a byte: how the loader reads it) and back
// (every byte but unreserved characters and '/' percent-encoded).
std::string uriToPath(const std::string& uri) {
    std::string out;
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '+') {
            out += ' ';
        } else if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
                   std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
            out += static_cast<char>(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

std::string pathToUri(const fs::path& path) {
    std::string out;
    for (char c : path.generic_string()) {
        const auto u = static_cast<unsigned char>(c);
        if (std::isalnum(u) || c == '-' || c == '_' || c == '.' || c == '~' || c == '/')
            out += c;
        else
            out += fmt::format("%{:02X}", unsigned(u));
    }
    return out;
}

// `file` as a URI relative to `folder` (both absolute); empty when it lies outside the folder,
// which scenes may not reference (docs/gltf-extensions.md, URIs).
std::string uriInside(const fs::path& file, const fs::path& folder) {
    const fs::path rel = file.lexically_normal().lexically_relative(folder.lexically_normal());
    if (rel.empty() || *rel.begin() == "..") return "";
    return pathToUri(rel);
}

// Every "uri" string of the document (buffers, images, extensions) that names a file, visited
// with its JSON pointer.
void forEachFileUri(Json& node, const std::string& pointer, const std::function<void(Json&, const std::string&)>& f) {
    if (node.is_object()) {
        for (auto it = node.begin(); it != node.end(); ++it) {
            const std::string at = pointer.empty() ? it.key() : pointer + "." + it.key();
            if (it.key() == "uri" && it->is_string() && it->get<std::string>().rfind("data:", 0) != 0)
                f(*it, at);
            else
                forEachFileUri(*it, at, f);
        }
    } else if (node.is_array()) {
        for (size_t i = 0; i < node.size(); ++i) forEachFileUri(node[i], pointer + "[" + std::to_string(i) + "]", f);
    }
}

// The source scene's glTF with each map (written at mapPaths) as its material's curvature
// texture: an image and a texture per map, the material's PRESKIN_materials_skin gaining
// curvatureSource "texture", curvatureTexture and the map's scale and bias (the extension added
// where --skin made the material skin, and a material added for primitives that had none); the
// other URIs re-rooted at the new scene's folder. Throws preskin::Error, naming the file and the
// field, for a binary glTF and for any URI that would leave the new scene's folder.
std::string sceneWithMaps(const fs::path& source, const std::vector<CurvatureMap>& maps,
                          const std::vector<fs::path>& mapPaths, const fs::path& sceneOut) {
    if (source.extension() == ".glb")
        throw Error(
            fmt::format("--scene-out: {}: a binary glTF (.glb); write-back reads .gltf scenes", source.string()));
    std::ifstream in(source, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    Json doc = Json::parse(text.str(), nullptr, false);
    if (!in || doc.is_discarded() || !doc.is_object())
        throw Error(fmt::format("--scene-out: {}: cannot read the scene's JSON", source.string()));
    const fs::path from = fs::absolute(source).parent_path();
    const fs::path to = fs::absolute(sceneOut).parent_path();
    if (from.lexically_normal() != to.lexically_normal()) {
        forEachFileUri(doc, "", [&](Json& uri, const std::string& at) {
            const std::string moved = uriInside(from / uriToPath(uri.get<std::string>()), to);
            if (moved.empty())
                throw Error(
                    fmt::format("--scene-out: {}: {} '{}' would leave the new scene's folder; write the "
                                "scene in {} or a folder above it",
                                sceneOut.string(), at, uri.get<std::string>(), from.string()));
            uri = moved;
        });
    }
    Json& materials = doc["materials"];
    if (!materials.is_array()) materials = Json::array();
    for (size_t i = 0; i < maps.size(); ++i) {
        const std::string uri = uriInside(fs::absolute(mapPaths[i]), to);
        if (uri.empty())
            throw Error(
                fmt::format("--scene-out: {}: the map {} lies outside the scene's folder (give --out a folder "
                            "inside it)",
                            sceneOut.string(), mapPaths[i].string()));
        size_t index = size_t(maps[i].material);
        if (index >= materials.size()) {  // the default material --skin all gave primitives without one
            index = materials.size();
            materials.push_back(Json{{"name", maps[i].materialName}});
            for (Json& mesh : doc["meshes"])
                for (Json& primitive : mesh["primitives"])
                    if (!primitive.contains("material")) primitive["material"] = index;
        }
        Json& images = doc["images"];
        images.push_back(Json{{"uri", uri}});
        Json& textures = doc["textures"];
        textures.push_back(Json{{"source", images.size() - 1}});
        Json& skin = materials[index]["extensions"]["PRESKIN_materials_skin"];
        if (!skin.is_object()) skin = Json::object();
        skin["curvatureSource"] = "texture";
        skin["curvatureTexture"] = Json{{"index", textures.size() - 1}};
        skin["curvatureTextureScalePerM"] = maps[i].scalePerM;
        skin["curvatureTextureBias"] = maps[i].bias;
    }
    Json& used = doc["extensionsUsed"];
    if (!used.is_array()) used = Json::array();
    if (std::find(used.begin(), used.end(), "PRESKIN_materials_skin") == used.end())
        used.push_back("PRESKIN_materials_skin");
    return doc.dump(2) + "\n";
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
    std::string sceneText;
    if (!o.sceneOut.empty()) {
        if (fs::path(o.sceneOut).extension() != ".gltf")
            throw Error(
                fmt::format("--scene-out: {}: value: the scene is written as glTF JSON: name it .gltf", o.sceneOut));
        checkOutputFile(o.sceneOut);
        sceneText = sceneWithMaps(scenePath, maps, paths, o.sceneOut);
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
    if (!o.sceneOut.empty()) {
        writeTextFile(o.sceneOut, sceneText);
        std::fprintf(stderr, "preskin: wrote %s (the scene reading the maps)\n", o.sceneOut.c_str());
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
    cmd->add_option("--scene-out", o->sceneOut,
                    "also write the scene (.gltf) with each map as its material's curvature texture; its URIs must "
                    "stay inside its folder (maps in --out under it)");
    cmd->callback([o] { run(*o); });
}

}  // namespace preskin::cli
