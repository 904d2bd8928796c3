// A host translation unit: <vulkan/vulkan.h> with prototypes first, its own glm options (set on
// the command line by tests/CMakeLists.txt), then every header preskin installs
// (public_headers.h, generated from the installed set), linked against the shared library only.
// It checks that the library forces none of its own Vulkan or glm choices on the host, and
// that the LUT mapping a host copies into its uniforms is reachable through the public API.
#include <vulkan/vulkan.h>

#include "public_headers.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdio>
#include <type_traits>

#ifdef VK_NO_PROTOTYPES
#error "the host's Vulkan prototypes were switched off by a preskin header or target"
#endif
#ifndef GLM_FORCE_LEFT_HANDED
#error "the host's glm option did not reach this translation unit"
#endif
static_assert(std::is_same_v<decltype(&vkCreateInstance), PFN_vkCreateInstance>);

int main() {
    const preskin::LutSet& luts = preskin::LutSet::loadDefault();
    const preskin::gpu::LutMapping m = preskin::lutMapping(luts);
    // The shared GLSL mapping function run on the host's copy gives the set's own coordinates.
    const glm::vec2 host = preskin::gpu::preskinDiffuseLutUv(m, 0.3f, 0.2f);
    const glm::vec2 library = luts.diffuseUv(0.3f, 0.2f);
    if (std::abs(host.x - library.x) > 1e-6f || std::abs(host.y - library.y) > 1e-6f) {
        std::fprintf(stderr, "diffuse uv: host (%f, %f), library (%f, %f)\n", double(host.x), double(host.y),
                     double(library.x), double(library.y));
        return 1;
    }
    // glm's handedness is the host's: a left-handed lookAt looks down +Z.
    const glm::mat4 view = glm::lookAt(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 1.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    if (std::abs(view[2][2] - 1.0f) > 1e-6f) {
        std::fprintf(stderr, "lookAt is not left-handed: the host's glm option was overridden\n");
        return 1;
    }
    return 0;
}
