// What a frame is seen from: a View holds one eye (mono) or several (stereo: left, right), each a
// camera with its own transform and projection. The renderer draws every eye of a view in one
// forward pass (multiview); mono is the one-eye case of the same path.
//
// Projections are Vulkan-style (Y down in clip space, depth 0..1) with reversed Z (1 at the near
// plane); perspective ones have an infinite far plane. farM is still kept: it bounds the light
// clustering's depth slices.
#pragma once

#include <preskin/Export.h>
#include <preskin/Scene.h>

#include <preskin/Glm.h>

#include <cstdint>
#include <vector>

namespace preskin {

// The most eyes one view may hold (the renderer also stays within the device's multiview count).
inline constexpr uint32_t kMaxEyes = 6;

// One camera.
struct Eye {
    glm::mat4 viewFromWorld{1.0f};
    glm::mat4 clipFromView{1.0f};
    glm::vec3 positionWs{0.0f};
    float nearM = 0.01f;
    float farM = 100.0f;

    glm::mat4 clipFromWorld() const { return clipFromView * viewFromWorld; }
    bool orthographic() const { return clipFromView[2][3] == 0.0f; }
};

// An eye's field of view as OpenXR gives it (XrFovf): the angles in radians between the view
// direction and each edge; left and down are negative for a frustum around the view direction.
// Each angle lies in (-pi/2, pi/2) and left < right, down < up.
struct FovAngles {
    float left = -0.5f;
    float right = 0.5f;
    float up = 0.5f;
    float down = -0.5f;
};

struct View {
    std::vector<Eye> eyes;  // 1 .. kMaxEyes; stereo: eyes[0] left, eyes[1] right

    View() = default;
    explicit View(const Eye& eye) : eyes{eye} {}
    uint32_t eyeCount() const { return static_cast<uint32_t>(eyes.size()); }
    // Eye 0 (the only one of a mono view).
    const Eye& eye(uint32_t index = 0) const { return eyes.at(index); }
    Eye& eye(uint32_t index = 0) { return eyes.at(index); }
};

// A perspective eye from a camera-to-world transform (looking down -Z, +Y up) and its angles.
PRESKIN_API Eye perspectiveEye(const glm::mat4& worldFromView, const FovAngles& fov, float nearM, float farM);
// The symmetric angles of a vertical field of view (radians) and an aspect ratio (width / height).
PRESKIN_API FovAngles symmetricFov(float yfov, float aspect);
// The angles of a perspective eye's projection; throws preskin::Error for an orthographic one.
PRESKIN_API FovAngles fovOf(const Eye& eye);

// A stereo pair from a head pose (head-to-world: looking down -Z, +Y up, +X to the right) and an
// interpupillary distance: the left eye at -ipd/2 along the head's +X, the right at +ipd/2, both
// looking where the head looks, each with its own angles. Throws preskin::Error for a
// non-finite or negative IPD or invalid angles.
PRESKIN_API View stereoView(const glm::mat4& worldFromHead, float ipdM, const FovAngles& leftFov,
                            const FovAngles& rightFov, float nearM, float farM);
// The stereo pair seen from a mono perspective view's camera: the head where the mono eye is,
// both eyes with the mono eye's angles.
PRESKIN_API View stereoFromMono(const View& mono, float ipdM);

// Perspective view from a camera-to-world transform (looking down -Z, +Y up).
PRESKIN_API View perspectiveView(const glm::mat4& worldFromView, float yfov, float aspect, float nearM, float farM);
// Orbit around the bounds' centre: yaw about +Y (0 looks from +Z towards -Z), pitch up, both in
// degrees; distanceM <= 0 frames the bounds' bounding sphere.
PRESKIN_API View orbitView(const Bounds& bounds, float yawDeg, float pitchDeg, float distanceM, float aspect,
                           float yfov = 0.5f);
// The default framing: from the front (+Z), slightly above, the whole bounds in view.
PRESKIN_API View frameBoundsView(const Bounds& bounds, float aspect);
// A glTF camera; its aspect ratio is used when it has one, else `aspect`.
PRESKIN_API View cameraView(const Camera& camera, float aspect, const Bounds& sceneBounds);

}  // namespace preskin
