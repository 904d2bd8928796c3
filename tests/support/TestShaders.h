// The SPIR-V of the test compute shaders in tests/reference/shaders/*.comp, compiled at build time
// (include path: shaders/) and embedded in the test binary by tests/CMakeLists.txt.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

namespace preskin::test_shaders {

// The code of one shader by file name ("lut_lookup.comp"); empty when there is none.
std::span<const uint32_t> spirv(std::string_view fileName);

}  // namespace preskin::test_shaders
