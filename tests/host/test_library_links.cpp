// What each shared library links: libpreskin (what every host links) needs no Embree; the
// diffusion reference, which traces rays, lives in libpreskin_reference (read from the ELF
// dynamic sections with objdump).
#include "support/Process.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace preskin::test {
namespace {

std::string neededLibraries(const std::filesystem::path& library) {
    const ProcessResult r = runProcess("/usr/bin/objdump", {"-p", library.string()}, {}, library.parent_path(), 60.0);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    std::string needed;
    size_t at = 0;
    while ((at = r.out.find("NEEDED", at)) != std::string::npos) {
        const size_t end = r.out.find('\n', at);
        needed += r.out.substr(at, end - at) + "\n";
        at = end;
    }
    return needed;
}

TEST(LibraryLinks, PreskinNeedsNoEmbreeAndTheReferenceDoes) {
    if (!std::filesystem::exists("/usr/bin/objdump")) GTEST_SKIP() << "objdump (binutils) is not installed";
    const std::filesystem::path build(PRESKIN_BINARY_DIR);
    const std::string preskin = neededLibraries(build / "engine" / "libpreskin.so");
    const std::string reference = neededLibraries(build / "engine" / "reference" / "libpreskin_reference.so");
    EXPECT_NE(preskin.find("libtbb"), std::string::npos) << preskin;  // the dump was read
    EXPECT_EQ(preskin.find("embree"), std::string::npos) << preskin;
    EXPECT_NE(reference.find("embree"), std::string::npos) << reference;
    EXPECT_NE(reference.find("libpreskin.so"), std::string::npos) << reference;
}

}  // namespace
}  // namespace preskin::test
