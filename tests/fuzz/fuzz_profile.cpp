// libFuzzer target: diffusion profile JSON and LUT manifests on arbitrary bytes. Every input is
// read both as a profile (DiffusionProfile::fromJsonText) and as the manifest.json of a LUT
// folder that holds the committed tables (luts/*.exr), so a manifest close to the real one
// reaches the table checks. Only preskin::Error may come out.
// Seeds: tests/data/profiles, luts/manifest.json, tests/data/hostile (scripts/fuzz.sh).
#include "FuzzFolder.h"

#include <preskin/DiffusionProfile.h>
#include <preskin/Error.h>
#include <preskin/LutSet.h>

#include <string_view>

namespace {

const std::filesystem::path& lutFolder() {
    static const std::filesystem::path folder = [] {
        const std::filesystem::path dir = preskin::fuzz::fuzzFolder() / "luts";
        std::filesystem::create_directories(dir);
        const std::filesystem::path luts = std::filesystem::path(PRESKIN_SOURCE_DIR) / "luts";
        for (const char* name : {"diffuse.exr", "penumbra.exr", "sh_transfer.exr", "transmittance.exr"})
            std::filesystem::copy_file(luts / name, dir / name);
        return dir;
    }();
    return folder;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    try {
        preskin::DiffusionProfile::fromJsonText(std::string_view(reinterpret_cast<const char*>(data), size),
                                                "fuzz.json");
    } catch (const preskin::Error&) {}
    preskin::fuzz::writeFile(lutFolder() / "manifest.json", data, size);
    try {
        preskin::LutSet::load(lutFolder());
    } catch (const preskin::Error&) {}
    return 0;
}
