// Orbit, fly and scene cameras (see CameraController.h).
#include "CameraController.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace preskin::viewer {

namespace {

constexpr float kDegreesPerPx = 0.25f;
constexpr float kYfov = 0.5f;  // radians; orbitView's default

}  // namespace

void CameraController::reset(const Bounds& bounds, const std::vector<Camera>& sceneCameras) {
    bounds_ = bounds;
    cameras_ = sceneCameras;
    radiusM_ = bounds.empty() ? 1.0f : std::max(0.5f * glm::length(bounds.extent()), 1e-4f);
    mode_ = CameraMode::Orbit;
    sceneCamera_ = 0;
    yawDeg_ = 0.0f;
    pitchDeg_ = 8.0f;
    distanceM_ = 0.0f;
    flySpeedMps_ = radiusM_;
}

void CameraController::setOrbit(float yawDeg, float pitchDeg, float distanceM) {
    mode_ = CameraMode::Orbit;
    yawDeg_ = yawDeg;
    pitchDeg_ = std::clamp(pitchDeg, -89.0f, 89.0f);
    distanceM_ = distanceM;
}

float CameraController::orbitDistanceM(float aspect) const {
    if (distanceM_ > 0.0f) return distanceM_;
    const glm::vec3 center = bounds_.empty() ? glm::vec3(0.0f) : bounds_.center();
    return glm::length(orbitView(bounds_, yawDeg_, pitchDeg_, 0.0f, aspect, kYfov).eye().positionWs - center);
}

glm::vec3 CameraController::flyForward() const {
    const float yaw = glm::radians(yawDeg_);
    const float pitch = glm::radians(pitchDeg_);
    return -glm::vec3(std::sin(yaw) * std::cos(pitch), std::sin(pitch), std::cos(yaw) * std::cos(pitch));
}

void CameraController::setMode(CameraMode mode, float aspect) {
    if (mode == mode_) return;
    if (mode == CameraMode::Fly) {
        const Eye current = view(aspect).eye();
        flyPositionWs_ = current.positionWs;
        // Direction the current view looks along, as yaw/pitch of the fly camera.
        const glm::vec3 forward = -glm::vec3(glm::inverse(current.viewFromWorld)[2]);
        pitchDeg_ = glm::degrees(std::asin(std::clamp(-forward.y, -1.0f, 1.0f)));
        yawDeg_ = glm::degrees(std::atan2(-forward.x, -forward.z));
    }
    if (mode == CameraMode::Orbit) distanceM_ = 0.0f;
    if (mode == CameraMode::Scene && cameras_.empty()) return;
    mode_ = mode;
}

void CameraController::update(const CameraInput& input, float dtS, float aspect) {
    if (mode_ == CameraMode::Scene) return;
    yawDeg_ -= input.dragPx.x * kDegreesPerPx;
    yawDeg_ = std::fmod(yawDeg_, 360.0f);
    pitchDeg_ = std::clamp(pitchDeg_ + input.dragPx.y * kDegreesPerPx, -89.0f, 89.0f);
    if (mode_ == CameraMode::Orbit) {
        if (input.wheelSteps != 0.0f) {
            distanceM_ = orbitDistanceM(aspect);  // leaving "fit" starts from the fitted distance
            distanceM_ = std::clamp(distanceM_ * std::pow(0.9f, input.wheelSteps), radiusM_ * 0.05f, radiusM_ * 100.0f);
        }
        return;
    }
    if (input.wheelSteps != 0.0f)
        flySpeedMps_ = std::clamp(flySpeedMps_ * std::pow(1.2f, input.wheelSteps), radiusM_ * 0.01f, radiusM_ * 100.0f);
    const glm::vec3 forward = flyForward();
    const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0.0f, 1.0f, 0.0f)));
    const glm::vec3 move =
        right * input.moveAxes.x + glm::vec3(0.0f, 1.0f, 0.0f) * input.moveAxes.y + forward * input.moveAxes.z;
    flyPositionWs_ += move * flySpeedMps_ * (input.fast ? 4.0f : 1.0f) * dtS;
}

View CameraController::view(float aspect) const {
    if (mode_ == CameraMode::Scene && sceneCamera_ >= 0 && size_t(sceneCamera_) < cameras_.size())
        return cameraView(cameras_[size_t(sceneCamera_)], aspect, bounds_);
    if (mode_ != CameraMode::Fly) return orbitView(bounds_, yawDeg_, pitchDeg_, distanceM_, aspect, kYfov);
    const glm::vec3 center = bounds_.empty() ? glm::vec3(0.0f) : bounds_.center();
    const glm::mat4 worldFromView =
        glm::inverse(glm::lookAt(flyPositionWs_, flyPositionWs_ + flyForward(), glm::vec3(0.0f, 1.0f, 0.0f)));
    const float nearM = std::max(radiusM_ * 0.005f, 1e-4f);
    const float farM = std::max(glm::length(flyPositionWs_ - center) + 2.0f * radiusM_, nearM * 2.0f);
    return perspectiveView(worldFromView, kYfov, aspect, nearM, farM);
}

}  // namespace preskin::viewer
