// View construction: reversed-Z projections, stereo pairs and the default framings (see
// <preskin/View.h>).
#include <preskin/View.h>

#include <preskin/Error.h>

#include "view/Projection.h"

#include <fmt/core.h>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace preskin {

namespace {

glm::mat4 perspectiveFromFov(const FovAngles& fov, float nearM) {
    return reversedInfinitePerspective(std::tan(fov.left), std::tan(fov.right), std::tan(fov.up), std::tan(fov.down),
                                       nearM);
}

void checkFov(const FovAngles& fov, const char* what) {
    const float limit = 0.5f * glm::pi<float>() - 1e-3f;
    for (float a : {fov.left, fov.right, fov.up, fov.down})
        if (!std::isfinite(a) || std::abs(a) > limit)
            throw Error(fmt::format("{}: field-of-view angles must be finite and within +-90 degrees", what));
    if (!(fov.left < fov.right) || !(fov.down < fov.up))
        throw Error(fmt::format("{}: field of view needs left < right and down < up", what));
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

Eye perspectiveEye(const glm::mat4& worldFromView, const FovAngles& fov, float nearM, float farM) {
    checkFov(fov, "perspective eye");
    Eye eye;
    eye.viewFromWorld = glm::inverse(worldFromView);
    eye.clipFromView = perspectiveFromFov(fov, nearM);
    eye.positionWs = glm::vec3(worldFromView[3]);
    eye.nearM = nearM;
    eye.farM = farM;
    return eye;
}

FovAngles symmetricFov(float yfov, float aspect) {
    const float halfY = 0.5f * yfov;
    const float halfX = std::atan(std::tan(halfY) * aspect);
    return FovAngles{-halfX, halfX, halfY, -halfY};
}

FovAngles fovOf(const Eye& eye) {
    if (eye.orthographic()) throw Error("view: an orthographic eye has no field-of-view angles");
    const glm::vec4 t = perspectiveTangents(eye.clipFromView);
    return FovAngles{std::atan(t.x), std::atan(t.y), std::atan(t.z), std::atan(t.w)};
}

View stereoView(const glm::mat4& worldFromHead, float ipdM, const FovAngles& leftFov, const FovAngles& rightFov,
                float nearM, float farM) {
    if (!std::isfinite(ipdM) || ipdM < 0.0f || ipdM > 1.0f)
        throw Error(fmt::format("stereo view: IPD {} m is outside 0..1 m", ipdM));
    checkFov(leftFov, "stereo view: left eye");
    checkFov(rightFov, "stereo view: right eye");
    View view;
    for (int side : {-1, 1}) {
        glm::mat4 worldFromEye = worldFromHead;
        worldFromEye[3] = worldFromHead * glm::vec4(0.5f * ipdM * float(side), 0.0f, 0.0f, 1.0f);
        view.eyes.push_back(perspectiveEye(worldFromEye, side < 0 ? leftFov : rightFov, nearM, farM));
    }
    return view;
}

View stereoFromMono(const View& mono, float ipdM) {
    const Eye& eye = mono.eye(0);
    const FovAngles fov = fovOf(eye);
    return stereoView(glm::inverse(eye.viewFromWorld), ipdM, fov, fov, eye.nearM, eye.farM);
}

View perspectiveView(const glm::mat4& worldFromView, float yfov, float aspect, float nearM, float farM) {
    return View(perspectiveEye(worldFromView, symmetricFov(yfov, aspect), nearM, farM));
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
            const glm::vec3 v =
                glm::vec3(viewFromWorldAtCenter * glm::vec4(corner, 1.0f)) + glm::vec3(0.0f, 0.0f, 1.0f);
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
    if (!camera.orthographic) {
        // A field of view the file allows may still not fit this aspect (yfov near pi at 16:9):
        // say which camera and why.
        const FovAngles fov = symmetricFov(camera.yfov, a);
        const std::string what =
            fmt::format("{}{}camera '{}': yfov {} rad at aspect {}", camera.source.empty() ? "" : camera.source,
                        camera.source.empty() ? "" : " (", camera.name, camera.yfov, a) +
            (camera.source.empty() ? "" : ")");
        checkFov(fov, what.c_str());
        return View(perspectiveEye(camera.worldFromView, fov, nearM, farM));
    }
    Eye ortho;
    ortho.viewFromWorld = glm::inverse(camera.worldFromView);
    ortho.clipFromView = reversedOrthographic(camera.xmag, camera.ymag, nearM, farM);
    ortho.positionWs = eye;
    ortho.nearM = nearM;
    ortho.farM = farM;
    return View(ortho);
}

}  // namespace preskin
