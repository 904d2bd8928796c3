// libFuzzer target: environment images (Radiance .hdr, OpenEXR) on arbitrary bytes, through
// Environment::load (header checks, the core's Radiance decoder and the image component's OpenEXR one, the number rule, the SH
// projection). Only preskin::Error may come out.
// Seeds: tests/data/environments, tests/data/hostile/*.hdr (scripts/fuzz.sh).
#include "FuzzFolder.h"

#include <preskin/Environment.h>
#include <preskin/Error.h>
#include <preskin/imageio/ImageIo.h>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::filesystem::path path = preskin::fuzz::fuzzFolder() / "environment";
    preskin::fuzz::writeFile(path, data, size);
    preskin::imageio::registerCodecs();
    try {
        preskin::Environment::load(path);
    } catch (const preskin::Error&) {}
    return 0;
}
