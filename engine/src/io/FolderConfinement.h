// Keeps file references of a scene inside the scene's folder. A relative path is resolved one
// component at a time from the folder; each symbolic link met on the way is read (readlink) and
// its target resolved lexically against the link's own folder. A target that leaves the folder
// stops the resolution at once: nothing outside the folder is examined, so a refusal can tell
// nothing about what lies there (not whether it exists, its type or its size).
// Limits: at most 40 links per path, as Linux allows; the folder itself is canonicalised first
// (links above it are the user's choice).
#pragma once

#include <filesystem>
#include <optional>

namespace preskin::io {

struct ConfinedPath {
    std::filesystem::path path;  // absolute, free of links where it exists; meaningful when inside
    bool inside = false;         // false: a link leads outside the folder (or too many links)
};

// `folder` must be absolute; `relative` has no root and, lexically, no ".." leaving the folder.
ConfinedPath resolveInsideFolder(const std::filesystem::path& folder, const std::filesystem::path& relative);

}  // namespace preskin::io
