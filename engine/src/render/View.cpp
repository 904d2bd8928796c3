// View construction: reversed-Z projections and the default framings (see <preskin/View.h>).
#include <preskin/View.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace preskin {

namespace {

glm::mat4 reversedInfinitePerspective(float yfov, float aspect, float nearM) {
    const float f = 1.0f / std::tan(0.5f * yfov);
    glm::mat4 m(0.0f);
    m[0][0] = f / aspect;
    m[1][1] = -f;  // Vulkan clip space: +Y down
    m[2][3] = -1.0f;
    m[3][2] = nearM;  // depth = near / viewDepth
    return m;
}

glm::mat4 reversedOrthographic(float xmag, float ymag, float nearM, float farM) {
    glm::mat4 m(1.0f);
    m[0][0] = 1.0f / xmag;
    m[1][1] = -1.0f / ymag;
    m[2][2] = 1.0f / (farM - nearM);  // depth = (far + z) / (far - near): 1 at near, 0 at far
    m[3][2] = farM / (farM - nearM);
    return m;
}

}  // namespace

View perspectiveView(const glm::mat4& worldFromView, float yfov, float aspect, float nearM, float farM) {
    View view;
    view.viewFromWorld = glm::inverse(worldFromView);
    view.clipFromView = reversedInfinitePerspective(yfov, aspect, nearM);
    view.positionWs = glm::vec3(worldFromView[3]);
    view.nearM = nearM;
    view.farM = farM;
    return view;
}

View orbitView(const Bounds& bounds, float yawDeg, float pitchDeg, float distanceM, float aspect, float yfov) {
    const glm::vec3 center = bounds.empty() ? glm::vec3(0.0f) : bounds.center();
    const float radius = bounds.empty() ? 1.0f : std::max(0.5f * glm::length(bounds.extent()), 1e-4f);
    const float yaw = glm::radians(yawDeg);
    const float pitch = glm::radians(std::clamp(pitchDeg, -89.0f, 89.0f));
    const glm::vec3 offset(std::sin(yaw) * std::cos(pitch), std::sin(pitch), std::cos(yaw) * std::cos(pitch));
    float distance = distanceM;
    if (distance <= 0.0f) {
        // The nearest distance at which all 8 corners of the bounds are inside the view
        // (with a 4% margin): per corner, its offset across the view over the half-angle tangent
        // plus its depth towards the camera.
        const glm::mat4 viewFromWorldAtCenter = glm::lookAt(center + offset, center, glm::vec3(0.0f, 1.0f, 0.0f));
        const float tanY = std::tan(0.5f * yfov) / 1.04f;
        const float tanX = tanY * aspect;
        const glm::vec3 lo = bounds.empty() ? glm::vec3(-1.0f) : bounds.min;
        const glm::vec3 hi = bounds.empty() ? glm::vec3(1.0f) : bounds.max;
        distance = 1e-3f;
        for (int i = 0; i < 8; ++i) {
            const glm::vec3 corner((i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z);
            const glm::vec3 v = glm::vec3(viewFromWorldAtCenter * glm::vec4(corner, 1.0f)) + glm::vec3(0.0f, 0.0f, 1.0f);
            const float towards = v.z;  // > 0: nearer the camera than the centre
            distance = std::max(distance, std::abs(v.x) / tanX + towards);
            distance = std::max(distance, std::abs(v.y) / tanY + towards);
        }
    }
    const glm::vec3 eye = center + offset * distance;
    const glm::mat4 worldFromView = glm::inverse(glm::lookAt(eye, center, glm::vec3(0.0f, 1.0f, 0.0f)));
    const float nearM = std::max(distance - radius * 1.5f, distance * 1e-3f);
    return perspectiveView(worldFromView, yfov, aspect, nearM, distance + radius * 2.0f);
}

View frameBoundsView(const Bounds& bounds, float aspect) { return orbitView(bounds, 0.0f, 8.0f, 0.0f, aspect); }

View cameraView(const Camera& camera, float aspect, const Bounds& sceneBounds) {
    const glm::vec3 eye(camera.worldFromView[3]);
    float farM = camera.zfar;
    if (farM <= 0.0f) {
        const float radius = sceneBounds.empty() ? 10.0f : 0.5f * glm::length(sceneBounds.extent());
        const glm::vec3 center = sceneBounds.empty() ? eye : sceneBounds.center();
        farM = glm::length(center - eye) + 2.0f * radius;
    }
    const float nearM = std::max(camera.znear, 1e-5f);
    farM = std::max(farM, nearM * 2.0f);
    const float a = camera.aspectRatio > 0.0f ? camera.aspectRatio : aspect;
    if (!camera.orthographic) return perspectiveView(camera.worldFromView, camera.yfov, a, nearM, farM);
    View view;
    view.viewFromWorld = glm::inverse(camera.worldFromView);
    view.clipFromView = reversedOrthographic(camera.xmag, camera.ymag, nearM, farM);
    view.positionWs = eye;
    view.nearM = nearM;
    view.farM = farM;
    return view;
}

}  // namespace preskin
