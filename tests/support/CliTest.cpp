#include "support/CliTest.h"

#include <unistd.h>

#include <sstream>

namespace preskin::test {

namespace fs = std::filesystem;

void CliTest::SetUp() {
    if (!fs::exists(PRESKIN_CLI_PATH)) GTEST_SKIP() << "the preskin tool is not built: " << PRESKIN_CLI_PATH;
    std::ostringstream name;
    name << "preskin_cli_" << ::getpid() << "_" << ::testing::UnitTest::GetInstance()->current_test_info()->name();
    dir_ = fs::temp_directory_path() / name.str();
    fs::remove_all(dir_);
    fs::create_directories(dir_);
}

void CliTest::TearDown() {
    std::error_code ec;
    if (!dir_.empty()) fs::remove_all(dir_, ec);
}

void CliTest::expectError(const ProcessResult& r, const std::vector<std::string>& needles, const fs::path& out) const {
    EXPECT_EQ(r.exitCode, 1) << r.err;
    EXPECT_EQ(r.err.rfind("preskin: error: ", 0), 0u) << r.err;
    size_t errorLines = 0;
    std::istringstream lines(r.err);
    for (std::string line; std::getline(lines, line);)
        if (line.rfind("preskin: error: ", 0) == 0) ++errorLines;
    EXPECT_EQ(errorLines, 1u) << r.err;
    for (const std::string& n : needles) EXPECT_NE(r.err.find(n), std::string::npos) << "'" << n << "' in: " << r.err;
    EXPECT_FALSE(fs::exists(out)) << out;
    if (!fs::is_directory(out.parent_path())) return;
    for (const auto& entry : fs::directory_iterator(out.parent_path()))
        EXPECT_EQ(entry.path().filename().string().find(".partial"), std::string::npos) << entry.path();
}

}  // namespace preskin::test
