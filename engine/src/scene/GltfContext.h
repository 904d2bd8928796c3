// State shared by the parts of the glTF loader (materials, meshes, nodes), and typed readers for
// extension fields held as tinygltf::Value. Every reader names the field in its error message:
// a field that is present with the wrong type, or a number the input-number rule refuses
// (io/NumberRule.h: finite, at most 1e6 in magnitude), is an error; a missing one yields
// std::nullopt.
#pragma once

#include "io/MessageText.h"
#include "io/NumberRule.h"
#include "scene/GltfFiles.h"
#include "scene/TinyGltf.h"

#include <preskin/Scene.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace preskin::gltf {

struct LoadContext {
    std::string file;                // the scene file as given, for messages
    std::filesystem::path folder;    // absolute folder of the scene file
    bool allowOutsideLinks = false;  // follow symbolic links that leave the folder
    const tinygltf::Model* model = nullptr;
    Scene* scene = nullptr;
    // Per image: a description of its format when it is not decodable (then it has no pixels).
    std::vector<std::string> unsupportedImageFormat;
    // Cameras the prepass found of no glTF type (warned there): nodes' references to them are dropped.
    std::vector<size_t> skippedCameras;
    // Primitives (mesh, primitive) the prepass found drawing nothing (warned there): left out.
    std::vector<std::pair<size_t, size_t>> skippedPrimitives;

    [[noreturn]] void fail(const std::string& where, const std::string& what) const { gltf::fail(file, where, what); }
    void warn(const std::string& where, const std::string& what) const {
        scene->warnings.push_back(file + ": " + where + ": " + io::messageText(what, 4 * io::kMessageExcerptChars));
    }
};

// A number as written in JSON (shortest form: 0.5, 1, 1e-07).
inline std::string number(double value) { return io::numberText(value); }

// Fails naming `where` unless `value` passes the input-number rule; returns it.
inline double checkedNumber(const LoadContext& ctx, double value, const std::string& where) {
    if (auto problem = io::numberProblem(value)) ctx.fail(where, *problem);
    return value;
}

inline std::string indexed(const std::string& array, size_t index) { return array + "[" + std::to_string(index) + "]"; }

// Typed reads from a JSON object held as tinygltf::Value.
std::optional<double> numberField(const LoadContext& ctx, const tinygltf::Value& object, const char* key,
                                  const std::string& where);
std::optional<int> integerField(const LoadContext& ctx, const tinygltf::Value& object, const char* key,
                                const std::string& where);
std::optional<bool> boolField(const LoadContext& ctx, const tinygltf::Value& object, const char* key,
                              const std::string& where);
std::optional<std::string> stringField(const LoadContext& ctx, const tinygltf::Value& object, const char* key,
                                       const std::string& where);
std::optional<glm::vec2> vec2Field(const LoadContext& ctx, const tinygltf::Value& object, const char* key,
                                   const std::string& where);
std::optional<glm::vec3> vec3Field(const LoadContext& ctx, const tinygltf::Value& object, const char* key,
                                   const std::string& where);

// Components (passing the input-number rule) of a core glTF number array with an exact length,
// or nullopt when empty.
std::optional<std::vector<double>> fixedArray(const LoadContext& ctx, const std::vector<double>& values, size_t length,
                                              const std::string& where);

}  // namespace preskin::gltf
