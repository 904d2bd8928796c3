// Golden image of the bundled head scene (samples/assets/head/head.gltf) as the product draws it:
// `preskin render --width 256 --height 256` (default view, scene lights and environment, the
// committed LUTs, tone-mapped sRGB PNG, validation layers on) on the test device, against
// tests/golden/<driver>/head_256.png, where <driver> comes from the device name (the text before
// any "(", lower case, other characters as "-": "llvmpipe (LLVM 15.0.6, 256 bits)" -> llvmpipe).
// Pass: every channel within 5/255 on at least 99.9% of the pixels.
// A driver without a golden skips, saying how to make one: scripts/update-goldens.sh, which runs
// this test with PRESKIN_UPDATE_GOLDENS=1 to write the golden (and device.txt, the full device
// name) instead of comparing.
#include "support/GpuTest.h"
#include "support/ImageCompare.h"
#include "support/Process.h"

#include <preskin/Renderer.h>

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace preskin::test {
namespace {

std::string driverFolderName(const std::string& deviceName) {
    std::string name = deviceName.substr(0, deviceName.find('('));
    std::string folder;
    for (char c : name) {
        const auto u = static_cast<unsigned char>(c);
        if (std::isalnum(u))
            folder += static_cast<char>(std::tolower(u));
        else if (!folder.empty() && folder.back() != '-')
            folder += '-';
    }
    while (!folder.empty() && folder.back() == '-') folder.pop_back();
    return folder.empty() ? "unknown" : folder;
}

class SkinGolden : public GpuTest {};

TEST_F(SkinGolden, HeadSceneMatchesDriverGolden) {
    const std::string device = context().deviceName();
    const std::string driver = driverFolderName(device);
    const std::filesystem::path goldenDir = std::filesystem::path(PRESKIN_SOURCE_DIR) / "tests" / "golden" / driver;
    const std::filesystem::path golden = goldenDir / "head_256.png";
    const char* updateEnv = std::getenv("PRESKIN_UPDATE_GOLDENS");
    const bool update = updateEnv && std::string(updateEnv) == "1";
    if (!update && !std::filesystem::exists(golden))
        GTEST_SKIP() << "no golden image for driver '" << driver << "' (" << golden.string()
                     << "); create it with scripts/update-goldens.sh '" << device << "'";

    // Render with the CLI, as a user would.
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("preskin_test_golden_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::filesystem::path rendered = dir / "head_256.png";
    const ProcessResult run = runCli(
        {"render", "--width", "256", "--height", "256", "--validation", "--device", device, "--out", rendered.string()},
        dir, 120.0);
    ASSERT_EQ(run.exitCode, 0) << run.out << run.err;
    std::string error;
    const RenderedImage image = readPng(rendered, error);
    std::filesystem::remove_all(dir);
    ASSERT_EQ(image.width, 256u) << error;
    ASSERT_EQ(image.height, 256u);

    if (update) {
        std::filesystem::create_directories(goldenDir);
        writeImage(golden, image);
        std::ofstream(goldenDir / "device.txt") << device << "\n";
        std::printf("[ golden   ] wrote %s (device %s)\n", golden.string().c_str(), device.c_str());
        return;
    }

    const RenderedImage expected = readPng(golden, error);
    ASSERT_EQ(expected.width, image.width) << golden.string() << ": " << error;
    ASSERT_EQ(expected.height, image.height) << golden.string();
    size_t within = 0;
    int worst = 0;
    RenderedImage difference = image;  // |rendered - golden| x 16, for a person to look at
    const size_t pixels = size_t(image.width) * image.height;
    for (size_t p = 0; p < pixels; ++p) {
        int diff = 0;
        for (size_t c = 0; c < 3; ++c) {
            const int d = std::abs(int(image.rgba8[p * 4 + c]) - int(expected.rgba8[p * 4 + c]));
            diff = std::max(diff, d);
            difference.rgba8[p * 4 + c] = static_cast<uint8_t>(std::min(255, d * 16));
        }
        worst = std::max(worst, diff);
        if (diff <= 5) ++within;
    }
    std::printf("[ golden   ] %s: %zu of %zu pixels within 5/255 (worst %d/255)\n", driver.c_str(), within, pixels,
                worst);
    const bool pass = double(within) >= 0.999 * double(pixels);
    if (!pass) {
        dumpImage("golden_head_256_rendered", image);
        dumpImage("golden_head_256_difference_x16", difference);
    }
    EXPECT_TRUE(pass) << within << " of " << pixels << " pixels within 5/255 of " << golden.string() << " (worst "
                      << worst << "/255). If the change is intended, run scripts/update-goldens.sh and commit the "
                      << "new golden.";
}

}  // namespace
}  // namespace preskin::test
