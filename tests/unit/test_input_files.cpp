// The shared input layer (engine/src/io, env/EnvironmentHeader): the bounded reader refuses what
// is not a regular file within its size limit, the JSON parser refuses depth and size beyond its
// limits (and survives nesting far past them), the folder confinement follows links only while
// they stay inside, the number rule, and the environment header's size.
#include "unit/GltfTestFiles.h"

#include "env/EnvironmentHeader.h"
#include "io/FolderConfinement.h"
#include "io/InputFile.h"
#include "io/JsonDocument.h"
#include "io/MessageText.h"
#include "io/NumberRule.h"

#include <preskin/Environment.h>
#include <preskin/Error.h>

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <limits>

namespace preskin::test {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

template <typename F>
std::string errorOf(F&& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    } catch (const std::exception& e) {
        return std::string("unexpected exception: ") + e.what();
    }
    return "no error";
}

TEST(InputFile, ReadsRegularFilesWithinTheLimitOnly) {
    TempDir dir;
    test::writeText(dir / "a.txt", std::string(100, 'x'));
    EXPECT_EQ(io::readInputFile(dir / "a.txt", "a.txt", 100).size(), 100u);
    EXPECT_EQ(io::readInputFileStart(dir / "a.txt", "a.txt", 100, 10).size(), 10u);
    EXPECT_EQ(io::checkInputFile(dir / "a.txt", "a.txt", 100), 100u);
    EXPECT_EQ(errorOf([&] { io::readInputFile(dir / "a.txt", "a.txt", 99); }),
              "a.txt: file: 100 bytes exceeds the limit of 99 bytes");
    EXPECT_EQ(errorOf([&] { io::readInputFile(dir / "none", "none", 99); }), "none: file: not found");
    EXPECT_EQ(errorOf([&] { io::readInputFile(dir.path(), "dir", 99); }), "dir: file: is a folder, not a file");
    EXPECT_EQ(errorOf([&] { io::readInputFile("/dev/zero", "zero", 99); }),
              "zero: file: is a device, not a regular file");
    ASSERT_EQ(::mkfifo((dir / "fifo").c_str(), 0600), 0);
    EXPECT_EQ(errorOf([&] { io::readInputFile(dir / "fifo", "fifo", 99); }),
              "fifo: file: is a FIFO (named pipe), not a regular file");
    EXPECT_EQ(errorOf([&] { io::checkInputFile(dir / "fifo", "fifo", 99); }),
              "fifo: file: is a FIFO (named pipe), not a regular file");
    fs::create_symlink("/dev/zero", dir / "link");
    EXPECT_EQ(errorOf([&] { io::readInputFile(dir / "link", "link", 99); }),
              "link: file: is a device, not a regular file");
}

TEST(JsonDocument, RefusesDepthAndSizeBeyondTheLimits) {
    auto nested = [](size_t depth) { return std::string(depth, '[') + std::string(depth, ']'); };
    EXPECT_NO_THROW(io::parseJson(nested(64), "j"));
    EXPECT_EQ(errorOf([&] { io::parseJson(nested(65), "j"); }), "j: JSON: nested deeper than the limit of 64 levels");
    // Far past the limit, as deep as the input that overflowed the stack of a recursive dump.
    EXPECT_EQ(errorOf([&] { io::parseJson(nested(1000000), "j"); }),
              "j: JSON: nested deeper than the limit of 64 levels");
    io::JsonLimits small;
    small.maxValues = 4;
    EXPECT_NO_THROW(io::parseJson(std::string("[1, 2, 3]"), "j", small));
    EXPECT_EQ(errorOf([&] { io::parseJson(std::string("[1, 2, 3, 4]"), "j", small); }),
              "j: JSON: more than the limit of 4 values");
    EXPECT_EQ(
        errorOf([&] { io::parseJson(std::string("{\"a\": }"), "j"); }),
        "j: JSON: parse error at line 1, column 7: syntax error while parsing value - unexpected '}'; expected '[', "
        "'{', or a literal");
    const nlohmann::json parsed = io::parseJson(std::string("{\"a\": [1, {\"b\": null}]}"), "j");
    EXPECT_EQ(parsed["a"][1]["b"], nullptr);
}

TEST(MessageText, IsOneBoundedLine) {
    EXPECT_EQ(io::messageText("a\nb\r\nc\x01"), "a; b; c");
    EXPECT_EQ(io::messageText(std::string(500, 'x'), 10), "xxxxxxxxxx...");
    EXPECT_EQ(io::jsonExcerpt(nlohmann::json::parse("[\"\\n\", 1]")), "[\"\\n\",1]");
}

TEST(NumberRule, FiniteAndAtMostAMillion) {
    EXPECT_TRUE(io::acceptedNumber(0.0));
    EXPECT_TRUE(io::acceptedNumber(-1e6));
    EXPECT_TRUE(io::acceptedNumber(1e6));
    EXPECT_FALSE(io::acceptedNumber(1.000001e6));
    EXPECT_FALSE(io::acceptedNumber(std::numeric_limits<double>::quiet_NaN()));
    EXPECT_FALSE(io::acceptedNumber(-std::numeric_limits<double>::infinity()));
    EXPECT_EQ(io::numberProblem(1e300), "1e+300 exceeds the limit of 1e+06 in magnitude");
    EXPECT_EQ(io::numberProblem(std::numeric_limits<double>::quiet_NaN()), "nan is not a finite number");
    EXPECT_EQ(io::numberProblem(0.5), std::nullopt);
}

TEST(FolderConfinement, FollowsLinksOnlyWhileTheyStayInside) {
    TempDir dir;
    const fs::path scene = fs::canonical(dir.path()) / "scene";
    fs::create_directories(scene / "sub");
    fs::create_directories(dir / "outside");
    test::writeText(scene / "real.bin", "x");
    test::writeText(dir / "outside" / "secret.bin", "x");
    fs::create_symlink("real.bin", scene / "relative.bin");
    fs::create_symlink(scene / "real.bin", scene / "absolute_inside.bin");
    fs::create_symlink("../real.bin", scene / "sub" / "up.bin");
    fs::create_symlink("../outside/secret.bin", scene / "out.bin");
    fs::create_symlink("/", scene / "root");
    fs::create_symlink("../out.bin", scene / "sub" / "via.bin");
    fs::create_symlink("loop_b", scene / "loop_a");
    fs::create_symlink("loop_a", scene / "loop_b");
    fs::create_symlink("sub", scene / "subdir");

    struct Case {
        const char* relative;
        bool inside;
        const char* resolved;  // below `scene`, when inside
    };
    for (const Case& c :
         {Case{"real.bin", true, "real.bin"}, Case{"relative.bin", true, "real.bin"},
          Case{"absolute_inside.bin", true, "real.bin"}, Case{"sub/up.bin", true, "real.bin"},
          Case{"subdir/up.bin", true, "real.bin"}, Case{"missing.bin", true, "missing.bin"}, Case{"out.bin", false, ""},
          Case{"sub/via.bin", false, ""}, Case{"root/etc/hostname", false, ""}, Case{"loop_a", false, ""}}) {
        SCOPED_TRACE(c.relative);
        const io::ConfinedPath p = io::resolveInsideFolder(scene, c.relative);
        EXPECT_EQ(p.inside, c.inside);
        if (c.inside) {
            EXPECT_EQ(p.path, scene / c.resolved);
        }
    }
}

TEST(EnvironmentHeader, SizeAndFormatComeFromTheHeader) {
    const std::string hdr = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 512 +X 1024\n";
    const auto h = env::readEnvironmentHeader(std::span(reinterpret_cast<const uint8_t*>(hdr.data()), hdr.size()));
    EXPECT_EQ(h.format, env::EnvironmentFormat::RadianceHdr);
    EXPECT_EQ(h.width, 1024);
    EXPECT_EQ(h.height, 512);
    TempDir dir;
    const std::vector<uint8_t> exr = [&] {
        auto out = OIIO::ImageOutput::create("openexr");
        OIIO::ImageSpec spec(64, 32, 3, OIIO::TypeDesc::HALF);
        spec.attribute("preskin:padding", std::string(300, 'p'));  // an attribute before dataWindow or after
        std::vector<uint16_t> pixels(64 * 32 * 3, 0);
        out->open((dir / "e.exr").string(), spec);
        out->write_image(OIIO::TypeDesc::HALF, pixels.data());
        out->close();
        return test::readBytes(dir / "e.exr");
    }();
    const auto e = env::readEnvironmentHeader(exr);
    EXPECT_EQ(e.format, env::EnvironmentFormat::OpenExr);
    EXPECT_EQ(e.width, 64);
    EXPECT_EQ(e.height, 32);
    const std::vector<uint8_t> png = test::encodeImage(dir.path(), "p.png", 2, 2, 3, std::vector<uint8_t>(12, 0));
    try {
        env::readEnvironmentHeader(png);
        FAIL();
    } catch (const std::runtime_error& error) {
        EXPECT_STREQ(error.what(), "format: not a Radiance HDR or OpenEXR file");
    }
    const std::string flipped = "#?RADIANCE\n\n+Y 512 +X 1024\n";
    try {
        env::readEnvironmentHeader(std::span(reinterpret_cast<const uint8_t*>(flipped.data()), flipped.size()));
        FAIL();
    } catch (const std::runtime_error& error) {
        EXPECT_STREQ(error.what(), "resolution: orientation +Y 512 +X 1024 is not supported (only -Y +X)");
    }
}

// tests/data/environments/sky.hdr and sky.exr (make_environment_files.py) hold the same sky,
// 8-bit RGBE and half float: both decode to the SH of that sky computed here from its formula.
TEST(EnvironmentFiles, HdrAndExrDecodeToTheirSky) {
    EquirectImage sky;
    sky.width = 16;
    sky.height = 8;
    for (uint32_t y = 0; y < sky.height; ++y)
        for (uint32_t x = 0; x < sky.width; ++x) {
            const double up = 1.0 - (y + 0.5) / sky.height;
            const double bright = std::max(up - 0.5, 0.0) * 2.0;
            sky.rgb.insert(sky.rgb.end(),
                           {float(0.2 + 0.8 * bright), float(0.25 + 0.9 * bright),
                            float(0.3 + 1.2 * bright + 0.1 * std::sin(double(x)))});
        }
    const ShRgb expected = projectEquirect(sky);
    const fs::path dir = fs::path(PRESKIN_SOURCE_DIR) / "tests" / "data" / "environments";
    for (const char* name : {"sky.hdr", "sky.exr"}) {
        SCOPED_TRACE(name);
        const ShRgb got = Environment::load(dir / name).radianceSh();
        for (int i = 0; i < 9; ++i)
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(got.c[i][c], expected.c[i][c], 0.01f * expected.c[0][c]) << i;
    }
}

}  // namespace
}  // namespace preskin::test
