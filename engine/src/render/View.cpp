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
    const float fitFov = std::min(yfov, 2.0f * std::atan(std::tan(0.5f * yfov) * aspect));
    const float distance = distanceM > 0.0f ? distanceM : radius / std::sin(0.5f * fitFov) * 1.02f;
    const float yaw = glm::radians(yawDeg);
    const float pitch = glm::radians(std::clamp(pitchDeg, -89.0f, 89.0f));
    const glm::vec3 offset(std::sin(yaw) * std::cos(pitch), std::sin(pitch), std::cos(yaw) * std::cos(pitch));
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
