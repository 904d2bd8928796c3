// samples/host built against an installed preskin core, as an engine builds against it: `cmake
// --install --component Unspecified` (the core alone: no image component, no tools) into a fresh
// prefix, samples/host configured with CMAKE_PREFIX_PATH (its own
// find_package(preskin CONFIG), glslang run on its own shader with preskin_SHADER_DIR) and built,
// its pictures of the head compared with `preskin render` (the build's) of the same view, the
// environment's specular from its SH (the host sample binds no prefiltered environment):
//  - its own passes without shadows, and with its shadow pass at the low tier (penumbra
//    scattering and transmission compiled out): within the golden tolerance, every channel
//    within 5/255 on at least 99.9% of the pixels;
//  - its own shadow pass and every technique: within 5/255 on 99.5% of the pixels (the renderer
//    adds the wide shadow map, which carries red a little further into cast shadows), while the
//    shadow pass itself changes at least 2% of them;
//  - preskin's renderer recorded into the host's command buffer on the host's device
//    (--renderer: Context::wrap, Renderer::record): `preskin render`'s image, within 1/255.
// The validation layers are on in every program.
#include "support/ElfClosure.h"
#include "support/ImageCompare.h"
#include "support/Process.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace preskin::test {
namespace {

namespace fs = std::filesystem;

TEST(HostSample, BuiltAgainstTheInstallRendersLikePreskinRender) {
    const fs::path work = fs::path(PRESKIN_BINARY_DIR) / "host-sample-test";
    const fs::path prefix = work / "prefix";
    const fs::path build = work / "build";  // kept between runs: only what changed is rebuilt
    std::error_code ec;
    fs::remove_all(prefix, ec);
    fs::create_directories(build);
    auto run = [&](const fs::path& program, const std::vector<std::string>& args, double limitS,
                   const std::vector<std::string>& env = {}) {
        const ProcessResult r = runProcess(program, args, env, work, limitS);
        EXPECT_EQ(r.exitCode, 0) << program.string() << " " << (args.empty() ? "" : args[0]) << "\n" << r.out << r.err;
        return r;
    };
    {
        const ProcessResult installed = installBuild(prefix, "Unspecified", 120.0);
        ASSERT_EQ(installed.exitCode, 0) << installed.out << installed.err;
    }
    EXPECT_FALSE(fs::exists(prefix / "include" / "preskin" / "imageio"));
    run(PRESKIN_CMAKE_COMMAND,
        {"-S", PRESKIN_SOURCE_DIR "/samples/host", "-B", build.string(), "-G", PRESKIN_CMAKE_GENERATOR,
         "-DCMAKE_BUILD_TYPE=Release", "-DCMAKE_PREFIX_PATH=" + prefix.string(),
         "-DCMAKE_CXX_COMPILER_LAUNCHER=" PRESKIN_CXX_LAUNCHER},
        120.0);
    run(PRESKIN_CMAKE_COMMAND, {"--build", build.string()}, 300.0);
    ASSERT_FALSE(HasFailure());

    // The host loads the core and nothing of OpenImageIO.
    const ElfClosure closure = elfClosure(build / "preskin-host");
    EXPECT_EQ(closure.libraries.count("libpreskin.so.0.1"), 1u);
    for (const auto& [name, library] : closure.libraries)
        EXPECT_EQ(name.find("OpenImageIO"), std::string::npos) << name << " needed by " << library.neededBy;

    const ProcessResult help = run(build / "preskin-host", {"--help"}, 30.0);
    EXPECT_EQ(help.out.rfind("usage: preskin-host", 0), 0u) << help.out;

    const std::string size = "96";
    auto host = [&](const std::string& out, std::vector<std::string> options) {
        options.insert(options.end(), {"--device", testDevice(), "--width", size, "--height", size, "--out", out});
        const ProcessResult r =
            run(build / "preskin-host", options, 120.0, {"VK_INSTANCE_LAYERS=VK_LAYER_KHRONOS_validation"});
        EXPECT_EQ((r.out + r.err).find("Validation"), std::string::npos) << r.out << r.err;
    };
    auto render = [&](const std::string& out, std::vector<std::string> options) {
        options.insert(options.begin(), {"render", "--device", testDevice(), "--validation"});
        options.insert(options.end(), {"--width", size, "--height", size, "--out", out});
        run(PRESKIN_CLI_PATH, options, 120.0);
    };
    host("host.png", {"--no-shadows"});
    render("preskin.png", {"--no-shadows", "--no-specular-ibl"});
    host("host-shadows-low.png", {"--skin-quality", "low"});
    render("preskin-shadows-low.png", {"--skin-quality", "low", "--no-specular-ibl"});
    host("host-shadows.png", {});
    render("preskin-shadows.png", {"--no-specular-ibl"});
    host("host-renderer.png", {"--renderer"});
    render("preskin-default.png", {});
    ASSERT_FALSE(HasFailure());

    auto read = [&](const std::string& name) {
        std::string error;
        const RenderedImage image = readPng(work / name, error);
        EXPECT_TRUE(error.empty()) << error;
        return image;
    };
    // The share of pixels with a channel more than `tolerance` apart; the largest difference.
    auto compare = [&](const std::string& a, const std::string& b, int tolerance, int& largest) {
        const RenderedImage x = read(a), y = read(b);
        EXPECT_EQ(x.width, y.width);
        EXPECT_EQ(x.height, y.height);
        if (x.rgba8.size() != y.rgba8.size()) return 1.0;
        largest = 0;
        const double share = double(pixelsDifferingBy(x, y, tolerance, largest)) / (double(x.width) * double(x.height));
        std::printf("%s vs %s: %.2f%% of pixels differ by more than %d/255, largest difference %d/255\n", a.c_str(),
                    b.c_str(), 100.0 * share, tolerance, largest);
        return share;
    };
    int largest = 0;
    EXPECT_LE(compare("host.png", "preskin.png", 5, largest), 0.001);
    EXPECT_LE(compare("host-shadows-low.png", "preskin-shadows-low.png", 5, largest), 0.001);
    EXPECT_LE(compare("host-shadows.png", "preskin-shadows.png", 5, largest), 0.005);
    EXPECT_GE(compare("host-shadows.png", "host.png", 5, largest), 0.02);
    EXPECT_LE(compare("host-renderer.png", "preskin-default.png", 1, largest), 0.0);
    // The head is in the picture: not just two empty backgrounds that agree.
    const RenderedImage reference = read("preskin.png");
    const size_t pixels = size_t(reference.width) * reference.height;
    size_t head = 0;
    for (size_t p = 0; p < pixels; ++p)
        head += std::abs(int(reference.rgba8[4 * p]) - int(reference.rgba8[0])) > 10 ? 1 : 0;
    EXPECT_GT(head, pixels / 5);
}

// A program built with `pkg-config --cflags --libs preskin` against an install that was moved
// after `cmake --install --prefix`: preskin.pc names its paths from its own folder, so the
// headers, the library and the shader folder are found where the tree now lies.
TEST(HostSample, PkgConfigFindsAMovedInstall) {
    const fs::path work = fs::path(PRESKIN_BINARY_DIR) / "pkg-config-test";
    std::error_code ec;
    fs::remove_all(work, ec);
    fs::create_directories(work);
    const ProcessResult install = installBuild(work / "installed", "", 120.0);
    ASSERT_EQ(install.exitCode, 0) << install.out << install.err;
    const fs::path prefix = work / "moved";
    fs::rename(work / "installed", prefix);
    std::FILE* source = std::fopen((work / "main.cpp").c_str(), "w");
    ASSERT_NE(source, nullptr);
    std::fputs(
        "#include <preskin/DiffusionProfile.h>\n#include <preskin/LutSet.h>\n#include <cstdio>\n"
        "int main() { std::printf(\"%.3f\\n\", preskin::DiffusionProfile::deonLuebke().reachMm(1e-4)); }\n",
        source);
    std::fclose(source);
    const fs::path pcDir = fs::exists(prefix / "lib" / "pkgconfig") ? prefix / "lib" / "pkgconfig" : fs::path();
    ASSERT_FALSE(pcDir.empty()) << "no lib/pkgconfig under " << prefix;
    const std::string env = "PKG_CONFIG_PATH=" + pcDir.string();
    const ProcessResult build = runProcess(
        "/bin/sh", {"-c", "c++ -std=c++20 main.cpp -o main $(pkg-config --cflags --libs preskin)"}, {env}, work, 300.0);
    ASSERT_EQ(build.exitCode, 0) << build.out << build.err;
    const ProcessResult shaders =
        runProcess("/bin/sh", {"-c", "pkg-config --variable=shaderdir preskin"}, {env}, work, 30.0);
    ASSERT_EQ(shaders.exitCode, 0) << shaders.err;
    std::string shaderDir = shaders.out.substr(0, shaders.out.find('\n'));
    EXPECT_TRUE(fs::exists(fs::path(shaderDir) / "preskin" / "skin.glsl")) << shaderDir;
    EXPECT_EQ(fs::weakly_canonical(shaderDir).string().rfind(fs::weakly_canonical(prefix).string(), 0), 0u)
        << shaderDir;
    // No LD_LIBRARY_PATH: the run path pkg-config's flags give finds the library where it is.
    const ProcessResult ran = runProcess(work / "main", {}, {"LD_LIBRARY_PATH="}, work, 30.0);
    ASSERT_EQ(ran.exitCode, 0) << ran.err;
    EXPECT_EQ(ran.out, "9.934\n");
}

}  // namespace
}  // namespace preskin::test
