// What each shared library links: libpreskin (what every host links) needs no Embree; the
// diffusion reference, which traces rays, lives in libpreskin_reference (read from the ELF
// dynamic sections with objdump). The core's whole closure (every library it loads, and theirs)
// stays within an explicit list of small libraries, built and installed: OpenImageIO and its
// hundreds of dependencies come only with the image component.
#include "support/ElfClosure.h"
#include "support/Process.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

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

// What libpreskin may load beyond the C/C++ runtime (the Vulkan loader it opens itself, with
// dlopen, and is not among its DT_NEEDED): the glTF parser and stb_image (which tinygltf links),
// PNG and JPEG decoding with zlib, fmt and TBB.
const std::vector<std::string> kCoreLibraries = {"libtinygltf.so.2d", "libstb.so.0", "libpng16.so.16", "libz.so.1",
                                                 "libjpeg.so.62",     "libfmt.so.9", "libtbb.so.12"};

void expectLeanClosure(const std::filesystem::path& library, const char* what) {
    ASSERT_TRUE(std::filesystem::exists(library)) << library;
    const ElfClosure closure = elfClosure(library);
    EXPECT_TRUE(closure.problems.empty()) << closure.problems.front();
    std::vector<std::string> allowed = runtimeLibraries();
    allowed.insert(allowed.end(), kCoreLibraries.begin(), kCoreLibraries.end());
    for (const std::string& outside : closure.outside(allowed)) ADD_FAILURE() << what << " loads " << outside;
    size_t count = 0;
    uint64_t bytes = 0;
    std::printf("%s closure beyond the C/C++ runtime:\n", what);
    for (const auto& [name, lib] : closure.libraries) {
        const auto& runtime = runtimeLibraries();
        if (std::find(runtime.begin(), runtime.end(), name) != runtime.end()) continue;
        ++count;
        bytes += lib.bytes;
        std::printf("  %-20s %8.1f KiB  %s\n", name.c_str(), double(lib.bytes) / 1024.0, lib.path.c_str());
    }
    std::printf("  %zu libraries, %.2f MB\n", count, double(bytes) / 1e6);
    EXPECT_LE(count, 12u);
    EXPECT_LE(bytes, 8'000'000u);
    // The dependencies really were read: the runtime and the PNG decoder are there.
    EXPECT_EQ(closure.libraries.count("libstdc++.so.6"), 1u);
    EXPECT_EQ(closure.libraries.count("libpng16.so.16"), 1u);
}

TEST(LibraryLinks, CoreClosureIsTheAllowedSmallLibraries) {
    expectLeanClosure(std::filesystem::path(PRESKIN_BINARY_DIR) / "engine" / "libpreskin.so", "built libpreskin");
}

TEST(LibraryLinks, InstalledCoreClosureIsTheAllowedSmallLibraries) {
    const std::filesystem::path prefix = std::filesystem::path(PRESKIN_BINARY_DIR) / "core-install-test";
    std::error_code ec;
    std::filesystem::remove_all(prefix, ec);
    const ProcessResult install = installBuild(prefix, "Unspecified", 120.0);
    ASSERT_EQ(install.exitCode, 0) << install.out << install.err;
    std::filesystem::path library;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(prefix))
        if (entry.path().filename() == "libpreskin.so") library = entry.path();
    ASSERT_FALSE(library.empty()) << "no libpreskin.so under " << prefix;
    expectLeanClosure(library, "installed libpreskin");
    // The core install holds neither the image component nor the tools.
    for (const auto& entry : std::filesystem::recursive_directory_iterator(prefix)) {
        EXPECT_EQ(entry.path().filename().string().find("imageio"), std::string::npos) << entry.path();
        EXPECT_NE(entry.path().parent_path().filename(), "bin") << entry.path();
    }
}

// The image component is where OpenImageIO is.
TEST(LibraryLinks, ImageComponentCarriesOpenImageIo) {
    const std::filesystem::path library =
        std::filesystem::path(PRESKIN_BINARY_DIR) / "engine" / "imageio" / "libpreskin_imageio.so";
    const ElfClosure closure = elfClosure(library);
    bool oiio = false;
    for (const auto& [name, lib] : closure.libraries) oiio = oiio || name.find("libOpenImageIO") == 0;
    EXPECT_TRUE(oiio);
    EXPECT_EQ(closure.libraries.count("libpreskin.so.0.1"), 1u);
    std::printf("libpreskin_imageio closure: %zu libraries\n", closure.libraries.size());
}

}  // namespace
}  // namespace preskin::test
