// Reversed-Z projection matrices (Vulkan clip space: +Y down, depth 1 at the near plane), shared
// by the public view helpers (View.cpp) and the light grid's cluster camera.
#pragma once

#include <glm/glm.hpp>

namespace preskin {

// Off-centre perspective with an infinite far plane from the tangents of its edge angles
// (left < right, down < up): ndc x = (2 x/d - (r + l)) / (r - l) at view depth d = -z, ndc y
// likewise but flipped, depth = near / d.
inline glm::mat4 reversedInfinitePerspective(float left, float right, float up, float down, float nearM) {
    glm::mat4 m(0.0f);
    m[0][0] = 2.0f / (right - left);
    m[2][0] = (right + left) / (right - left);
    m[1][1] = -2.0f / (up - down);
    m[2][1] = -(up + down) / (up - down);
    m[2][3] = -1.0f;
    m[3][2] = nearM;
    return m;
}

// The edge tangents (left, right, up, down) of a perspective projection of the usual form (no
// x/y terms in its depth and w rows): the inverse of the formula above.
inline glm::vec4 perspectiveTangents(const glm::mat4& clipFromView) {
    const float spanX = 2.0f / clipFromView[0][0];
    const float sumX = clipFromView[2][0] * spanX;
    const float spanY = -2.0f / clipFromView[1][1];
    const float sumY = -clipFromView[2][1] * spanY;
    return glm::vec4(0.5f * (sumX - spanX), 0.5f * (sumX + spanX), 0.5f * (sumY + spanY), 0.5f * (sumY - spanY));
}

}  // namespace preskin
