// libFuzzer target: the glTF loader on arbitrary bytes, as a .glb when they start with the GLB
// magic and as a .gltf otherwise. The scene's folder holds a valid buffer (triangle.bin) and a
// PNG (texture.png) so that URIs can reach real files. Only preskin::Error may come out; any
// other exception, crash, leak or undefined behaviour is a finding.
// Seeds: tests/data/gltf, tests/data/hostile (scripts/fuzz.sh).
#include "FuzzFolder.h"

#include "scene/GltfLoader.h"

#include <preskin/Error.h>

#include <cstring>
#include <vector>

namespace {

const std::filesystem::path& sceneFolder() {
    static const std::filesystem::path folder = [] {
        const std::filesystem::path dir = preskin::fuzz::fuzzFolder() / "scene";
        std::filesystem::create_directories(dir);
        const std::filesystem::path data = std::filesystem::path(PRESKIN_SOURCE_DIR) / "tests" / "data";
        std::filesystem::copy_file(data / "gltf" / "triangle.bin", dir / "triangle.bin");
        std::filesystem::copy_file(data / "hostile" / "huge.png", dir / "texture.png");
        return dir;
    }();
    return folder;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const bool glb = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
    const std::filesystem::path path = sceneFolder() / (glb ? "fuzz.glb" : "fuzz.gltf");
    try {
        preskin::gltf::loadSceneBytes(std::vector<uint8_t>(data, data + size), path, {});
    } catch (const preskin::Error&) {
        // The expected outcome for almost every input: a refusal with a message.
    }
    return 0;
}
