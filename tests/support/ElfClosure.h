// The shared libraries an ELF file loads: its DT_NEEDED entries, resolved as the dynamic loader
// resolves them (DT_RPATH when there is no DT_RUNPATH, then extra folders standing for
// LD_LIBRARY_PATH, then DT_RUNPATH, then the system folders; $ORIGIN expanded), and theirs in
// turn. Read from the files' dynamic sections (64-bit little-endian ELF), without running them.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace preskin::test {

struct ElfLibrary {
    std::filesystem::path path;  // empty when not found
    uint64_t bytes = 0;          // its file size
    std::string neededBy;        // the first file that named it
};

struct ElfClosure {
    std::map<std::string, ElfLibrary> libraries;  // by DT_NEEDED name
    std::vector<std::string> problems;            // unreadable files, names not found

    // The libraries (by name) outside `allowed`, each with the file that needs it.
    std::vector<std::string> outside(const std::vector<std::string>& allowed) const;
};

// `searchFirst`: folders searched before the file's DT_RUNPATH (as LD_LIBRARY_PATH);
// `systemFolders` false: only the files' own paths and searchFirst (a library found nowhere
// else is reported as not found, as on a bare system).
ElfClosure elfClosure(const std::filesystem::path& file, const std::vector<std::filesystem::path>& searchFirst = {},
                      bool systemFolders = true);

// The C and C++ runtime every Linux program may expect: glibc's libraries, libstdc++, libgcc_s.
const std::vector<std::string>& runtimeLibraries();

}  // namespace preskin::test
