// The output rule of <preskin/OutputFile.h>.
#include <preskin/Error.h>
#include <preskin/OutputFile.h>

#include <fmt/core.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <system_error>
#include <vector>

namespace preskin {

namespace fs = std::filesystem;

namespace {

fs::path folderOf(const fs::path& path) { return path.has_parent_path() ? path.parent_path() : fs::path("."); }

// The folders of `path` that do not exist yet, outermost first; throws when the nearest one that
// exists is not a writable folder.
std::vector<fs::path> missingFolders(const fs::path& path) {
    std::vector<fs::path> missing;
    fs::path dir = folderOf(path);
    std::error_code ec;
    while (!fs::exists(fs::symlink_status(dir, ec)) && dir != folderOf(dir)) {
        missing.push_back(dir);
        dir = folderOf(dir);
    }
    std::reverse(missing.begin(), missing.end());
    if (!fs::is_directory(dir, ec))
        throw Error(fmt::format("{}: output: {} is not a folder", path.string(), dir.string()));
    if (::access(dir.c_str(), W_OK) != 0)
        throw Error(fmt::format("{}: output: folder {} is not writable", path.string(), dir.string()));
    return missing;
}

}  // namespace

void checkOutputFile(const fs::path& path) {
    std::error_code ec;
    if (path.empty() || !path.has_filename()) throw Error(fmt::format("{}: output: names no file", path.string()));
    if (fs::is_directory(path, ec)) throw Error(fmt::format("{}: output: is a folder, not a file", path.string()));
    missingFolders(path);
    // An existing file is replaced only when it is a regular file its owner left writable: the
    // rename would otherwise replace a read-only file (or a FIFO, a device) without a word.
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0) {
        if (!S_ISREG(st.st_mode))
            throw Error(fmt::format("{}: output: exists and is not a regular file; not replaced", path.string()));
        if ((st.st_mode & (S_IWUSR | S_IWGRP | S_IWOTH)) == 0 || ::access(path.c_str(), W_OK) != 0)
            throw Error(fmt::format("{}: output: exists and is read-only; not replaced", path.string()));
    }
}

void writeOutputFile(const fs::path& path, const std::function<void(const fs::path& temporary)>& write) {
    checkOutputFile(path);
    const std::vector<fs::path> made = missingFolders(path);
    std::error_code ec;
    auto removeMade = [&] {
        for (auto it = made.rbegin(); it != made.rend(); ++it) fs::remove(*it, ec);  // only if still empty
    };
    for (const fs::path& dir : made) {
        if (!fs::create_directory(dir, ec) && ec) {
            const std::string why = ec.message();
            removeMade();
            throw Error(fmt::format("{}: output: cannot make folder {}: {}", path.string(), dir.string(), why));
        }
    }
    const fs::path temp = folderOf(path) /
        fmt::format(".{}.{}.partial{}", path.filename().string(), ::getpid(), path.extension().string());
    auto fail = [&](const std::string& what) {
        fs::remove(temp, ec);
        removeMade();
        throw Error(fmt::format("{}: {}", path.string(), what));
    };
    try {
        write(temp);
    } catch (const Error&) {
        fs::remove(temp, ec);
        removeMade();
        throw;
    } catch (const std::exception& e) {
        fail(std::string("output: cannot write: ") + e.what());
    }
    fs::rename(temp, path, ec);
    if (ec) fail("output: cannot move the finished file into place: " + ec.message());
}

void writeTextFile(const fs::path& path, const std::string& text) {
    writeOutputFile(path, [&](const fs::path& temp) {
        std::ofstream out(temp, std::ios::binary | std::ios::trunc);
        out << text;
        out.close();
        if (!out) throw Error(fmt::format("{}: output: cannot write", path.string()));
    });
}

}  // namespace preskin
