// The directional shadow map's fit to the skin in view (see ShadowFit.h).
#include "render/ShadowFit.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace preskin {
namespace {

// Light-space axes: right, up (the image plane) and the travel direction (depth).
struct LightAxes {
    glm::vec3 right, up, forward;
};

LightAxes lightAxes(const glm::vec3& direction) {
    const glm::vec3 d = glm::normalize(direction);
    const glm::vec3 helper = std::abs(d.y) < 0.99f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
    const glm::vec3 right = glm::normalize(glm::cross(helper, d));
    return {right, glm::cross(d, right), d};
}

struct Rect {
    glm::vec2 lo{std::numeric_limits<float>::max()};
    glm::vec2 hi{-std::numeric_limits<float>::max()};
    void extend(const glm::vec2& p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    bool empty() const { return lo.x > hi.x || lo.y > hi.y; }
};

glm::vec2 project(const LightAxes& a, const glm::vec3& p) { return {glm::dot(p, a.right), glm::dot(p, a.up)}; }

Rect projectBounds(const LightAxes& a, const Bounds& b) {
    Rect r;
    for (int i = 0; i < 8; ++i)
        r.extend(project(
            a, glm::vec3((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y, (i & 4) ? b.max.z : b.min.z)));
    return r;
}

// The eyes' frusta corners, from the near plane to farM (reversed Z: depth 1 is near; a
// perspective projection reaches depth near / far at farM, an orthographic one depth 0).
Rect projectFrusta(const LightAxes& a, const View& view) {
    Rect r;
    for (const Eye& eye : view.eyes) {
        const glm::dmat4 worldFromClip = glm::inverse(glm::dmat4(eye.clipFromWorld()));
        const double farDepth =
            eye.orthographic() ? 0.0 : double(eye.nearM) / std::max(double(eye.farM), double(eye.nearM));
        for (int i = 0; i < 8; ++i) {
            const glm::dvec4 p =
                worldFromClip * glm::dvec4((i & 1) ? 1.0 : -1.0, (i & 2) ? 1.0 : -1.0, (i & 4) ? farDepth : 1.0, 1.0);
            r.extend(project(a, glm::vec3(glm::dvec3(p) / p.w)));
        }
    }
    return r;
}

}  // namespace

PoseBounds skinReceiverBounds(const Scene& scene) {
    return PoseBounds(scene, [&scene](const Primitive& primitive) {
        return primitive.material >= 0 && static_cast<size_t>(primitive.material) < scene.materials.size() &&
            scene.materials[static_cast<size_t>(primitive.material)].skin.has_value();
    });
}

ShadowFit fitDirectionalShadow(const Bounds& casters, const Bounds& receivers, const View& view,
                               const glm::vec3& direction, uint32_t mapSize) {
    const LightAxes a = lightAxes(direction);
    const glm::vec3 sphereCentre = casters.empty() ? glm::vec3(0.0f) : casters.center();
    const float sphereRadius = casters.empty() ? 1.0f : std::max(0.5f * glm::length(casters.extent()), 1e-4f);

    // The image: the receivers in view, else the casters' sphere.
    glm::vec2 centre = project(a, sphereCentre);
    float half = sphereRadius;
    if (!receivers.empty()) {
        const Rect r = projectBounds(a, receivers), f = projectFrusta(a, view);
        Rect overlap;
        overlap.lo = glm::max(r.lo, f.lo);
        overlap.hi = glm::min(r.hi, f.hi);
        if (!overlap.empty()) {
            const float fitted = 0.5f * std::max(overlap.hi.x - overlap.lo.x, overlap.hi.y - overlap.lo.y);
            const float margin = 1.0f + 16.0f / float(std::max(mapSize, 32u));  // 8 texels each side
            const float candidate = std::max(fitted * margin, 1e-5f);
            if (candidate < half) {
                half = candidate;
                centre = 0.5f * (overlap.lo + overlap.hi);
            }
        }
    }
    // Snap the centre to whole texels.
    const float texel = 2.0f * half / float(mapSize);
    centre = glm::round(centre / texel) * texel;

    ShadowFit fit;
    glm::mat4& m = fit.clipFromWorld;  // m[col][row]
    m = glm::mat4(0.0f);
    for (int i = 0; i < 3; ++i) {
        m[i][0] = a.right[i] / half;
        m[i][1] = a.up[i] / half;
        m[i][2] = a.forward[i] / (2.0f * sphereRadius);
    }
    m[3][0] = -centre.x / half;
    m[3][1] = -centre.y / half;
    m[3][2] = (sphereRadius - glm::dot(sphereCentre, a.forward)) / (2.0f * sphereRadius);
    m[3][3] = 1.0f;
    fit.texelSizeM = texel;
    fit.depthRangeM = 2.0f * sphereRadius;
    return fit;
}

}  // namespace preskin
