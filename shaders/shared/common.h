// Shared between C++ and GLSL: every GPU struct, binding number and constant is written once,
// in shaders/shared/, and read by both sides. Structs use only 16-byte members (vec4, uvec4,
// mat4) so std140 and std430 layouts equal the C++ layout; C++ checks sizes with static_assert.
#ifndef PRESKIN_SHARED_COMMON_H
#define PRESKIN_SHARED_COMMON_H

#ifdef __cplusplus
#include <glm/glm.hpp>

#include <cstdint>
#define PRESKIN_GPU_BEGIN namespace preskin::gpu { using namespace glm; using uint = std::uint32_t;
#define PRESKIN_GPU_END }
#define PRESKIN_CONST(type, name, value) inline constexpr type name = value;
#define PRESKIN_CHECK_SIZE(type, bytes) static_assert(sizeof(type) == (bytes), #type " layout changed");
#else
#define PRESKIN_GPU_BEGIN
#define PRESKIN_GPU_END
#define PRESKIN_CONST(type, name, value) const type name = value;
#define PRESKIN_CHECK_SIZE(type, bytes)
#endif

#endif
