// A view: camera transform and projection. Projections are Vulkan-style (Y down in clip space,
// depth 0..1) with reversed Z (1 at the near plane); perspective ones have an infinite far plane.
// farM is still kept: it bounds the light clustering's depth slices.
#pragma once

#include <preskin/Export.h>
#include <preskin/Scene.h>

#include <glm/glm.hpp>

namespace preskin {

struct View {
    glm::mat4 viewFromWorld{1.0f};
    glm::mat4 clipFromView{1.0f};
    glm::vec3 positionWs{0.0f};
    float nearM = 0.01f;
    float farM = 100.0f;

    glm::mat4 clipFromWorld() const { return clipFromView * viewFromWorld; }
};

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
