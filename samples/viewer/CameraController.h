// The viewer's cameras: orbit around the scene's bounds (preskin::orbitView; the untouched
// default equals frameBoundsView, the view `preskin render` uses), a free fly camera, or one of
// the scene's glTF cameras. Input is given per frame as mouse drag (pixels), wheel steps and
// movement keys; angles are degrees, distances metres, speeds metres per second.
// Limits: the orbit pivot is the bounds' centre (no panning); the fly camera has no roll.
#pragma once

#include <preskin/Scene.h>
#include <preskin/View.h>

#include <glm/glm.hpp>

#include <vector>

namespace preskin::viewer {

enum class CameraMode { Orbit, Fly, Scene };

struct CameraInput {
    glm::vec2 dragPx{0.0f};  // mouse movement while the rotate button is held
    float wheelSteps = 0.0f;
    glm::vec3 moveAxes{0.0f};  // x right, y up, z forward; each in [-1, 1]
    bool fast = false;
};

class CameraController {
public:
    // The default framing of `bounds`: orbit, yaw 0, pitch 8 degrees, fitted distance.
    void reset(const Bounds& bounds, const std::vector<Camera>& sceneCameras);
    void update(const CameraInput& input, float dtS, float aspect);
    View view(float aspect) const;

    CameraMode mode() const { return mode_; }
    // Switching to Fly starts from the current view's position and direction.
    void setMode(CameraMode mode, float aspect);
    void setSceneCamera(int index) { sceneCamera_ = index; }
    int sceneCamera() const { return sceneCamera_; }
    // Orbit parameters; distanceM <= 0 means "fit the bounds".
    void setOrbit(float yawDeg, float pitchDeg, float distanceM);
    // The orbit distance in use: distanceM, or the fitted one.
    float orbitDistanceM(float aspect) const;
    float& yawDeg() { return yawDeg_; }
    float& pitchDeg() { return pitchDeg_; }
    float& distanceM() { return distanceM_; }
    float& flySpeedMps() { return flySpeedMps_; }
    glm::vec3& flyPositionWs() { return flyPositionWs_; }

private:
    glm::vec3 flyForward() const;

    Bounds bounds_;
    std::vector<Camera> cameras_;
    CameraMode mode_ = CameraMode::Orbit;
    int sceneCamera_ = 0;
    float yawDeg_ = 0.0f;
    float pitchDeg_ = 8.0f;
    float distanceM_ = 0.0f;
    glm::vec3 flyPositionWs_{0.0f};
    float flySpeedMps_ = 0.5f;
    float radiusM_ = 1.0f;
};

}  // namespace preskin::viewer
