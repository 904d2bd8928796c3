// A private temporary folder for a fuzz target: inputs that must be files (a scene's folder, a
// LUT set's folder, an environment image) are written into it; removed when the process exits.
#pragma once

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace preskin::fuzz {

inline const std::filesystem::path& fuzzFolder() {
    static const std::filesystem::path folder = [] {
        std::string pattern = (std::filesystem::temp_directory_path() / "preskin-fuzz-XXXXXX").string();
        if (!mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
        std::atexit([] {
            std::error_code ec;
            std::filesystem::remove_all(fuzzFolder(), ec);
        });
        return std::filesystem::path(pattern);
    }();
    return folder;
}

inline void writeFile(const std::filesystem::path& path, const uint8_t* data, size_t size) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
}

}  // namespace preskin::fuzz
