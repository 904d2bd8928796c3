// The `preskin` tool end to end: bad input of every kind ends with one clear error line naming
// the file and the problem, a non-zero exit and no output file; a good render with validation on
// writes the image and reports its frame time.
#include "support/CliTest.h"
#include "support/Process.h"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

using preskin::test::ProcessResult;
using CliResult = ProcessResult;

class Cli : public preskin::test::CliTest {
protected:
    std::vector<std::string> renderArgs(const std::string& scene, const fs::path& out) {
        return {"render", scene, "--out", out.string(), "--width", "32", "--height", "32", "--device",
                preskin::test::testDevice()};
    }
};

const fs::path kData = fs::path(PRESKIN_SOURCE_DIR) / "tests" / "data" / "gltf";

struct BadScene {
    const char* file;
    const char* field;  // a part of the message that locates the problem
};

TEST_F(Cli, BadScenesFailWithOneLineNamingFileAndField) {
    const BadScene cases[] = {
        {"truncated.glb", "truncated.glb"},
        {"bad_magic.glb", "magic"},
        {"bad_chunk_length.glb", "chunk"},
        {"bad_json.gltf", "bad_json.gltf"},
        {"missing_buffer.gltf", "buffers[0]"},
        {"missing_image.gltf", "images[0]"},
        {"required_extension.gltf", "extensionsRequired"},
        {"accessor_out_of_range.gltf", "accessors["},
        {"index_out_of_range.gltf", "index"},
        {"nan_position.gltf", "POSITION"},
        {"uri_parent.gltf", "uri"},
        {"uri_absolute.gltf", "uri"},
        {"unsupported_image.gltf", "images[0]"},
        {"huge_count.gltf", "count"},
    };
    for (const BadScene& c : cases) {
        SCOPED_TRACE(c.file);
        const fs::path out = dir_ / "out.png";
        const CliResult r = run(renderArgs((kData / c.file).string(), out));
        expectError(r, {c.file, c.field}, out);
    }
}

TEST_F(Cli, MissingSceneFile) {
    const fs::path out = dir_ / "out.png";
    const CliResult r = run(renderArgs((dir_ / "nothing.gltf").string(), out));
    expectError(r, {"nothing.gltf"}, out);
}

TEST_F(Cli, UnwritableOrUnsupportedOutput) {
    const std::string scene = (kData / "triangle.gltf").string();
    {
        const fs::path out = dir_ / "no_such_folder" / "out.png";
        expectError(run(renderArgs(scene, out)), {"no_such_folder", "does not exist"}, out);
    }
    {
        const fs::path locked = dir_ / "locked";
        fs::create_directories(locked);
        ::chmod(locked.c_str(), 0500);
        const fs::path out = locked / "out.png";
        const CliResult r = run(renderArgs(scene, out));
        ::chmod(locked.c_str(), 0700);
        if (::geteuid() != 0) expectError(r, {"locked", "not writable"}, out);  // root may write anyway
    }
    {
        const fs::path out = dir_ / "out.jpg";
        expectError(run(renderArgs(scene, out)), {"out.jpg", ".jpg"}, out);
    }
}

TEST_F(Cli, BadNumbersAndFlags) {
    const std::string scene = (kData / "triangle.gltf").string();
    const fs::path out = dir_ / "out.png";
    {
        auto args = renderArgs(scene, out);
        args.insert(args.end(), {"--orbit", "10,nan,1"});
        expectError(run(args), {"--orbit", "nan"}, out);
    }
    {
        auto args = renderArgs(scene, out);
        args.insert(args.end(), {"--camera", "nobody"});
        expectError(run(args), {"--camera", "nobody"}, out);
    }
    {
        auto args = renderArgs(scene, out);
        args.insert(args.end(), {"--env", (dir_ / "missing.hdr").string()});
        expectError(run(args), {"missing.hdr"}, out);
    }
    {
        auto args = renderArgs(scene, out);
        args.back() = "no-such-gpu";  // the --device value
        expectError(run(args), {"--device", "no-such-gpu"}, out);
    }
    {
        auto args = renderArgs(scene, out);
        args.insert(args.end(), {"--frobnicate"});
        const CliResult r = run(args);
        EXPECT_NE(r.exitCode, 0);
        EXPECT_NE(r.err.find("frobnicate"), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(out));
    }
    for (const char* width : {"0", "100000", "-3", "abc"}) {
        auto args = renderArgs(scene, out);
        args.insert(args.end(), {"--width", width});
        const CliResult r = run(args);
        EXPECT_NE(r.exitCode, 0) << width;
        EXPECT_NE(r.err.find("--width"), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(out));
    }
}

TEST_F(Cli, RenderWithValidationWritesImageAndFrameTime) {
    const fs::path out = dir_ / "head.png";
    auto args = renderArgs("", out);
    args.erase(args.begin() + 1);  // no scene: the bundled head
    args.insert(args.end(), {"--validation"});
    const CliResult r = run(args);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.err.find("validation"), std::string::npos) << r.err;
    EXPECT_TRUE(fs::exists(out));
    EXPECT_NE(r.out.find(out.string()), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("frame time"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(" ms"), std::string::npos) << r.out;
}

TEST_F(Cli, HelpEverywhere) {
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{"--help"}, {"render", "--help"}, {"bake", "--help"}}) {
        const CliResult r = run(args);
        EXPECT_EQ(r.exitCode, 0);
        EXPECT_NE(r.out.find("Usage"), std::string::npos) << r.out;
    }
}

}  // namespace
