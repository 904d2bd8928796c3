// The `preskin` tool end to end: bad input of every kind ends with one clear error line naming
// the file and the problem, a non-zero exit and no output file; a good render with validation on
// writes the image and reports its frame time.
#include "support/CliTest.h"
#include "support/Process.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sys/stat.h>
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

namespace preskin::test {

namespace {

namespace fs = std::filesystem;

using CliResult = ProcessResult;

class Cli : public preskin::test::CliTest {
protected:
    std::vector<std::string> renderArgs(const std::string& scene, const fs::path& out) {
        return {"render", scene,      "--out", out.string(), "--width",
                "32",     "--height", "32",    "--device",   preskin::test::testDevice()};
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
        {"skin_joint_out_of_range.gltf", "JOINTS_0"},
        {"skin_no_joints.gltf", "skins[0].joints"},
        {"skin_inverse_bind_count.gltf", "inverseBindMatrices"},
        {"morph_target_count_mismatch.gltf", "targets"},
        {"morph_weights_length.gltf", "weights"},
        {"anim_count_mismatch.gltf", "animations[0].samplers[0]"},
        {"anim_cubic_count.gltf", "animations[0].samplers[0]"},
        {"anim_nan_time.gltf", "animations[0].samplers[0].input"},
        {"anim_infinite_value.gltf", "animations[0].samplers[0].output"},
        {"anim_times_not_increasing.gltf", "animations[0].samplers[0].input"},
        {"anim_matrix_node.gltf", "target.node"},
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
        // One rule for every output: missing folders are made when the file is written...
        const fs::path out = dir_ / "new_folder" / "deeper" / "out.png";
        const CliResult r = run(renderArgs(scene, out));
        EXPECT_EQ(r.exitCode, 0) << r.err;
        EXPECT_TRUE(fs::is_regular_file(out));
        // ...and not made when the run fails before writing.
        const fs::path never = dir_ / "never_made" / "out.png";
        expectError(run(renderArgs((dir_ / "nothing.gltf").string(), never)), {"nothing.gltf"}, never);
        EXPECT_FALSE(fs::exists(dir_ / "never_made"));
        // A file where a folder should be.
        { std::ofstream(dir_ / "a_file") << "x"; }
        const fs::path underFile = dir_ / "a_file" / "out.png";
        expectError(run(renderArgs(scene, underFile)), {"a_file", "is not a folder"}, underFile);
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

// 8-bit RGBA pixels of a PNG, with its size.
std::vector<unsigned char> readPng(const fs::path& path, int& width, int& height) {
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) return {};
    const OIIO::ImageSpec& spec = in->spec();
    width = spec.width;
    height = spec.height;
    std::vector<unsigned char> pixels(size_t(width) * size_t(height) * 4);
    in->read_image(0, 0, 0, 4, OIIO::TypeDesc::UINT8, pixels.data());
    return pixels;
}

TEST_F(Cli, StereoWritesEyesSideBySideAndEyeRendersOneOfThem) {
    const std::string scene = (kData / "triangle.gltf").string();
    auto render = [&](const std::string& name, const std::vector<std::string>& extra) {
        const fs::path out = dir_ / name;
        auto args = renderArgs(scene, out);
        args.insert(args.end(), extra.begin(), extra.end());
        args.push_back("--validation");
        const CliResult r = run(args);
        EXPECT_EQ(r.exitCode, 0) << r.err;
        int w = 0, h = 0;
        std::vector<unsigned char> pixels = readPng(out, w, h);
        return std::make_tuple(pixels, w, h);
    };
    for (const std::string msaa : {"1", "4"}) {
        SCOPED_TRACE("MSAA " + msaa);
        const auto [both, w, h] = render("stereo.png", {"--stereo", "--ipd", "0.3", "--msaa", msaa});
        ASSERT_EQ(w, 64);
        ASSERT_EQ(h, 32);
        const auto [left, lw, lh] = render("left.png", {"--eye", "left", "--ipd", "0.3", "--msaa", msaa});
        const auto [right, rw, rh] = render("right.png", {"--eye", "right", "--ipd", "0.3", "--msaa", msaa});
        ASSERT_EQ(lw, 32);
        ASSERT_EQ(rw, 32);
        size_t differ = 0, eyesDiffer = 0;
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x)
                for (int c = 0; c < 4; ++c) {
                    const size_t i = (size_t(y) * 32 + size_t(x)) * 4 + size_t(c);
                    const size_t l = (size_t(y) * 64 + size_t(x)) * 4 + size_t(c);
                    const size_t r = l + 32 * 4;
                    differ += std::abs(int(both[l]) - int(left[i])) > 1;
                    differ += std::abs(int(both[r]) - int(right[i])) > 1;
                    eyesDiffer += left[i] != right[i];
                }
        EXPECT_EQ(differ, 0u);
        EXPECT_GT(eyesDiffer, 20u) << "a 30 cm IPD moves the triangle between the eyes";
    }
}

// --skin none: every material is the standard glTF material, exactly as the same scene written
// without the skin extension renders; the skin render differs from it.
TEST_F(Cli, SkinNoneRendersTheSceneWithoutItsSkinExtension) {
    const fs::path source = fs::path(PRESKIN_SOURCE_DIR) / "samples" / "assets" / "spheres" / "sphere_10mm.gltf";
    nlohmann::json gltf = nlohmann::json::parse(std::ifstream(source));
    bool hadSkin = false;
    for (auto& material : gltf["materials"]) {
        if (material.contains("extensions"))
            hadSkin = material["extensions"].erase("PRESKIN_materials_skin") > 0 || hadSkin;
    }
    ASSERT_TRUE(hadSkin);
    const fs::path stripped = dir_ / "sphere_standard.gltf";
    std::ofstream(stripped) << gltf.dump();
    auto render = [&](const std::string& scene, const std::string& name, const std::vector<std::string>& extra) {
        const fs::path out = dir_ / name;
        auto args = renderArgs(scene, out);
        args.insert(args.end(), extra.begin(), extra.end());
        const CliResult r = run(args);
        EXPECT_EQ(r.exitCode, 0) << r.err;
        int w = 0, h = 0;
        return readPng(out, w, h);
    };
    const auto none = render(source.string(), "none.png", {"--skin", "none"});
    const auto standard = render(stripped.string(), "standard.png", {});
    const auto skin = render(source.string(), "skin.png", {});
    ASSERT_FALSE(none.empty());
    EXPECT_EQ(none, standard);
    size_t differ = 0;
    for (size_t i = 0; i < skin.size() && i < none.size(); ++i) differ += std::abs(int(skin[i]) - int(none[i])) > 2;
    EXPECT_GT(differ, 20u) << "the skin render should differ from the standard one";
}

TEST_F(Cli, StereoAndMsaaRefuseWhatCannotBeDrawn) {
    const std::string scene = (kData / "triangle.gltf").string();
    const fs::path out = dir_ / "out.png";
    {
        // lavapipe offers 1 and 4 samples only.
        auto args = renderArgs(scene, out);
        args.insert(args.end(), {"--msaa", "8"});
        const CliResult r = run(args);
        if (preskin::test::testDevice() == "llvmpipe") expectError(r, {"msaa", "8"}, out);
    }
    for (const char* ipd : {"-0.1", "nan", "2"}) {
        auto args = renderArgs(scene, out);
        args.insert(args.end(), {"--stereo", "--ipd", ipd});
        const CliResult r = run(args);
        EXPECT_NE(r.exitCode, 0) << ipd;
        EXPECT_NE(r.err.find("--ipd"), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(out));
    }
    {
        auto args = renderArgs(scene, out);
        args.insert(args.end(), {"--eye", "middle"});
        const CliResult r = run(args);
        EXPECT_NE(r.exitCode, 0);
        EXPECT_NE(r.err.find("--eye"), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(out));
    }
}

const fs::path kTube = fs::path(PRESKIN_SOURCE_DIR) / "samples" / "assets" / "tube" / "tube.gltf";

TEST_F(Cli, AnimationOptionsRefuseBadInput) {
    const std::string tube = kTube.string();
    const fs::path out = dir_ / "out.png";
    const std::vector<std::pair<std::vector<std::string>, std::vector<std::string>>> cases = {
        {{"--animation", "nosuch"}, {"tube.gltf", "nosuch", "bend"}},
        {{"--animation", "7"}, {"tube.gltf", "7"}},
        {{"--time", "nan"}, {"--time", "nan"}},
        {{"--time", "inf"}, {"--time", "inf"}},
        {{"--sequence", "0:1"}, {"--sequence", "START:END:FPS"}},
        {{"--sequence", "1:0:10"}, {"--sequence", "END"}},
        {{"--sequence", "0:1:0"}, {"--sequence", "FPS"}},
        {{"--sequence", "0:nan:10"}, {"--sequence", "nan"}},
        {{"--sequence", "0:1000:1000"}, {"--sequence", "frames"}},
        {{"--sequence", "0:1:4"}, {"--out", "frame-number"}},  // --out has no %d field
    };
    for (const auto& [extra, needles] : cases) {
        SCOPED_TRACE(extra[0] + " " + extra[1]);
        auto args = renderArgs(tube, out);
        args.insert(args.end(), extra.begin(), extra.end());
        expectError(run(args), needles, out);
    }
    auto args = renderArgs((kData / "triangle.gltf").string(), out);
    args.insert(args.end(), {"--time", "1"});
    expectError(run(args), {"--animation", "triangle.gltf", "no animations"}, out);
}

// A sequence writes one numbered file per time, START to END inclusive, and each frame equals the
// single render at its time (--time): the same pose whichever way it is asked for.
TEST_F(Cli, SequenceWritesNumberedFramesEqualToSingleRenders) {
    const std::string tube = kTube.string();
    const fs::path pattern = dir_ / "frames" / "bend_%03d.png";
    fs::create_directories(pattern.parent_path());
    auto args = renderArgs(tube, pattern);
    args.insert(args.end(), {"--sequence", "0:1:4", "--validation"});
    const CliResult r = run(args);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("frame 5/5"), std::string::npos) << r.err;
    std::vector<fs::path> written;
    for (const auto& entry : fs::directory_iterator(pattern.parent_path())) written.push_back(entry.path());
    ASSERT_EQ(written.size(), 5u);
    std::vector<unsigned char> first;
    for (int frame = 0; frame < 5; ++frame) {
        SCOPED_TRACE(frame);
        char name[32];
        std::snprintf(name, sizeof(name), "bend_%03d.png", frame);
        int w = 0, h = 0;
        const std::vector<unsigned char> fromSequence = readPng(pattern.parent_path() / name, w, h);
        ASSERT_EQ(w, 32);
        ASSERT_EQ(h, 32);
        const fs::path single = dir_ / "single.png";
        auto one = renderArgs(tube, single);
        one.insert(one.end(), {"--time", std::to_string(0.25 * frame)});
        ASSERT_EQ(run(one).exitCode, 0);
        int sw = 0, sh = 0;
        const std::vector<unsigned char> alone = readPng(single, sw, sh);
        ASSERT_EQ(alone.size(), fromSequence.size());
        size_t differ = 0;
        for (size_t i = 0; i < alone.size(); ++i) differ += std::abs(int(alone[i]) - int(fromSequence[i])) > 1;
        EXPECT_EQ(differ, 0u);
        if (frame == 0)
            first = fromSequence;
        else if (frame == 4) {
            size_t moved = 0;
            for (size_t i = 0; i < first.size(); ++i) moved += first[i] != fromSequence[i];
            EXPECT_GT(moved, 40u) << "the tube bends 90 degrees between the first and the last frame";
        }
    }
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

}  // namespace preskin::test
