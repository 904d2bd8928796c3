// The camera one light grid is built for, for every eye of a view (see <preskin/ClusterGrid.h>):
// the eye itself for mono, a conservative enclosing perspective camera for several eyes.
#include <preskin/ClusterGrid.h>

#include <preskin/Error.h>

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace preskin {

namespace {

// The world-space points of an eye's near-plane corners (reversed Z: ndc depth 1 at the near
// plane), in the order (-1,-1), (1,-1), (-1,1), (1,1).
std::array<glm::dvec3, 4> nearCornersWs(const Eye& eye) {
    const glm::dmat4 worldFromClip = glm::inverse(glm::dmat4(eye.clipFromWorld()));
    std::array<glm::dvec3, 4> corners;
    for (int i = 0; i < 4; ++i) {
        const glm::dvec4 p = worldFromClip * glm::dvec4((i & 1) ? 1.0 : -1.0, (i & 2) ? 1.0 : -1.0, 1.0, 1.0);
        corners[size_t(i)] = glm::dvec3(p) / p.w;
    }
    return corners;
}

}  // namespace

glm::mat4 ClusterCamera::clusterFromWorld() const {
    const glm::mat4 clip = eye.clipFromWorld();
    glm::mat4 m(0.0f);
    for (int column = 0; column < 4; ++column) {
        m[column][0] = clip[column][0];
        m[column][1] = clip[column][1];
        m[column][2] = -eye.viewFromWorld[column][2];  // view depth = -z
        m[column][3] = clip[column][3];
    }
    return m;
}

ClusterCamera clusterCamera(const View& view, uint32_t eyeWidthPx, uint32_t eyeHeightPx) {
    if (view.eyes.empty()) throw Error("view: it has no eyes");
    ClusterCamera camera;
    const glm::uvec2 eyeExtent(std::max(eyeWidthPx, 1u), std::max(eyeHeightPx, 1u));
    if (view.eyes.size() == 1) {
        camera.eye = view.eyes[0];
        camera.extentPx = eyeExtent;
        return camera;
    }
    for (const Eye& e : view.eyes)
        if (e.orthographic()) throw Error("view: a view of several eyes needs perspective eyes");

    // The basis: the eyes' mean view direction and up.
    glm::dvec3 forward(0.0), up(0.0), center(0.0);
    for (const Eye& e : view.eyes) {
        const glm::dmat4 worldFromView = glm::inverse(glm::dmat4(e.viewFromWorld));
        forward -= glm::dvec3(worldFromView[2]);
        up += glm::dvec3(worldFromView[1]);
        center += glm::dvec3(e.positionWs);
    }
    center /= double(view.eyes.size());
    if (glm::length(forward) < 1e-9) throw Error("view: the eyes look in opposite directions");
    forward = glm::normalize(forward);
    glm::dvec3 right = glm::cross(forward, up);
    if (glm::length(right) < 1e-9) right = glm::cross(forward, std::abs(forward.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0));
    right = glm::normalize(right);
    up = glm::cross(right, forward);
    auto local = [&](const glm::dvec3& v) { return glm::dvec3(glm::dot(v, right), glm::dot(v, up), glm::dot(v, forward)); };

    // The tangents of every eye's edge directions (apex to near-plane corner), and the mean
    // direction (tangent 0) so that moving the apex back always works.
    double lo[2] = {0.0, 0.0};
    double hi[2] = {0.0, 0.0};
    for (const Eye& e : view.eyes)
        for (const glm::dvec3& corner : nearCornersWs(e)) {
            const glm::dvec3 d = local(corner - glm::dvec3(e.positionWs));
            if (!(d.z > 1e-6 * glm::length(d)))
                throw Error("view: the eyes' fields of view together span 180 degrees or more");
            for (int k = 0; k < 2; ++k) {
                lo[k] = std::min(lo[k], d[k] / d.z);
                hi[k] = std::max(hi[k], d[k] / d.z);
            }
        }
    for (int k = 0; k < 2; ++k) {
        const double margin = 1e-3 * (hi[k] - lo[k]) + 1e-6;
        lo[k] -= margin;
        hi[k] += margin;
    }

    // Move the apex back along the mean direction until every eye's apex is inside:
    // a.x <= hi.x (a.z + t) and a.x >= lo.x (a.z + t), likewise for y.
    double back = 0.0;
    for (const Eye& e : view.eyes) {
        const glm::dvec3 a = local(glm::dvec3(e.positionWs) - center);
        for (int k = 0; k < 2; ++k) back = std::max({back, a[k] / hi[k] - a.z, a[k] / lo[k] - a.z});
    }
    const glm::dvec3 apex = center - forward * back;

    double nearM = std::numeric_limits<double>::infinity();
    double farM = 0.0;
    for (const Eye& e : view.eyes) {
        for (const glm::dvec3& corner : nearCornersWs(e)) nearM = std::min(nearM, glm::dot(corner - apex, forward));
        farM = std::max(farM, double(e.farM) + glm::length(glm::dvec3(e.positionWs) - apex));
    }
    nearM = std::max(nearM * (1.0 - 1e-3), 1e-6);

    glm::dmat4 worldFromCamera(1.0);
    worldFromCamera[0] = glm::dvec4(right, 0.0);
    worldFromCamera[1] = glm::dvec4(up, 0.0);
    worldFromCamera[2] = glm::dvec4(-forward, 0.0);
    worldFromCamera[3] = glm::dvec4(apex, 1.0);
    const FovAngles fov{float(std::atan(lo[0])), float(std::atan(hi[0])), float(std::atan(hi[1])), float(std::atan(lo[1]))};
    camera.eye = perspectiveEye(glm::mat4(worldFromCamera), fov, float(nearM), float(std::max(farM, nearM * 4.0)));

    // Eye 0's pixels per unit of tangent.
    const FovAngles fov0 = fovOf(view.eyes[0]);
    const double span0[2] = {std::tan(double(fov0.right)) - std::tan(double(fov0.left)),
                             std::tan(double(fov0.up)) - std::tan(double(fov0.down))};
    for (int k = 0; k < 2; ++k) {
        const double pixels = std::ceil(double(eyeExtent[k]) * (hi[k] - lo[k]) / span0[k]);
        camera.extentPx[k] = uint32_t(std::clamp(pixels, 1.0, 65536.0));
    }
    return camera;
}

}  // namespace preskin
