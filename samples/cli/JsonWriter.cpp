#include "JsonWriter.h"

#include <preskin/Error.h>

#include <fmt/core.h>

#include <fstream>
#include <system_error>

namespace preskin::cli {

void writeTextFile(const std::filesystem::path& path, const std::string& text, const char* flag) {
    const std::filesystem::path tmp = path.string() + ".tmp";
    {
        std::ofstream f(tmp, std::ios::binary);
        f << text;
        if (!f) {
            std::error_code ec;
            std::filesystem::remove(tmp, ec);
            throw Error(fmt::format("{}: output: cannot write ({})", path.string(), flag));
        }
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::filesystem::remove(tmp, ec);
        throw Error(fmt::format("{}: output: cannot write ({})", path.string(), flag));
    }
}

}  // namespace preskin::cli
