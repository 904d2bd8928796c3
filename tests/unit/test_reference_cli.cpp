// `preskin reference` end to end on the bundled 10 mm skin sphere at a small size with a coarse
// (fast) reference: it writes a linear EXR; bad input ends with one error line and leaves nothing
// behind.
#include "support/CliTest.h"

#include <preskin/DiffusionReference.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using preskin::test::ProcessResult;

class ReferenceCli : public preskin::test::CliTest {
protected:

    // The sphere at 20 x 20 pixels with a coarse reference (accuracy is not what these test).
    std::vector<std::string> common() const {
        return {sphere_, "--width", "20", "--height", "20", "--env-intensity", "0", "--leaf-ratio", "1",
                "--finest-leaf-ratio", "4", "--moment-tolerance", "1e-5"};
    }
    std::string sphere_ = (fs::path(PRESKIN_SOURCE_DIR) / "samples" / "assets" / "spheres" / "sphere_10mm.gltf").string();
};

TEST_F(ReferenceCli, ReferenceWritesALinearExr) {
    const fs::path out = dir_ / "ref.exr";
    std::vector<std::string> args{"reference"};
    for (const std::string& a : common()) args.push_back(a);
    args.insert(args.end(), {"--out", out.string(), "--threads", "2"});
    const ProcessResult r = run(args, 300.0);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(fs::exists(out));
    EXPECT_NE(r.out.find("wrote"), std::string::npos) << r.out;
    EXPECT_NE(r.err.find("100%"), std::string::npos) << "progress bar on stderr: " << r.err;
}

TEST_F(ReferenceCli, BadInputIsRefusedAndNothingIsWritten) {
    {
        const fs::path out = dir_ / "ref.png";
        expectError(run({"reference", sphere_, "--out", out.string()}), {".exr"}, out);
    }
    {
        const fs::path out = dir_ / "ref.exr";
        expectError(run({"reference", (dir_ / "missing.gltf").string(), "--out", out.string()}), {"missing.gltf"}, out);
    }
}

}  // namespace
