// A fixture for end-to-end tests of the `preskin` tool: a fresh temporary folder per test (named
// after the process and the test), `run` for `preskin <args>` with a time limit, and the check
// every bad input must pass: exit status 1, exactly one line "preskin: error: ..." holding every
// needle, and no output file or partial file left behind.
#pragma once

#include "support/Process.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

namespace preskin::test {

class CliTest : public ::testing::Test {
protected:
    void SetUp() override;
    void TearDown() override;

    ProcessResult run(const std::vector<std::string>& args, double limitS = 120.0) const {
        return runCli(args, dir_, limitS);
    }
    void expectError(const ProcessResult& r, const std::vector<std::string>& needles,
                     const std::filesystem::path& out) const;

    std::filesystem::path dir_;
};

}  // namespace preskin::test
