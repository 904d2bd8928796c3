// Area light outlines over the viewport (see LightGizmos.h).
#include "LightGizmos.h"

#include <preskin/LightRecord.h>

#include <imgui.h>

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <optional>

namespace preskin::viewer {

namespace {

constexpr ImU32 kColor = IM_COL32(255, 214, 120, 220);

struct Projector {
    glm::mat4 clipFromWorld;
    float width;
    float height;

    // Pixel position of a world point, or nothing behind the eye.
    std::optional<ImVec2> operator()(const glm::vec3& p) const {
        const glm::vec4 c = clipFromWorld * glm::vec4(p, 1.0f);
        if (!(c.w > 1e-6f)) return std::nullopt;
        return ImVec2((c.x / c.w * 0.5f + 0.5f) * width, (c.y / c.w * 0.5f + 0.5f) * height);
    }

    void polyline(ImDrawList* draw, const std::vector<glm::vec3>& points, bool closed) const {
        std::vector<ImVec2> px;
        for (const glm::vec3& p : points) {
            const auto q = (*this)(p);
            if (!q) return;  // partly behind the eye: not drawn
            px.push_back(*q);
        }
        draw->AddPolyline(px.data(), int(px.size()), kColor, closed ? ImDrawFlags_Closed : ImDrawFlags_None, 1.5f);
    }

    // A circle of radius r about c in the plane of the unit axes a and b.
    void circle(ImDrawList* draw, const glm::vec3& c, const glm::vec3& a, const glm::vec3& b, float r) const {
        std::vector<glm::vec3> points;
        for (int i = 0; i < 32; ++i) {
            const float t = glm::two_pi<float>() * float(i) / 32.0f;
            points.push_back(c + r * (std::cos(t) * a + std::sin(t) * b));
        }
        polyline(draw, points, true);
    }
};

}  // namespace

void drawAreaLightGizmos(const std::vector<Light>& lights, const Eye& eye, float widthPx, float heightPx) {
    ImDrawList* draw = ImGui::GetBackgroundDrawList();
    const Projector project{eye.clipFromWorld(), widthPx, heightPx};
    const glm::vec3 eyePosition = eye.positionWs;
    for (const Light& l : lights) {
        if (!isAreaLight(l.type)) continue;
        const AreaLightAxes axes = areaLightAxes(l);
        const glm::vec3 c = l.positionWs;
        // The plane facing the eye, for spheres and tube ends.
        const glm::vec3 toEye = glm::length(eyePosition - c) > 0.0f ? glm::normalize(eyePosition - c) : axes.normal;
        glm::vec3 right = glm::cross(toEye, glm::vec3(0.0f, 1.0f, 0.0f));
        right = glm::length(right) > 1e-4f ? glm::normalize(right) : glm::vec3(1.0f, 0.0f, 0.0f);
        const glm::vec3 up = glm::cross(right, toEye);
        const float facingLength = 0.5f * std::max({l.radius, l.width, l.height});
        switch (l.type) {
        case LightType::Sphere: project.circle(draw, c, right, up, l.radius); break;
        case LightType::Tube: {
            const glm::vec3 half = axes.width * (0.5f * l.length);
            glm::vec3 side = glm::cross(axes.width, toEye);
            side = glm::length(side) > 1e-4f ? glm::normalize(side) * l.radius : right * l.radius;
            project.circle(draw, c - half, right, up, l.radius);
            project.circle(draw, c + half, right, up, l.radius);
            project.polyline(draw, {c - half + side, c + half + side}, false);
            project.polyline(draw, {c - half - side, c + half - side}, false);
            break;
        }
        case LightType::Rectangle: {
            const glm::vec3 u = axes.width * (0.5f * l.width), v = axes.height * (0.5f * l.height);
            project.polyline(draw, {c - u - v, c + u - v, c + u + v, c - u + v}, true);
            project.polyline(draw, {c, c + axes.normal * facingLength}, false);
            break;
        }
        case LightType::Disc:
            project.circle(draw, c, axes.width, axes.height, l.radius);
            project.polyline(draw, {c, c + axes.normal * facingLength}, false);
            break;
        default: break;
        }
    }
}

}  // namespace preskin::viewer
