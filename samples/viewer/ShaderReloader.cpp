// File watching and run-time GLSL compilation with glslang (see ShaderReloader.h).
#include "ShaderReloader.h"

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>

#include <fmt/core.h>

#include <algorithm>
#include <exception>
#include <fstream>
#include <memory>
#include <sstream>
#include <system_error>

namespace preskin::viewer {

namespace {

constexpr auto kPollInterval = std::chrono::milliseconds(500);
constexpr auto kQuietTime = std::chrono::milliseconds(200);

bool isEntryPoint(const std::filesystem::path& p) {
    const std::string ext = p.extension().string();
    return ext == ".vert" || ext == ".frag" || ext == ".comp";
}

bool isWatched(const std::filesystem::path& p) {
    const std::string ext = p.extension().string();
    return isEntryPoint(p) || ext == ".glsl" || ext == ".h";
}

std::optional<std::string> readText(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return std::nullopt;
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// Resolves #include "x" against the including file's folder, then the shader folder (so
// "preskin/skin.glsl" and "shared/gpu_types.h" work from anywhere).
class FolderIncluder : public glslang::TShader::Includer {
public:
    explicit FolderIncluder(std::filesystem::path root) : root_(std::move(root)) {}

    IncludeResult* includeLocal(const char* headerName, const char* includerName, size_t) override {
        if (includerName && *includerName) {
            if (IncludeResult* r = tryOpen(std::filesystem::path(includerName).parent_path() / headerName)) return r;
        }
        return tryOpen(root_ / headerName);
    }
    IncludeResult* includeSystem(const char* headerName, const char*, size_t) override {
        return tryOpen(root_ / headerName);
    }
    void releaseInclude(IncludeResult* result) override {
        if (!result) return;
        delete static_cast<std::string*>(result->userData);
        delete result;
    }

private:
    IncludeResult* tryOpen(const std::filesystem::path& path) {
        std::error_code ec;
        if (!std::filesystem::is_regular_file(path, ec)) return nullptr;
        auto text = readText(path);
        if (!text) return nullptr;
        auto* owned = new std::string(std::move(*text));
        return new IncludeResult(path.lexically_normal().string(), owned->data(), owned->size(), owned);
    }

    std::filesystem::path root_;
};

}  // namespace

std::vector<uint32_t> compileGlsl(const std::filesystem::path& file, const std::filesystem::path& includeDir,
                                  std::string& log) {
    const std::string ext = file.extension().string();
    const EShLanguage stage = ext == ".vert" ? EShLangVertex : ext == ".frag" ? EShLangFragment : EShLangCompute;
    const auto source = readText(file);
    if (!source) {
        log += fmt::format("{}: cannot read the file\n", file.string());
        return {};
    }
    const std::string name = file.string();
    const char* text = source->c_str();
    const int length = static_cast<int>(source->size());
    const char* names[] = {name.c_str()};

    glslang::TShader shader(stage);
    shader.setStringsWithLengthsAndNames(&text, &length, names, 1);
    shader.setEnvInput(glslang::EShSourceGlsl, stage, glslang::EShClientVulkan, 100);
    shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_3);
    shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_6);
    const auto messages = static_cast<EShMessages>(EShMsgSpvRules | EShMsgVulkanRules);
    FolderIncluder includer(includeDir);
    const bool parsed = shader.parse(GetDefaultResources(), 460, false, messages, includer);
    const std::string parseLog = shader.getInfoLog();
    if (!parseLog.empty()) log += parseLog;
    if (!parsed) return {};

    glslang::TProgram program;
    program.addShader(&shader);
    if (!program.link(messages)) {
        log += fmt::format("{}: link failed\n{}", name, program.getInfoLog());
        return {};
    }
    std::vector<uint32_t> spirv;
    glslang::SpvOptions options;
    spv::SpvBuildLogger logger;
    glslang::GlslangToSpv(*program.getIntermediate(stage), spirv, &logger, &options);
    const std::string spvLog = logger.getAllMessages();
    if (!spvLog.empty()) log += fmt::format("{}: {}", name, spvLog);
    return spirv;
}

ShaderReloader::ShaderReloader(std::filesystem::path shaderDir) : dir_(std::move(shaderDir)) {
    std::error_code ec;
    enabled_ = !dir_.empty() && std::filesystem::is_directory(dir_, ec);
    if (!enabled_) return;
    glslang::InitializeProcess();
    known_ = scan();
    nextPoll_ = Clock::now() + kPollInterval;
}

ShaderReloader::~ShaderReloader() {
    if (job_.valid()) job_.wait();
    if (enabled_) glslang::FinalizeProcess();
}

ShaderReloader::Snapshot ShaderReloader::scan() const {
    Snapshot snapshot;
    std::error_code ec;
    for (auto it = std::filesystem::recursive_directory_iterator(dir_, ec);
         !ec && it != std::filesystem::recursive_directory_iterator(); it.increment(ec)) {
        std::error_code fileEc;
        if (!it->is_regular_file(fileEc) || !isWatched(it->path())) continue;
        const auto time = it->last_write_time(fileEc);
        const auto size = it->file_size(fileEc);
        if (!fileEc) snapshot[it->path()] = {time, size};
    }
    return snapshot;
}

void ShaderReloader::poll() {
    if (!enabled_) return;
    const auto now = Clock::now();
    if (watching_ && now >= nextPoll_) {
        nextPoll_ = now + kPollInterval;
        Snapshot current = scan();
        if (current != known_) {
            for (const auto& [path, stamp] : current) {
                auto it = known_.find(path);
                if (it == known_.end() || it->second != stamp)
                    pendingChanges_.push_back(path.lexically_relative(dir_).string());
            }
            for (const auto& [path, stamp] : known_)
                if (!current.count(path))
                    pendingChanges_.push_back(path.lexically_relative(dir_).string() + " (removed)");
            known_ = std::move(current);
            changedAt_ = now;
        }
    }
    if (changedAt_ && now - *changedAt_ >= kQuietTime && !job_.valid()) {
        std::sort(pendingChanges_.begin(), pendingChanges_.end());
        pendingChanges_.erase(std::unique(pendingChanges_.begin(), pendingChanges_.end()), pendingChanges_.end());
        start(std::exchange(pendingChanges_, {}));
        changedAt_.reset();
    }
}

void ShaderReloader::requestBuild() {
    if (!enabled_) return;
    known_ = scan();
    if (job_.valid()) {
        changedAt_ = Clock::now();  // build again once the running one is done
        return;
    }
    start({});
}

void ShaderReloader::start(std::vector<std::string> changed) {
    const std::filesystem::path dir = dir_;
    job_ = std::async(std::launch::async, [dir, changed = std::move(changed)] {
        const auto begin = Clock::now();
        ShaderBuild build;
        build.changedFiles = changed;
        build.ok = true;
        try {
            std::vector<std::filesystem::path> entries;
            std::error_code ec;
            for (auto it = std::filesystem::directory_iterator(dir, ec);
                 !ec && it != std::filesystem::directory_iterator(); it.increment(ec)) {
                std::error_code fileEc;
                if (it->is_regular_file(fileEc) && isEntryPoint(it->path())) entries.push_back(it->path());
            }
            std::sort(entries.begin(), entries.end());
            for (const auto& file : entries) {
                std::vector<uint32_t> spirv = compileGlsl(file, dir, build.log);
                if (spirv.empty())
                    build.ok = false;
                else
                    build.spirvByFile[file.filename().string()] = std::move(spirv);
            }
            if (entries.empty()) {
                build.ok = false;
                build.log += fmt::format("{}: no shader entry points (*.vert, *.frag, *.comp)\n", dir.string());
            }
        } catch (const std::exception& e) {
            build.ok = false;
            build.log += fmt::format("{}: {}\n", dir.string(), e.what());
        }
        build.compileMs = std::chrono::duration<double, std::milli>(Clock::now() - begin).count();
        return build;
    });
}

std::optional<ShaderBuild> ShaderReloader::takeResult() {
    if (!job_.valid() || job_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return std::nullopt;
    return job_.get();
}

}  // namespace preskin::viewer
