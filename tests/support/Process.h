// Child processes for end-to-end tests (the preskin tool, the viewer, Xvfb): started with an
// argument vector (no shell), extra environment entries, stdout and stderr into files of a
// folder, and a time limit after which the process is killed.
#pragma once

#include <sys/types.h>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace preskin::test {

// True in the sanitizer build (AddressSanitizer): timings mean nothing there.
bool underAddressSanitizer();

struct ProcessResult {
    int exitCode = -1;  // -1: killed by a signal or by the time limit
    bool timedOut = false;
    std::string out;
    std::string err;
};

std::string readFile(const std::filesystem::path& path);

// `cmake --install` of the build into `prefix` (one `component`, or every one when empty), one
// at a time across the test processes (a lock file in the build folder): installs write the
// build's install manifests.
ProcessResult installBuild(const std::filesystem::path& prefix, const std::string& component, double limitS);
// The Vulkan device the tests run on: $PRESKIN_TEST_DEVICE, else "llvmpipe".
std::string testDevice();

class Process {
public:
    Process(const std::filesystem::path& program, const std::vector<std::string>& args,
            const std::vector<std::string>& extraEnv, const std::filesystem::path& dir);
    ~Process();
    Process(const Process&) = delete;
    Process& operator=(const Process&) = delete;

    bool running() const;
    std::string output() const { return readFile(outPath()); }
    std::string errors() const { return readFile(errPath()); }
    // Waits until stdout or stderr contains `text`; false when the time is up or the process ended.
    bool waitForOutput(const std::string& text, double limitS) const;
    ProcessResult wait(double limitS);

private:
    std::filesystem::path outPath() const { return dir_ / "stdout.txt"; }
    std::filesystem::path errPath() const { return dir_ / "stderr.txt"; }

    std::filesystem::path dir_;
    pid_t pid_ = -1;
    std::string startError_;
};

ProcessResult runProcess(const std::filesystem::path& program, const std::vector<std::string>& args,
                         const std::vector<std::string>& extraEnv, const std::filesystem::path& dir, double limitS);
// `preskin <args>` (the built tool), output files in `dir`.
ProcessResult runCli(const std::vector<std::string>& args, const std::filesystem::path& dir, double limitS = 300.0);
// `program <args>` with its address space limited to `memoryBytes` (ulimit -v in /bin/sh, which
// then execs the program): an allocation beyond it fails inside the program.
ProcessResult runWithMemoryLimit(const std::filesystem::path& program, const std::vector<std::string>& args,
                                 const std::filesystem::path& dir, double limitS, uint64_t memoryBytes);

}  // namespace preskin::test
