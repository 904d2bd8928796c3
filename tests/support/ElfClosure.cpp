// ELF dynamic dependencies (see ElfClosure.h). Format: the System V ABI's ELF-64 object file
// format: the program headers give PT_DYNAMIC and the PT_LOAD segments that map the string
// table's address (DT_STRTAB) back to a file offset.
#include "support/ElfClosure.h"

#include <elf.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>

namespace preskin::test {

namespace fs = std::filesystem;

namespace {

struct DynamicEntries {
    std::vector<std::string> needed;
    std::vector<std::string> runpath;
    std::vector<std::string> rpath;
};

std::vector<std::string> splitPath(const std::string& text, const fs::path& origin) {
    std::vector<std::string> out;
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ':');) {
        for (const char* token : {"$ORIGIN", "${ORIGIN}"})
            for (size_t at; (at = item.find(token)) != std::string::npos;)
                item.replace(at, std::strlen(token), origin.string());
        if (!item.empty()) out.push_back(item);
    }
    return out;
}

std::optional<DynamicEntries> readDynamic(const fs::path& file, std::string& problem) {
    std::ifstream in(file, std::ios::binary);
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    Elf64_Ehdr header{};
    if (bytes.size() < sizeof header) return problem = file.string() + ": not an ELF file", std::nullopt;
    std::memcpy(&header, bytes.data(), sizeof header);
    if (std::memcmp(header.e_ident, ELFMAG, SELFMAG) != 0 || header.e_ident[EI_CLASS] != ELFCLASS64 ||
        header.e_ident[EI_DATA] != ELFDATA2LSB)
        return problem = file.string() + ": not a 64-bit little-endian ELF file", std::nullopt;
    std::vector<Elf64_Phdr> segments(header.e_phnum);
    for (size_t i = 0; i < segments.size(); ++i) {
        const size_t at = header.e_phoff + i * header.e_phentsize;
        if (at + sizeof(Elf64_Phdr) > bytes.size()) return problem = file.string() + ": truncated", std::nullopt;
        std::memcpy(&segments[i], bytes.data() + at, sizeof(Elf64_Phdr));
    }
    auto fileOffset = [&](uint64_t address) -> std::optional<uint64_t> {
        for (const Elf64_Phdr& s : segments)
            if (s.p_type == PT_LOAD && address >= s.p_vaddr && address < s.p_vaddr + s.p_filesz)
                return address - s.p_vaddr + s.p_offset;
        return std::nullopt;
    };
    DynamicEntries out;
    for (const Elf64_Phdr& s : segments) {
        if (s.p_type != PT_DYNAMIC) continue;
        std::vector<Elf64_Dyn> entries;
        for (uint64_t at = s.p_offset;
             at + sizeof(Elf64_Dyn) <= std::min<uint64_t>(bytes.size(), s.p_offset + s.p_filesz);
             at += sizeof(Elf64_Dyn)) {
            Elf64_Dyn d{};
            std::memcpy(&d, bytes.data() + at, sizeof d);
            if (d.d_tag == DT_NULL) break;
            entries.push_back(d);
        }
        std::optional<uint64_t> strtab;
        for (const Elf64_Dyn& d : entries)
            if (d.d_tag == DT_STRTAB) strtab = fileOffset(d.d_un.d_ptr);
        if (!strtab) return problem = file.string() + ": no string table", std::nullopt;
        auto text = [&](uint64_t offset) {
            const uint64_t at = *strtab + offset;
            if (at >= bytes.size()) return std::string();
            return std::string(bytes.data() + at, strnlen(bytes.data() + at, bytes.size() - at));
        };
        for (const Elf64_Dyn& d : entries) {
            if (d.d_tag == DT_NEEDED) out.needed.push_back(text(d.d_un.d_val));
            if (d.d_tag == DT_RUNPATH) out.runpath = splitPath(text(d.d_un.d_val), fs::absolute(file).parent_path());
            if (d.d_tag == DT_RPATH) out.rpath = splitPath(text(d.d_un.d_val), fs::absolute(file).parent_path());
        }
    }
    return out;
}

}  // namespace

std::vector<std::string> ElfClosure::outside(const std::vector<std::string>& allowed) const {
    std::vector<std::string> out;
    for (const auto& [name, library] : libraries)
        if (std::find(allowed.begin(), allowed.end(), name) == allowed.end())
            out.push_back(name + " (needed by " + library.neededBy + ")");
    return out;
}

ElfClosure elfClosure(const fs::path& file, const std::vector<fs::path>& searchFirst, bool systemFolders) {
    static const std::vector<std::string> kSystem = {
        "/lib/x86_64-linux-gnu", "/usr/lib/x86_64-linux-gnu", "/lib64", "/usr/lib64", "/lib", "/usr/lib"};
    ElfClosure closure;
    std::vector<std::pair<fs::path, std::string>> pending = {{file, file.filename().string()}};
    while (!pending.empty()) {
        const auto [current, name] = pending.back();
        pending.pop_back();
        std::string problem;
        const std::optional<DynamicEntries> dynamic = readDynamic(current, problem);
        if (!dynamic) {
            closure.problems.push_back(problem);
            continue;
        }
        std::vector<std::string> folders = dynamic->runpath.empty() ? dynamic->rpath : std::vector<std::string>{};
        for (const fs::path& f : searchFirst) folders.push_back(f.string());
        folders.insert(folders.end(), dynamic->runpath.begin(), dynamic->runpath.end());
        if (systemFolders) folders.insert(folders.end(), kSystem.begin(), kSystem.end());
        for (const std::string& needed : dynamic->needed) {
            if (closure.libraries.count(needed)) continue;
            ElfLibrary library;
            library.neededBy = current.filename().string();
            std::error_code ec;
            for (const std::string& folder : folders)
                if (fs::is_regular_file(fs::path(folder) / needed, ec)) {
                    library.path = fs::canonical(fs::path(folder) / needed, ec);
                    library.bytes = fs::file_size(library.path, ec);
                    break;
                }
            if (library.path.empty())
                closure.problems.push_back(needed + " (needed by " + library.neededBy + ") not found");
            else
                pending.push_back({library.path, needed});
            closure.libraries[needed] = library;
        }
    }
    return closure;
}

const std::vector<std::string>& runtimeLibraries() {
    static const std::vector<std::string> kRuntime = {"libc.so.6",       "libm.so.6",           "libdl.so.2",
                                                      "libpthread.so.0", "librt.so.1",          "libstdc++.so.6",
                                                      "libgcc_s.so.1",   "ld-linux-x86-64.so.2"};
    return kRuntime;
}

}  // namespace preskin::test
