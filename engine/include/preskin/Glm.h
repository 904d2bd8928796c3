// The glm configuration preskin's API is compiled against. The library's own glm options
// (depth range, handedness) are private to it: nothing in the public headers depends on them,
// so a host keeps its own. What must match is the memory layout of the vector and matrix types
// the API passes: glm's default packed highp types. A host that defines
// GLM_FORCE_DEFAULT_ALIGNED_GENTYPES or a GLM_FORCE_PRECISION_* option changes those types and
// stops here with a message rather than passing misaligned data.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

static_assert(glm::defaultp == glm::packed_highp,
              "preskin's API uses glm's default packed highp types: do not define GLM_FORCE_DEFAULT_ALIGNED_GENTYPES "
              "or GLM_FORCE_PRECISION_* in code that includes preskin headers");
static_assert(sizeof(glm::vec3) == 12 && sizeof(glm::vec4) == 16 && alignof(glm::vec4) == alignof(float) &&
                  sizeof(glm::mat4) == 64 && sizeof(glm::quat) == 16,
              "preskin's API expects glm's packed vector, matrix and quaternion layouts");
