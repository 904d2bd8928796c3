// The fixture of the hostile-input tests (test_hostile_input.cpp, test_hostile_features.cpp): runs
// of the `preskin` tool under a time and an address-space limit, and the one-line refusal they
// must end with.
#pragma once

#include "support/Process.h"
#include "unit/GltfTestFiles.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace preskin::test {

namespace fs = std::filesystem;

inline const fs::path kHostile = fs::path(PRESKIN_SOURCE_DIR) / "tests" / "data" / "hostile";
inline const fs::path kTriangle = fs::path(PRESKIN_SOURCE_DIR) / "tests" / "data" / "gltf" / "triangle.gltf";
// Address space for runs that must fail before any GPU work: the tool maps about 450 MiB at
// start (shared libraries, thread stacks); the unfixed inputs took 1.7 to 7 GB.
constexpr uint64_t kRefusalMemory = 1ull << 30;
// Runs that render on lavapipe (its JIT and thread pools reserve address space).
constexpr uint64_t kRenderMemory = 3ull << 30;

class HostileInput : public ::testing::Test {
protected:
    void SetUp() override {
        if (!fs::exists(PRESKIN_CLI_PATH)) GTEST_SKIP() << "the preskin tool is not built: " << PRESKIN_CLI_PATH;
        dir_ = tmp_.path();
        out_ = dir_ / "out.png";
    }

    ProcessResult run(const std::vector<std::string>& args, uint64_t memory = kRefusalMemory, double limitS = 60.0) {
        return preskin::test::runWithMemoryLimit(PRESKIN_CLI_PATH, args, dir_, limitS, memory);
    }

    std::vector<std::string> render(const fs::path& scene, std::vector<std::string> extra = {}) const {
        std::vector<std::string> args{"render", scene.string(), "--out", out_.string(), "--width",
                                      "16",     "--height",     "16",    "--device",    preskin::test::testDevice()};
        args.insert(args.end(), extra.begin(), extra.end());
        return args;
    }

    // Exactly "preskin: error: <message>" on one line, exit 1, nothing written.
    void expectRefused(const ProcessResult& r, const std::string& message) const {
        EXPECT_FALSE(r.timedOut) << message;
        EXPECT_EQ(r.exitCode, 1) << r.err;
        EXPECT_EQ(r.err, "preskin: error: " + message + "\n");
        EXPECT_FALSE(fs::exists(out_)) << out_;
        for (const auto& entry : fs::directory_iterator(dir_))
            EXPECT_EQ(entry.path().filename().string().find(".partial"), std::string::npos) << entry.path();
    }

    preskin::test::TempDir tmp_;
    fs::path dir_;
    fs::path out_;
};

inline std::string hostile(const std::string& name) { return (kHostile / name).string(); }

}  // namespace preskin::test
