// Link-by-link path resolution confined to a folder (see FolderConfinement.h).
#include "io/FolderConfinement.h"

#include <sys/stat.h>
#include <unistd.h>

#include <deque>
#include <string>
#include <system_error>

namespace preskin::io {

namespace fs = std::filesystem;

namespace {

constexpr int kMaxLinks = 40;

bool lexicallyInside(const fs::path& path, const fs::path& folder) {
    const fs::path rel = path.lexically_relative(folder);
    if (rel.empty()) return false;
    if (rel == ".") return true;
    return *rel.begin() != ".." && !rel.is_absolute();
}

std::deque<fs::path> components(const fs::path& relative) {
    std::deque<fs::path> out;
    for (const fs::path& part : relative) {
        if (!part.empty() && part != "." && part != "/") out.push_back(part);
    }
    return out;
}

}  // namespace

ConfinedPath resolveInsideFolder(const fs::path& folder, const fs::path& relative) {
    std::error_code ec;
    fs::path root = fs::canonical(folder, ec);
    if (ec) root = folder.lexically_normal();
    std::deque<fs::path> pending = components(relative);
    fs::path current = root;
    int links = 0;
    while (!pending.empty()) {
        const fs::path part = pending.front();
        pending.pop_front();
        if (part == "..") {
            if (current == root) return {current, false};
            current = current.parent_path();
            continue;
        }
        const fs::path candidate = current / part;
        struct stat st {};
        if (::lstat(candidate.c_str(), &st) != 0 || !S_ISLNK(st.st_mode)) {
            // Missing (the caller reports it as missing inside the folder) or not a link.
            current = candidate;
            continue;
        }
        if (++links > kMaxLinks) return {candidate, false};
        std::string target(static_cast<size_t>(st.st_size > 0 ? st.st_size : 255) + 1, '\0');
        const ssize_t n = ::readlink(candidate.c_str(), target.data(), target.size());
        if (n < 0 || static_cast<size_t>(n) >= target.size()) return {candidate, false};
        target.resize(static_cast<size_t>(n));
        // `current` holds no links, so ".." in the target is resolved correctly by lexical rules.
        const fs::path resolved =
            (fs::path(target).is_absolute() ? fs::path(target) : current / target).lexically_normal();
        if (!lexicallyInside(resolved, root)) return {candidate, false};
        std::deque<fs::path> rest = components(resolved.lexically_relative(root));
        rest.insert(rest.end(), pending.begin(), pending.end());
        pending = std::move(rest);
        current = root;
    }
    return {current, true};
}

}  // namespace preskin::io
