// Shader hot reload: watches the source tree's shaders/ folder (entry points *.vert, *.frag,
// *.comp and every include under it, e.g. preskin/*.glsl and shared/*.h) by polling file times,
// and when something changed compiles every entry point to SPIR-V with the glslang library on a
// worker thread (GLSL 460 for Vulkan 1.3 / SPIR-V 1.6, as the build's glslangValidator does;
// "preskin/..." and "shared/..." includes resolve against the folder). The result is either the
// SPIR-V of every entry point by file name (for Renderer::setShaderOverrides) or the compiler log.
// Limits: polling (every 0.5 s), not inotify; a change is compiled once the files have been
// quiet for 0.2 s, so an editor's save-in-several-writes is seen as one change.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <future>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace preskin::viewer {

struct ShaderBuild {
    bool ok = false;
    std::map<std::string, std::vector<uint32_t>> spirvByFile;
    std::string log;  // compiler messages (errors and warnings), one line per message
    std::vector<std::string> changedFiles;
    double compileMs = 0.0;
};

class ShaderReloader {
public:
    // `shaderDir` is the source tree's shaders/ folder; when it does not exist, reloading is off.
    explicit ShaderReloader(std::filesystem::path shaderDir);
    ~ShaderReloader();
    ShaderReloader(const ShaderReloader&) = delete;
    ShaderReloader& operator=(const ShaderReloader&) = delete;

    bool enabled() const { return enabled_; }
    // Whether file changes start a build by themselves (requestBuild works either way).
    void setWatching(bool watching) { watching_ = watching; }
    bool watching() const { return watching_; }
    const std::filesystem::path& directory() const { return dir_; }
    bool compiling() const { return job_.valid(); }

    // Call once per frame: watches the files and starts a compile when they changed.
    void poll();
    // Compiles now, whether or not anything changed.
    void requestBuild();
    // A finished compile, once.
    std::optional<ShaderBuild> takeResult();

private:
    using Clock = std::chrono::steady_clock;
    using Snapshot = std::map<std::filesystem::path, std::pair<std::filesystem::file_time_type, uintmax_t>>;
    Snapshot scan() const;
    void start(std::vector<std::string> changed);

    std::filesystem::path dir_;
    bool enabled_ = false;
    bool watching_ = true;
    Snapshot known_;
    Clock::time_point nextPoll_{};
    std::optional<Clock::time_point> changedAt_;
    std::vector<std::string> pendingChanges_;
    std::future<ShaderBuild> job_;
};

// Compiles one GLSL entry point (stage from the extension). Returns empty SPIR-V and appends to
// `log` on failure.
std::vector<uint32_t> compileGlsl(const std::filesystem::path& file, const std::filesystem::path& includeDir,
                                  std::string& log);

}  // namespace preskin::viewer
