#include "support/Process.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <thread>

extern char** environ;

#if defined(__SANITIZE_ADDRESS__)
#define PRESKIN_TESTS_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define PRESKIN_TESTS_UNDER_ASAN 1
#endif
#endif
#ifndef PRESKIN_TESTS_UNDER_ASAN
#define PRESKIN_TESTS_UNDER_ASAN 0
#endif

namespace preskin::test {

namespace fs = std::filesystem;

bool underAddressSanitizer() { return PRESKIN_TESTS_UNDER_ASAN != 0; }

std::string readFile(const fs::path& p) {
    std::ifstream f(p);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

std::string testDevice() {
    const char* device = std::getenv("PRESKIN_TEST_DEVICE");
    return device && *device ? device : "llvmpipe";
}

Process::Process(const fs::path& program, const std::vector<std::string>& args,
                 const std::vector<std::string>& extraEnv, const fs::path& dir)
    : dir_(dir) {
    std::vector<std::string> argStore{program.string()};
    argStore.insert(argStore.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& a : argStore) argv.push_back(a.data());
    argv.push_back(nullptr);

    std::vector<std::string> envStore;
    for (char** e = environ; *e; ++e) {
        const std::string entry(*e);
        bool replaced = false;
        for (const std::string& extra : extraEnv)
            if (entry.substr(0, entry.find('=') + 1) == extra.substr(0, extra.find('=') + 1)) replaced = true;
        if (!replaced) envStore.push_back(entry);
    }
    envStore.insert(envStore.end(), extraEnv.begin(), extraEnv.end());
    std::vector<char*> envp;
    for (std::string& e : envStore) envp.push_back(e.data());
    envp.push_back(nullptr);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addchdir_np(&actions, dir.c_str());
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, outPath().c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, errPath().c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int spawned = posix_spawn(&pid_, program.c_str(), &actions, nullptr, argv.data(), envp.data());
    posix_spawn_file_actions_destroy(&actions);
    if (spawned != 0) {
        pid_ = -1;
        startError_ = std::string("cannot start ") + program.string() + ": " + std::strerror(spawned);
    }
}

Process::~Process() {
    if (pid_ > 0) wait(0.0);
}

bool Process::running() const {
    if (pid_ <= 0) return false;
    siginfo_t info{};
    return ::waitid(P_PID, id_t(pid_), &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid == 0;
}

bool Process::waitForOutput(const std::string& text, double limitS) const {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(limitS);
    while (std::chrono::steady_clock::now() < deadline) {
        if (output().find(text) != std::string::npos || errors().find(text) != std::string::npos) return true;
        if (!running()) return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return false;
}

ProcessResult Process::wait(double limitS) {
    ProcessResult result;
    if (pid_ <= 0) {
        result.err = startError_;
        return result;
    }
    // The time limits catch hangs; the sanitizer build runs every process several times slower.
    const double limit = underAddressSanitizer() ? 5.0 * limitS : limitS;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(limit);
    int status = 0;
    while (true) {
        const pid_t done = ::waitpid(pid_, &status, WNOHANG);
        if (done == pid_) break;
        if (std::chrono::steady_clock::now() > deadline) {
            ::kill(pid_, SIGKILL);
            ::waitpid(pid_, &status, 0);
            result.timedOut = true;
            break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    pid_ = -1;
    result.exitCode = !result.timedOut && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    result.out = readFile(outPath());
    result.err = readFile(errPath());
    return result;
}

ProcessResult runProcess(const fs::path& program, const std::vector<std::string>& args,
                         const std::vector<std::string>& extraEnv, const fs::path& dir, double limitS) {
    Process process(program, args, extraEnv, dir);
    return process.wait(limitS);
}

ProcessResult runCli(const std::vector<std::string>& args, const fs::path& dir, double limitS) {
    return runProcess(PRESKIN_CLI_PATH, args, {}, dir, limitS);
}

ProcessResult runWithMemoryLimit(const fs::path& program, const std::vector<std::string>& args, const fs::path& dir,
                                 double limitS, uint64_t memoryBytes) {
#if PRESKIN_TESTS_UNDER_ASAN
    // AddressSanitizer reserves terabytes of address space for its shadow, so an address-space
    // limit cannot apply; its own resident-memory limit ends the program with a report instead.
    const char* options = std::getenv("ASAN_OPTIONS");
    const std::string limit = "hard_rss_limit_mb=" + std::to_string(memoryBytes >> 20);
    return runProcess(program, args,
                      {"ASAN_OPTIONS=" + (options && *options ? std::string(options) + ":" : "") + limit}, dir, limitS);
#else
    std::vector<std::string> shellArgs{
        "-c", "ulimit -v " + std::to_string(memoryBytes / 1024) + " && exec \"$0\" \"$@\"", program.string()};
    shellArgs.insert(shellArgs.end(), args.begin(), args.end());
    return runProcess("/bin/sh", shellArgs, {}, dir, limitS);
#endif
}

}  // namespace preskin::test

namespace preskin::test {

ProcessResult installBuild(const std::filesystem::path& prefix, const std::string& component, double limitS) {
    std::vector<std::string> args = {(std::filesystem::path(PRESKIN_BINARY_DIR) / ".install.lock").string(), PRESKIN_CMAKE_COMMAND,
                                     "--install", PRESKIN_BINARY_DIR, "--prefix", prefix.string()};
    if (!component.empty()) {
        args.push_back("--component");
        args.push_back(component);
    }
    return runProcess("/usr/bin/flock", args, {}, PRESKIN_BINARY_DIR, limitS);
}

}  // namespace preskin::test
