// What a new user trips over, end to end through the built tools: each case is a command a user
// types after reading the README, and what it must do. (Misspelt options: HostileInput.
// CommandLineErrorsAreOneLineAndExitOne; output folders: Cli.UnwritableOrUnsupportedOutput;
// pkg-config: HostSample.PkgConfigFindsAMovedInstall; the documented commands: Docs.*; the
// viewer's --msaa: Viewer.MsaaTheDeviceDoesNotOfferIsRefusedAtStart.)
#include "support/CliTest.h"
#include "support/ImageCompare.h"
#include "support/Process.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace preskin::test {
namespace {

namespace fs = std::filesystem;

const fs::path kSource = PRESKIN_SOURCE_DIR;
const fs::path kTriangle = kSource / "tests" / "data" / "gltf" / "triangle.gltf";
const fs::path kHead = kSource / "samples" / "assets" / "head" / "head.gltf";

class NewUser : public CliTest {
protected:
    // Small images; on the test device for the commands that render (reference runs on the CPU).
    std::vector<std::string> small(std::vector<std::string> args) const {
        args.insert(args.end(), {"--width", "16", "--height", "16"});
        if (args[0] != "reference") args.insert(args.end(), {"--device", testDevice()});
        return args;
    }
};

TEST_F(NewUser, UnknownCameraListsTheScenesCameras) {
    const fs::path out = dir_ / "out.png";
    expectError(run(small({"render", kHead.string(), "--camera", "side", "--out", out.string()})),
                {"--camera side", "has no camera of that name", "its cameras: front, cheek_nose, lips, ear"}, out);
    expectError(run(small({"render", kTriangle.string(), "--camera", "front", "--out", out.string()})),
                {"--camera front", "it has no cameras"}, out);
}

TEST_F(NewUser, ASceneThatIsAFolderOrMissingSaysSo) {
    const fs::path out = dir_ / "out.png";
    expectError(run(small({"render", (kSource / "docs").string(), "--out", out.string()})),
                {"docs: file: is a folder, not a glTF scene"}, out);
    // A relative path is resolved against the working folder, and the message says where it looked.
    expectError(run(small({"render", "scenes/head.gltf", "--out", out.string()})),
                {"scenes/head.gltf: file: not found (looked for " + (dir_ / "scenes" / "head.gltf").string() + ")"},
                out);
}

TEST_F(NewUser, BakeProfileKeywordsJsonFormsAndTypos) {
    const fs::path out = dir_ / "luts";
    expectError(run({"bake", "--profile", "Burley", "--out", out.string()}),
                {"--profile Burley: value:", "did you mean burley?", "looked for " + (dir_ / "Burley").string()}, out);
    // The JSON forms docs/gltf-extensions.md lists are the forms of `bake --profile FILE.json`.
    std::ofstream(dir_ / "deon.json") << R"({"type": "deonLuebke", "name": "skin"})";
    const ProcessResult deon = run({"bake", "--profile", (dir_ / "deon.json").string(), "--out", out.string()});
    EXPECT_EQ(deon.exitCode, 0) << deon.err;
    EXPECT_TRUE(fs::exists(out / "manifest.json"));
    // A LUT folder is loaded, not baked: said so, with where to use it.
    std::ofstream(dir_ / "folder.json") << R"({"type": "lutFolder", "uri": "luts"})";
    const fs::path other = dir_ / "other";
    expectError(run({"bake", "--profile", (dir_ / "folder.json").string(), "--out", other.string()}),
                {"folder.json: type:", "already baked", "--luts"}, other);
}

TEST_F(NewUser, ReferenceAndCompareTakeLuts) {
    const std::string luts = (kSource / "luts").string();
    const ProcessResult reference =
        run(small({"reference", kTriangle.string(), "--luts", luts, "--out", (dir_ / "r.exr").string()}));
    EXPECT_EQ(reference.exitCode, 0) << reference.err;
    const ProcessResult compare = run(small({"compare", kTriangle.string(), "--luts", luts, "--json",
                                             (dir_ / "c.json").string(), "--image", (dir_ / "c.png").string()}));
    EXPECT_EQ(compare.exitCode, 0) << compare.err;
}

TEST_F(NewUser, MsaaTheDeviceDoesNotOfferNamesTheOption) {
    if (testDevice() != "llvmpipe") GTEST_SKIP() << "lavapipe offers 1 and 4 samples; other devices differ";
    const fs::path out = dir_ / "out.png";
    expectError(run(small({"render", kTriangle.string(), "--msaa", "2", "--out", out.string()})),
                {"--msaa: value: 2 samples are not offered by llvmpipe", "(offered: 1, 4)"}, out);
}

TEST_F(NewUser, StereoAndOneEyeAreNotBothAccepted) {
    const fs::path out = dir_ / "out.png";
    expectError(run(small({"render", kTriangle.string(), "--stereo", "--eye", "left", "--out", out.string()})),
                {"cannot be combined with"}, out);
}

TEST_F(NewUser, ASceneWithNothingToDrawWarns) {
    std::ofstream(dir_ / "empty.gltf") << R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": []}], "scene": 0})";
    const fs::path out = dir_ / "out.png";
    const ProcessResult r = run(small({"render", (dir_ / "empty.gltf").string(), "--out", out.string()}));
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("preskin: warning: " + (dir_ / "empty.gltf").string() + ": scenes: nothing to draw"),
              std::string::npos)
        << r.err;
}

// The same image written twice, a second apart, is the same bytes (no time stamp in the file).
TEST_F(NewUser, ExrOutputsAreTheSameBytesRunToRun) {
    std::string first;
    for (int i = 0; i < 2; ++i) {
        const fs::path out = dir_ / ("out" + std::to_string(i) + ".exr");
        const ProcessResult r = run(small({"render", kTriangle.string(), "--out", out.string()}));
        ASSERT_EQ(r.exitCode, 0) << r.err;
        if (i == 0) {
            first = readFile(out);
            ::sleep(1);
        } else {
            EXPECT_EQ(readFile(out), first);
        }
    }
    const ProcessResult ref = run(small({"reference", kTriangle.string(), "--out", (dir_ / "a.exr").string()}));
    ASSERT_EQ(ref.exitCode, 0) << ref.err;
    ::sleep(1);
    ASSERT_EQ(run(small({"reference", kTriangle.string(), "--out", (dir_ / "b.exr").string()})).exitCode, 0);
    EXPECT_EQ(readFile(dir_ / "a.exr"), readFile(dir_ / "b.exr"));
}

TEST_F(NewUser, SequenceIntoAFolderThatDoesNotExistYet) {
    const fs::path animated = kSource / "samples" / "assets" / "head" / "head_animated.gltf";
    const ProcessResult r = run(small({"render", animated.string(), "--sequence", "0:0.2:10", "--out",
                                       (dir_ / "frames" / "talk_%04d.png").string()}));
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::exists(dir_ / "frames" / "talk_0000.png"));
    EXPECT_TRUE(fs::exists(dir_ / "frames" / "talk_0001.png"));
}

// scripts/render-sample.sh --out FILE: the caller's output replaces the default head.png.
TEST_F(NewUser, RenderSampleScriptTakesTheCallersOut) {
    const fs::path out = dir_ / "other.png";
    const ProcessResult r =
        runProcess(kSource / "scripts" / "render-sample.sh",
                   {"--out", out.string(), "--width", "16", "--height", "16", "--device", testDevice()},
                   {"PRESKIN_SKIP_SETUP=1", std::string("PRESKIN_BUILD_DIR=") + PRESKIN_BINARY_DIR}, dir_, 120.0);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::exists(out));
}

// `render --profile` bakes a profile at start as the viewer's --profile does (burley with the
// viewer's parameters unless --albedo and --mfp say otherwise): the image is the one rendered with
// the same profile baked by `preskin bake` into a LUT folder, and differs from the default d'Eon set.
TEST_F(NewUser, RenderTakesAProfileAsTheViewerDoes) {
    const fs::path burley = dir_ / "burley.png", baked = dir_ / "baked.png", deon = dir_ / "deon.png";
    const ProcessResult a =
        run(small({"render", "--camera", "cheek_nose", "--profile", "burley", "--out", burley.string()}));
    ASSERT_EQ(a.exitCode, 0) << a.err;
    const ProcessResult bake = run({"bake", "--profile", "burley", "--albedo", "0.83,0.57,0.45", "--mfp",
                                    "1.2,0.5,0.25", "--size", "256", "--out", (dir_ / "luts").string()});
    ASSERT_EQ(bake.exitCode, 0) << bake.err;
    const ProcessResult b =
        run(small({"render", "--camera", "cheek_nose", "--luts", (dir_ / "luts").string(), "--out", baked.string()}));
    ASSERT_EQ(b.exitCode, 0) << b.err;
    const ProcessResult c = run(small({"render", "--camera", "cheek_nose", "--out", deon.string()}));
    ASSERT_EQ(c.exitCode, 0) << c.err;
    std::string error;
    const RenderedImage imageA = readPng(burley, error), imageB = readPng(baked, error), imageC = readPng(deon, error);
    ASSERT_FALSE(imageA.rgba8.empty()) << error;
    int largest = 0;
    // The LUT folder stores half floats: a step of 1/255 at most.
    EXPECT_EQ(pixelsDifferingBy(imageA, imageB, 1, largest), 0u) << "largest difference " << largest;
    EXPECT_GT(pixelsDifferingBy(imageA, imageC, 1, largest), 0u) << "burley should not render as d'Eon";
    const fs::path out = dir_ / "out.png";
    expectError(
        run(small({"render", "--profile", "burley", "--luts", (dir_ / "luts").string(), "--out", out.string()})),
        {"--profile", "--luts"}, out);
    expectError(run(small({"render", "--profile", "deon", "--albedo", "0.5,0.5,0.5", "--out", out.string()})),
                {"--albedo and --mfp apply only to --profile burley"}, out);
    expectError(run(small({"render", "--profile", "Burley", "--out", out.string()})), {"did you mean burley?"}, out);
}

// --version names the program and the version of the library it loaded (the project's).
TEST_F(NewUser, VersionNamesTheProgramAndTheLibrary) {
    const ProcessResult r = run({"--version"});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_EQ(r.out, std::string("preskin ") + PRESKIN_PROJECT_VERSION + "\n") << r.out;
}

// An unknown debug view lists the ones there are; an --out that is a folder or has no
// extension says what to name instead of "unsupported image type ''".
TEST_F(NewUser, DebugViewsAndOutputNamesSayWhatIsExpected) {
    const fs::path out = dir_ / "out.png";
    expectError(
        run(small({"render", kTriangle.string(), "--debug", "albedo", "--out", out.string()})),
        {"--debug", "albedo", "none, curvature, normals, shadow, penumbra, lightcount, shambient, transmission"}, out);
    fs::create_directories(dir_ / "renders");
    expectError(run(small({"render", kTriangle.string(), "--out", (dir_ / "renders").string()})),
                {"--out " + (dir_ / "renders").string() + ": is a folder; name the image file in it (.png or .exr)"},
                dir_ / "renders" / "out.png");
    expectError(run(small({"render", kTriangle.string(), "--out", (dir_ / "renders" / "").string()})),
                {"is a folder; name the image file in it"}, dir_ / "renders" / "out.png");
    expectError(run(small({"render", kTriangle.string(), "--out", (dir_ / "image").string()})),
                {"--out " + (dir_ / "image").string() + ": no file extension; name a .png or .exr file"},
                dir_ / "image");
    // --help says that --width is each eye's with --stereo.
    const ProcessResult help = run({"render", "--help"});
    EXPECT_NE(help.out.find("--width and --height are each eye's"), std::string::npos) << help.out;
}

// The bundled spheres have UV poles but no normal map: loading them warns about nothing.
TEST_F(NewUser, BundledScenesLoadWithoutWarnings) {
    for (const char* scene : {"spheres/sphere_10mm.gltf", "spheres/sphere_40mm.gltf", "head/head.gltf"}) {
        const fs::path out = dir_ / "out.png";
        const ProcessResult r =
            run(small({"render", (kSource / "samples" / "assets" / scene).string(), "--out", out.string()}));
        EXPECT_EQ(r.exitCode, 0) << scene << ": " << r.err;
        EXPECT_EQ(r.err.find("warning"), std::string::npos) << scene << ": " << r.err;
    }
}

}  // namespace
}  // namespace preskin::test
