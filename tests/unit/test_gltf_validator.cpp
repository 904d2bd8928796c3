// The Khronos glTF-Validator as the outside judge of what the loader accepts: over every .gltf and
// .glb in samples/assets and tests/data (scripts/validate-gltf.js; skipped with a message where
// node or the gltf-validator module is absent):
//  - every shipped scene (samples/assets) is valid (no error) and loads;
//  - a test file the loader refuses is invalid, or is listed below with the reason for the
//    policy (a limit of docs/limits.md, data the validator does not decode);
//  - a test file the loader accepts is valid, or is listed with the warning it gets.
#include "support/Process.h"

#include <preskin/Error.h>
#include <preskin/Scene.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace preskin::test {
namespace {

namespace fs = std::filesystem;

const fs::path kSource = PRESKIN_SOURCE_DIR;

// Valid by the validator, refused by the loader on purpose.
const std::map<std::string, std::string> kRefusedThoughValid{
    {"hostile/emissive_strength_1e300.gltf",
     "a number beyond 1e6 in magnitude (the input-number rule, docs/limits.md)"},
    {"hostile/light_intensity_1e300.gltf", "a number beyond 1e6 in magnitude (the input-number rule)"},
    {"hostile/skin_specular_1e300.gltf", "a number beyond 1e6 in magnitude (the input-number rule)"},
    {"hostile/texture_transform_1e300.gltf", "a number beyond 1e6 in magnitude (the input-number rule)"},
    {"hostile/huge_png.gltf", "an image larger than the texture limit (docs/limits.md), refused from its header"},
    {"hostile/png_bad_crc.gltf", "PNG data that does not decode (the validator reads image headers only)"},
    {"hostile/accessor_without_view_huge.gltf", "more vertices than the scene limit (docs/limits.md)"},
    {"gltf/required_extension.gltf",
     "a required extension preskin does not implement: glTF says a loader must refuse it"},
    {"gltf/uri_parent.gltf", "a URI that leaves the scene's folder (the URI policy, docs/gltf-extensions.md)"},
};

// Invalid by the validator, read by the loader (with a warning, or as the spec's intent is clear).
const std::map<std::string, std::string> kAcceptedThoughInvalid{};

std::vector<fs::path> gltfFiles() {
    std::vector<fs::path> files;
    for (const fs::path& root : {kSource / "samples" / "assets", kSource / "tests" / "data"})
        for (const auto& entry : fs::recursive_directory_iterator(root)) {
            const std::string ext = entry.path().extension().string();
            if (entry.is_regular_file() && (ext == ".gltf" || ext == ".glb")) files.push_back(entry.path());
        }
    std::sort(files.begin(), files.end());
    return files;
}

TEST(GltfValidator, ShippedScenesAreValidAndEveryRefusalIsInvalidOrAPolicy) {
    if (std::system("command -v node >/dev/null 2>&1") != 0) GTEST_SKIP() << "node is not installed";
    const std::vector<fs::path> files = gltfFiles();
    std::vector<std::string> args{(kSource / "scripts" / "validate-gltf.js").string()};
    for (const fs::path& f : files) args.push_back(f.string());
    const ProcessResult r = runProcess(
        "/usr/bin/env",
        [&] {
            std::vector<std::string> a{"node"};
            a.insert(a.end(), args.begin(), args.end());
            return a;
        }(),
        {}, fs::temp_directory_path(), 300.0);
    if (r.exitCode == 2) GTEST_SKIP() << r.err << " (set PRESKIN_GLTF_VALIDATOR to its folder)";
    ASSERT_EQ(r.exitCode, 0) << r.err;

    std::map<std::string, nlohmann::json> verdict;
    std::istringstream lines(r.out);
    for (std::string line; std::getline(lines, line);) {
        const nlohmann::json j = nlohmann::json::parse(line);
        verdict[j.at("file").get<std::string>()] = j;
    }
    ASSERT_EQ(verdict.size(), files.size());
    size_t shipped = 0, refused = 0, accepted = 0;
    for (const fs::path& file : files) {
        const nlohmann::json& v = verdict.at(file.string());
        const bool valid = v.at("errors").get<int>() == 0;
        std::string loadError;
        try {
            (void)Scene::load(file);
        } catch (const Error& e) {
            loadError = e.what();
        }
        const bool isShipped = file.string().find("/samples/assets/") != std::string::npos;
        const std::string key = fs::relative(file, kSource / "tests" / "data").string();
        if (isShipped) {
            ++shipped;
            EXPECT_TRUE(valid) << file << ": the validator reports " << v.dump();
            EXPECT_TRUE(loadError.empty()) << loadError;
        } else if (!loadError.empty()) {
            ++refused;
            if (valid) {
                EXPECT_TRUE(kRefusedThoughValid.count(key))
                    << key << " is valid glTF (" << v.dump() << ") but refused: " << loadError;
            } else {
                EXPECT_FALSE(kRefusedThoughValid.count(key))
                    << key << " is listed as valid but the validator says " << v.dump();
            }
        } else {
            ++accepted;
            if (!valid) {
                EXPECT_TRUE(kAcceptedThoughInvalid.count(key))
                    << key << " is invalid glTF (" << v.dump() << ") but loads";
            }
        }
    }
    std::printf("[ validator] %zu shipped, %zu refused, %zu accepted test files\n", shipped, refused, accepted);
    EXPECT_GE(shipped, 6u);
}

}  // namespace
}  // namespace preskin::test
