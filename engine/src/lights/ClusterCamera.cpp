// The camera one light grid is built for, for every eye of a view (see <preskin/ClusterGrid.h>):
// the eye itself for mono, a conservative enclosing perspective camera for several eyes.
#include <preskin/ClusterGrid.h>

#include <preskin/Error.h>

#include "view/Projection.h"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace preskin {

namespace {

// An eye's frustum as the light grid needs it: apex, the world directions of its four edge rays
// scaled to unit view depth, and its near depth. From the eye's matrices without inverting a 4x4.
struct EyeFrustum {
    glm::dvec3 apex;
    std::array<glm::dvec3, 4> edges;  // (left, down), (right, down), (left, up), (right, up)
    double nearM;
};

EyeFrustum eyeFrustum(const Eye& eye) {
    const glm::dmat3 worldFromView = glm::inverse(glm::dmat3(glm::mat3(eye.viewFromWorld)));
    const glm::dvec4 t(perspectiveTangents(eye.clipFromView));  // left, right, up, down
    EyeFrustum f{glm::dvec3(eye.positionWs), {}, double(eye.nearM)};
    for (int i = 0; i < 4; ++i)
        f.edges[size_t(i)] = worldFromView * glm::dvec3((i & 1) ? t.y : t.x, (i & 2) ? t.z : t.w, -1.0);
    return f;
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
    for (const Eye& e : view.eyes)
        camera.viewpoints.push_back(e.orthographic()
                                        ? glm::vec4(glm::normalize(glm::vec3(glm::inverse(e.viewFromWorld)[2])), 0.0f)
                                        : glm::vec4(e.positionWs, 1.0f));
    const glm::uvec2 eyeExtent(std::max(eyeWidthPx, 1u), std::max(eyeHeightPx, 1u));
    if (view.eyes.size() == 1) {
        camera.eye = view.eyes[0];
        camera.extentPx = eyeExtent;
        return camera;
    }
    for (const Eye& e : view.eyes)
        if (e.orthographic()) throw Error("view: a view of several eyes needs perspective eyes");

    if (view.eyes.size() > kMaxEyes) throw Error(fmt::format("view: {} eyes (at most {})", view.eyes.size(), kMaxEyes));
    std::array<EyeFrustum, kMaxEyes> frusta;
    const size_t eyes = view.eyes.size();
    for (size_t e = 0; e < eyes; ++e) frusta[e] = eyeFrustum(view.eyes[e]);

    // The basis: the eyes' mean view direction and up.
    glm::dvec3 forward(0.0), up(0.0), center(0.0);
    for (size_t e = 0; e < eyes; ++e) {
        const EyeFrustum& f = frusta[e];
        forward += glm::normalize(f.edges[0] + f.edges[1] + f.edges[2] + f.edges[3]);
        up += glm::normalize((f.edges[2] + f.edges[3]) - (f.edges[0] + f.edges[1]));
        center += f.apex;
    }
    center /= double(eyes);
    if (glm::length(forward) < 1e-9) throw Error("view: the eyes look in opposite directions");
    forward = glm::normalize(forward);
    glm::dvec3 right = glm::cross(forward, up);
    if (glm::length(right) < 1e-9)
        right = glm::cross(forward, std::abs(forward.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0));
    right = glm::normalize(right);
    up = glm::cross(right, forward);
    auto local = [&](const glm::dvec3& v) {
        return glm::dvec3(glm::dot(v, right), glm::dot(v, up), glm::dot(v, forward));
    };

    // The tangents of every eye's edge directions, and the mean direction (tangent 0) so that
    // moving the apex back always works.
    double lo[2] = {0.0, 0.0};
    double hi[2] = {0.0, 0.0};
    for (size_t e = 0; e < eyes; ++e)
        for (const glm::dvec3& edge : frusta[e].edges) {
            const glm::dvec3 d = local(edge);
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
    for (size_t e = 0; e < eyes; ++e) {
        const glm::dvec3 a = local(frusta[e].apex - center);
        for (int k = 0; k < 2; ++k) back = std::max({back, a[k] / hi[k] - a.z, a[k] / lo[k] - a.z});
    }
    const glm::dvec3 apex = center - forward * back;

    double nearM = std::numeric_limits<double>::infinity();
    double farM = 0.0;
    for (size_t e = 0; e < eyes; ++e) {
        const EyeFrustum& f = frusta[e];
        for (const glm::dvec3& edge : f.edges)
            nearM = std::min(nearM, glm::dot(f.apex + edge * f.nearM - apex, forward));
        farM = std::max(farM, double(view.eyes[e].farM) + glm::length(f.apex - apex));
    }
    nearM = std::max(nearM * (1.0 - 1e-3), 1e-6);

    // The camera: right, up, -forward as its axes, at the apex.
    glm::mat4 viewFromWorld(1.0f);
    for (int i = 0; i < 3; ++i) {
        viewFromWorld[i][0] = float(right[i]);
        viewFromWorld[i][1] = float(up[i]);
        viewFromWorld[i][2] = float(-forward[i]);
    }
    viewFromWorld[3] =
        glm::vec4(float(-glm::dot(right, apex)), float(-glm::dot(up, apex)), float(glm::dot(forward, apex)), 1.0f);
    camera.eye.viewFromWorld = viewFromWorld;
    camera.eye.clipFromView =
        reversedInfinitePerspective(float(lo[0]), float(hi[0]), float(hi[1]), float(lo[1]), float(nearM));
    camera.eye.positionWs = glm::vec3(apex);
    camera.eye.nearM = float(nearM);
    camera.eye.farM = float(std::max(farM, nearM * 4.0));

    // Eye 0's pixels per unit of tangent.
    const glm::dvec4 t0(perspectiveTangents(view.eyes[0].clipFromView));
    const double span0[2] = {t0.y - t0.x, t0.z - t0.w};
    for (int k = 0; k < 2; ++k) {
        const double pixels = std::ceil(double(eyeExtent[k]) * (hi[k] - lo[k]) / span0[k]);
        camera.extentPx[k] = uint32_t(std::clamp(pixels, 1.0, 65536.0));
    }
    return camera;
}

}  // namespace preskin
