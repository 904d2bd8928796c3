// Embree 3 ray queries for the diffusion reference (see RayScene.h).
#include "RayScene.h"

#include <preskin/Error.h>

#include <embree3/rtcore.h>
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace preskin::reference {
namespace {

RTCDevice device(void* d) { return static_cast<RTCDevice>(d); }
RTCScene scene(void* s) { return static_cast<RTCScene>(s); }

void checkDevice(RTCDevice d, const char* what) {
    const RTCError e = rtcGetDeviceError(d);
    if (e != RTC_ERROR_NONE) throw Error(fmt::format("Embree: {}: error {}", what, static_cast<int>(e)));
}

// Intersection filter of the closest-hit query: asks the RayScene's HitFilter.
void intersectFilter(const RTCFilterFunctionNArguments* args) {
    const auto* self = static_cast<const RayScene*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const uint32_t primitive = RTCHitN_primID(args->hit, args->N, i);
        const double u = RTCHitN_u(args->hit, args->N, i);
        const double v = RTCHitN_v(args->hit, args->N, i);
        const glm::dvec3 dir(RTCRayN_dir_x(args->ray, args->N, i), RTCRayN_dir_y(args->ray, args->N, i),
                             RTCRayN_dir_z(args->ray, args->N, i));
        if (!self->filter()(primitive, glm::dvec3(1.0 - u - v, u, v), dir)) args->valid[i] = 0;
    }
}

struct PointQueryState {
    const RayScene* self;
    const std::function<bool(uint32_t)>* keep;
    glm::dvec3 point;
    double radius;
    std::vector<uint32_t>* out;
};

bool pointQueryCallback(RTCPointQueryFunctionArguments* args) {
    auto* state = static_cast<PointQueryState*>(args->userPtr);
    const uint32_t t = args->primID;
    if (!(*state->keep)(t)) return false;
    const auto c = state->self->mesh().corners(t);
    if (pointTriangleDistance(state->point, c[0], c[1], c[2]) <= state->radius) state->out->push_back(t);
    return false;  // the query radius stays
}

}  // namespace

double pointTriangleDistance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0.0 && d2 <= 0.0) return glm::length(ap);
    const glm::dvec3 bp = p - b;
    const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0.0 && d4 <= d3) return glm::length(bp);
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return glm::length(p - (a + ab * (d1 / (d1 - d3))));
    const glm::dvec3 cp = p - c;
    const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0.0 && d5 <= d6) return glm::length(cp);
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return glm::length(p - (a + ac * (d2 / (d2 - d6))));
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0)
        return glm::length(p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))));
    const double sum = va + vb + vc;
    if (!(sum > 0.0)) return std::min({glm::length(ap), glm::length(bp), glm::length(cp)});  // degenerate
    return glm::length(p - (a + ab * (vb / sum) + ac * (vc / sum)));
}

RayScene::RayScene(const ReferenceMesh& mesh, HitFilter filter) : mesh_(mesh), filter_(std::move(filter)) {
    RTCDevice d = rtcNewDevice("set_affinity=0");
    if (!d)
        throw Error(
            fmt::format("Embree: cannot create a device: error {}", static_cast<int>(rtcGetDeviceError(nullptr))));
    device_ = d;
    RTCScene s = rtcNewScene(d);
    scene_ = s;
    rtcSetSceneFlags(s, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(s, RTC_BUILD_QUALITY_HIGH);
    if (!mesh.triangles.empty()) {
        RTCGeometry g = rtcNewGeometry(d, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                     3 * sizeof(float), mesh.positionsWs.size()));
        auto* indices = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                       3 * sizeof(uint32_t), mesh.triangles.size()));
        checkDevice(d, "geometry buffers");
        for (size_t i = 0; i < mesh.positionsWs.size(); ++i)
            for (int k = 0; k < 3; ++k) vertices[3 * i + size_t(k)] = static_cast<float>(mesh.positionsWs[i][k]);
        for (size_t i = 0; i < mesh.triangles.size(); ++i)
            for (int k = 0; k < 3; ++k) indices[3 * i + size_t(k)] = mesh.triangles[i].v[size_t(k)];
        rtcSetGeometryUserData(g, this);
        rtcSetGeometryIntersectFilterFunction(g, intersectFilter);
        rtcCommitGeometry(g);
        rtcAttachGeometry(s, g);
        rtcReleaseGeometry(g);
    }
    rtcCommitScene(s);
    checkDevice(d, "scene build");
}

RayScene::~RayScene() {
    if (scene_) rtcReleaseScene(scene(scene_));
    if (device_) rtcReleaseDevice(device(device_));
}

std::optional<RayHit> RayScene::intersect(const glm::dvec3& origin, const glm::dvec3& direction) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh{};
    rh.ray.org_x = float(origin.x);
    rh.ray.org_y = float(origin.y);
    rh.ray.org_z = float(origin.z);
    rh.ray.dir_x = float(direction.x);
    rh.ray.dir_y = float(direction.y);
    rh.ray.dir_z = float(direction.z);
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = std::numeric_limits<float>::infinity();
    rh.ray.mask = 0xffffffffu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene(scene_), &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
    RayHit hit;
    hit.point.triangle = rh.hit.primID;
    const double u = rh.hit.u, v = rh.hit.v;
    hit.point.bary = glm::dvec3(1.0 - u - v, u, v);
    hit.distance = rh.ray.tfar;
    return hit;
}

bool RayScene::occluded(const glm::dvec3& origin, const glm::dvec3& direction, double tNear, double tFar) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray{};
    ray.org_x = float(origin.x);
    ray.org_y = float(origin.y);
    ray.org_z = float(origin.z);
    ray.dir_x = float(direction.x);
    ray.dir_y = float(direction.y);
    ray.dir_z = float(direction.z);
    ray.tnear = float(tNear);
    ray.tfar = std::isfinite(tFar) ? float(tFar) : std::numeric_limits<float>::infinity();
    ray.mask = 0xffffffffu;
    rtcOccluded1(scene(scene_), &context, &ray);
    return ray.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

void RayScene::trianglesWithin(const glm::dvec3& p, double radius, const std::function<bool(uint32_t)>& keep,
                               std::vector<uint32_t>& out) const {
    out.clear();
    RTCPointQuery query{};
    query.x = float(p.x);
    query.y = float(p.y);
    query.z = float(p.z);
    query.radius = float(radius * (1.0 + 1e-6)) + 1e-12f;  // float rounding must not drop a triangle
    query.time = 0.0f;
    RTCPointQueryContext context;
    rtcInitPointQueryContext(&context);
    PointQueryState state{this, &keep, p, radius, &out};
    rtcPointQuery(scene(scene_), &query, &context, pointQueryCallback, &state);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
}

}  // namespace preskin::reference
