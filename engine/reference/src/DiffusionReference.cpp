// The diffusion reference: primary rays through pixel centres, material lookups at the pixel's
// footprint, and the surface integral of the profile times the irradiance (see
// <preskin/DiffusionReference.h> and docs/reference.md).
#include <preskin/DiffusionReference.h>
#include <preskin/Error.h>

#include "IrradianceField.h"
#include "RayScene.h"
#include "ReferenceMaterials.h"
#include "ReferenceMesh.h"
#include "SurfaceIntegral.h"
#include "TracedEnvironment.h"

#include <fmt/core.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>

namespace preskin {
namespace {

constexpr double kPiD = 3.14159265358979323846;
// The renderer's clear colour (Renderer.cpp), so backgrounds look alike.
constexpr glm::vec3 kBackground(0.045f, 0.045f, 0.05f);

void checkSetting(double value, double lo, double hi, const char* field, bool openLow = false) {
    const bool ok = std::isfinite(value) && (openLow ? value > lo : value >= lo) && value <= hi;
    if (!ok)
        throw Error(fmt::format("ReferenceSettings.{}: must be in {}{}, {}], got {}", field, openLow ? "(" : "[", lo,
                                hi, value));
}

// Barycentric coordinates of q (in the triangle's plane) with respect to a, b, c.
glm::dvec3 barycentricOf(const glm::dvec3& q, const std::array<glm::dvec3, 3>& t) {
    const glm::dvec3 v0 = t[1] - t[0], v1 = t[2] - t[0], v2 = q - t[0];
    const double d00 = glm::dot(v0, v0), d01 = glm::dot(v0, v1), d11 = glm::dot(v1, v1);
    const double d20 = glm::dot(v2, v0), d21 = glm::dot(v2, v1);
    const double denom = d00 * d11 - d01 * d01;
    if (!(std::abs(denom) > 0.0)) return {1.0, 0.0, 0.0};
    const double v = (d11 * d20 - d01 * d21) / denom;
    const double w = (d00 * d21 - d01 * d20) / denom;
    return {1.0 - v - w, v, w};
}

// A visible point for the cast-shadow edge search: 0 not facing the shadow light (or
// background), 1 facing and lit, 2 facing and in a cast shadow; and whether it may lie in the
// terminator band (skin, its cosine to the shadow light within kTerminatorBandNoL).
struct EdgePoint {
    glm::dvec3 positionWs{0.0};
    double radiusM = 0.0;     // the cast-shadow edge radius (shadowEdgeWidths)
    double clearanceM = 0.0;  // the terminator band's clearance (terminatorClearanceMm)
    int state = 0;
    bool bandCandidate = false;
    int bandReachPx = 0;  // pixels a point within the clearance can lie from this one, at most
};

// Whether a visible point within radiusM of pixel (x, y)'s satisfies `found`, searched over the
// pixels up to reachPx away (exact in world space).
template <typename Found>
bool anyPointWithin(const std::vector<EdgePoint>& points, int w, int h, int x, int y, double radiusM, int reachPx,
                    Found found) {
    const EdgePoint& p = points[size_t(y) * size_t(w) + size_t(x)];
    for (int ny = std::max(0, y - reachPx); ny <= std::min(h - 1, y + reachPx); ++ny)
        for (int nx = std::max(0, x - reachPx); nx <= std::min(w - 1, x + reachPx); ++nx) {
            const EdgePoint& q = points[size_t(ny) * size_t(w) + size_t(nx)];
            if (found(q) && glm::length(q.positionWs - p.positionWs) <= radiusM) return true;
        }
    return false;
}

// The cast-shadow edge search's reach: the radius over the pixel footprint of the neighbours
// (the right or lower one, whichever is on a surface).
int edgeReachPx(const std::vector<EdgePoint>& points, int w, int h, int x, int y) {
    const EdgePoint& p = points[size_t(y) * size_t(w) + size_t(x)];
    double footprint = 0.0;
    for (const auto& [dx, dy] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}}) {
        const int nx = x + dx, ny = y + dy;
        if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
        const EdgePoint& q = points[size_t(ny) * size_t(w) + size_t(nx)];
        if (q.radiusM > 0.0) footprint = std::max(footprint, glm::length(q.positionWs - p.positionWs));
    }
    return footprint > 0.0 ? int(std::min(std::ceil(p.radiusM / footprint) + 1.0, 256.0)) : 1;
}

// Marks the pixels with a facing point of the other state within their edge radius
// (nearShadowEdge), and the terminator band's candidates with no point in a cast shadow within
// their clearance (terminatorBand).
void markShadowEdges(ReferenceImage& image, const std::vector<EdgePoint>& points) {
    const int w = int(image.width), h = int(image.height);
    tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y != rows.end(); ++y)
            for (int x = 0; x < w; ++x) {
                const size_t i = size_t(y) * size_t(w) + size_t(x);
                const EdgePoint& p = points[i];
                if (p.state != 0)
                    image.nearShadowEdge[i] =
                        anyPointWithin(points, w, h, x, y, p.radiusM, edgeReachPx(points, w, h, x, y),
                                       [&](const EdgePoint& q) { return q.state != 0 && q.state != p.state; });
                if (p.bandCandidate)
                    image.terminatorBand[i] = !anyPointWithin(points, w, h, x, y, p.clearanceM, p.bandReachPx,
                                                              [](const EdgePoint& q) { return q.state == 2; });
            }
    });
}

}  // namespace

using namespace reference;

struct DiffusionReference::Impl {
    ReferenceSettings settings;
    DiffusionProfile profile;
    ReferenceMesh mesh;
    ReferenceMaterials materials;
    std::unique_ptr<RayScene> rays;
    std::unique_ptr<IrradianceField> irradiance;
    std::unique_ptr<SurfaceIntegral> integral;
    double reachMm = 0.0;
    mutable tbb::enumerable_thread_specific<IrradianceCache> caches;

    std::unique_ptr<TracedEnvironment> traced;

    Impl(const Scene& scene, const std::vector<Light>& lights, const ShRgb& sh, const Environment* environment,
         const DiffusionProfile& p, const ReferenceSettings& s)
        : settings(s), profile(p), mesh(ReferenceMesh::fromScene(scene)), materials(scene) {
        if (s.environmentSamples > 0 && !environment)
            throw Error("ReferenceSettings: environmentSamples: tracing the environment needs the Environment");
        if (s.environmentSamples > (1u << 20))
            throw Error(
                fmt::format("ReferenceSettings: environmentSamples: {} is above {}", s.environmentSamples, 1u << 20));
        checkSetting(s.tailFraction, 1e-9, 0.1, "tailFraction");
        checkSetting(s.leafRatio, 0.0, 2.0, "leafRatio", true);
        checkSetting(s.finestLeafRatio, 0.0, 100.0, "finestLeafRatio", true);
        checkSetting(s.momentTolerance, 0.0, 1e-2, "momentTolerance", true);
        checkSetting(s.shadowEdgeWidths, 0.0, 100.0, "shadowEdgeWidths");
        checkSetting(s.terminatorClearanceMm, 0.0, 1000.0, "terminatorClearanceMm");
        reachMm = profile.reachMm(s.tailFraction);
        rays = std::make_unique<RayScene>(mesh, [this](uint32_t t, const glm::dvec3& bary, const glm::dvec3& dir) {
            return acceptHit(t, bary, dir);
        });
        if (s.environmentSamples > 0) traced = std::make_unique<TracedEnvironment>(*environment, s.environmentSamples);
        irradiance = std::make_unique<IrradianceField>(mesh, *rays, materials, lights, sh, s.shadows, traced.get());
        SurfaceIntegralSettings is;
        is.reachMm = reachMm;
        is.leafRatio = s.leafRatio;
        is.finestMm = s.finestLeafRatio * profile.narrowestScaleMm();
        is.momentTolerance = s.momentTolerance;
        integral = std::make_unique<SurfaceIntegral>(
            mesh, *rays, *irradiance, [this](uint32_t t) { return materials.isSkin(mesh.triangles[t].material); },
            [this](uint32_t t) { return materials.material(mesh.triangles[t].material).doubleSided; }, profile, is);
    }

    // What the rasterizer would not draw: culled back faces and alpha-masked texels.
    bool acceptHit(uint32_t triangle, const glm::dvec3& bary, const glm::dvec3& direction) const {
        const uint32_t m = mesh.triangles[triangle].material;
        if (!materials.material(m).doubleSided && glm::dot(mesh.faceNormal(triangle), direction) >= 0.0) return false;
        return materials.covers(m, mesh.uv({triangle, bary}));
    }

    ReferenceSample shade(const RayHit& hit, const glm::dvec3& direction, const UvFootprint& footprint) const {
        const SurfacePoint& p = hit.point;
        const uint32_t m = mesh.triangles[p.triangle].material;
        const bool flip = glm::dot(mesh.faceNormal(p.triangle), direction) > 0.0;  // back of a double-sided face
        ReferenceSample out;
        out.positionWs = mesh.position(p);
        out.normalWs = flip ? -mesh.normal(p) : mesh.normal(p);
        const glm::dvec3 base(materials.baseColor(m, footprint));
        const Material& material = materials.material(m);
        if (material.skin) {
            const double scatterScale = std::max(double(material.skin->scatterScale), 1e-6);
            const SurfaceIntegralResult r =
                integral->integrate(out.positionWs, 1000.0 * scatterScale, flip, caches.local());
            out.radiance = base / kPiD * r.value;
            out.skin = true;
            out.curvaturePerMm = (flip ? -1.0 : 1.0) * mesh.curvature(p) * 0.001 / scatterScale;
            out.irradianceSamples = r.irradianceSamples;
        }
        const IrradianceSample atX = irradiance->at(p, flip);
        if (!material.skin) {
            const glm::dvec3 diffuse = base * (1.0 - materials.metallic(m, footprint));
            out.radiance = diffuse / kPiD * atX.irradiance;
        }
        out.facesShadowLight = atX.shadow != ShadowState::NotFacing;
        out.inCastShadow = atX.shadow == ShadowState::CastShadow;
        out.shadowLightNoL = irradiance->shadowLightCosine(p, flip);
        ++out.irradianceSamples;
        out.radiance += materials.emissive(m, footprint);
        return out;
    }
};

DiffusionReference::DiffusionReference(const Scene& scene, const std::vector<Light>& lights, const ShRgb& radianceSh,
                                       const DiffusionProfile& profile, const ReferenceSettings& settings)
    : impl_(std::make_unique<Impl>(scene, lights, radianceSh, nullptr, profile, settings)) {}

DiffusionReference::DiffusionReference(const Scene& scene, const std::vector<Light>& lights,
                                       const Environment& environment, const DiffusionProfile& profile,
                                       const ReferenceSettings& settings)
    : impl_(std::make_unique<Impl>(scene, lights, environment.radianceSh(), &environment, profile, settings)) {}

DiffusionReference::~DiffusionReference() = default;

double DiffusionReference::reachMm() const { return impl_->reachMm; }

std::optional<ReferenceSample> DiffusionReference::trace(const glm::dvec3& originWs,
                                                         const glm::dvec3& directionWs) const {
    const glm::dvec3 dir = glm::normalize(directionWs);
    const auto hit = impl_->rays->intersect(originWs, dir);
    if (!hit) return std::nullopt;
    return impl_->shade(*hit, dir, UvFootprint{impl_->mesh.uv(hit->point), glm::dvec2(0.0), glm::dvec2(0.0)});
}

ReferenceImage DiffusionReference::render(const Eye& eye, uint32_t width, uint32_t height, float exposure,
                                          const ReferenceProgress& progress) const {
    if (width == 0 || height == 0 || width > 16384 || height > 16384)
        throw Error(fmt::format("image size: {}x{} is outside 1..16384 pixels per side", width, height));
    const Impl& im = *impl_;
    const glm::dmat4 worldFromClip = glm::inverse(glm::dmat4(eye.clipFromWorld()));
    auto unproject = [&](double px, double py, double depth) {
        const glm::dvec4 p = worldFromClip * glm::dvec4(2.0 * px / width - 1.0, 2.0 * py / height - 1.0, depth, 1.0);
        return glm::dvec3(p) / p.w;
    };
    // The ray through a pixel position (pixel centres at +0.5): from the near plane (depth 1,
    // reversed Z) towards depth 0.5 (twice the near distance, or half way for orthographic).
    auto ray = [&](double px, double py, glm::dvec3& origin, glm::dvec3& direction) {
        origin = unproject(px, py, 1.0);
        direction = glm::normalize(unproject(px, py, 0.5) - origin);
    };

    ReferenceImage image;
    image.width = width;
    image.height = height;
    const size_t count = size_t(width) * height;
    image.rgba32f.assign(count * 4, 0.0f);
    image.skin.assign(count, 0);
    image.curvaturePerMm.assign(count, 0.0f);
    image.nearShadowEdge.assign(count, 0);
    image.terminatorBand.assign(count, 0);
    std::vector<uint64_t> rowSamples(height, 0);
    std::vector<EdgePoint> points(count);
    auto worldMPerProfileMm = [&](const RayHit& hit) {
        const Material& material = im.materials.material(im.mesh.triangles[hit.point.triangle].material);
        return 1e-3 / (material.skin ? std::max(double(material.skin->scatterScale), 1e-6) : 1.0);
    };
    std::atomic<uint32_t> rowsDone{0};
    std::mutex progressMutex;
    uint32_t reported = 0;

    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, height, 1), [&](const tbb::blocked_range<uint32_t>& rows) {
        for (uint32_t y = rows.begin(); y != rows.end(); ++y) {
            for (uint32_t x = 0; x < width; ++x) {
                const size_t i = size_t(y) * width + x;
                glm::dvec3 origin, direction;
                ray(x + 0.5, y + 0.5, origin, direction);
                const auto hit = im.rays->intersect(origin, direction);
                if (!hit) {
                    for (int c = 0; c < 3; ++c) image.rgba32f[4 * i + size_t(c)] = kBackground[c];
                    continue;
                }
                // The pixel's footprint in TEXCOORD_0 as GPUs take it: coarse derivatives of
                // its 2x2 quad (the quad's top-left pixel and its right and lower neighbours),
                // with the rays of those pixel centres met with the hit triangle's plane.
                const auto corners = im.mesh.corners(hit->point.triangle);
                const glm::dvec3 faceNormal = im.mesh.faceNormal(hit->point.triangle);
                const glm::dvec2 uv = im.mesh.uv(hit->point);
                auto uvAt = [&](double px, double py) {
                    glm::dvec3 o, d;
                    ray(px, py, o, d);
                    const double denom = glm::dot(d, faceNormal);
                    if (!(std::abs(denom) > 1e-12)) return uv;
                    const glm::dvec3 q = o + d * (glm::dot(corners[0] - o, faceNormal) / denom);
                    return im.mesh.uv({hit->point.triangle, barycentricOf(q, corners)});
                };
                const double qx = double(x & ~1u) + 0.5, qy = double(y & ~1u) + 0.5;
                const glm::dvec2 quadUv = uvAt(qx, qy);
                const UvFootprint footprint{uv, uvAt(qx + 1.0, qy) - quadUv, uvAt(qx, qy + 1.0) - quadUv};
                const ReferenceSample s = im.shade(*hit, direction, footprint);
                for (int c = 0; c < 3; ++c) image.rgba32f[4 * i + size_t(c)] = float(s.radiance[c] * double(exposure));
                image.rgba32f[4 * i + 3] = 1.0f;
                image.skin[i] = s.skin ? 1 : 0;
                image.curvaturePerMm[i] = float(s.curvaturePerMm);
                rowSamples[y] += s.irradianceSamples;
                const double toM = worldMPerProfileMm(*hit);
                EdgePoint& e = points[i];
                e = {s.positionWs, im.settings.shadowEdgeWidths * im.profile.maxWidthMm() * toM,
                     im.settings.terminatorClearanceMm * toM, s.facesShadowLight ? (s.inCastShadow ? 2 : 1) : 0,
                     s.skin && s.shadowLightNoL && *s.shadowLightNoL >= kTerminatorBandNoL[0] &&
                         *s.shadowLightNoL <= kTerminatorBandNoL[1]};
                if (e.bandCandidate) {
                    // A point within the clearance lies no nearer along the ray than the hit less the
                    // clearance, where neighbouring pixels' rays are closest: at most the clearance
                    // over that spacing pixels away on the screen, however the surface turns.
                    const double nearest = std::max(glm::length(s.positionWs - origin) - e.clearanceM, 0.0);
                    double spacing = std::numeric_limits<double>::infinity();
                    for (const auto& [dx, dy] : {std::pair{1.5, 0.5}, std::pair{0.5, 1.5}}) {
                        glm::dvec3 o, d;
                        ray(x + dx, y + dy, o, d);
                        spacing = std::min(spacing, glm::length(o + d * nearest - (origin + direction * nearest)));
                    }
                    e.bandReachPx = spacing > 0.0
                        ? int(std::min(std::ceil(e.clearanceM / spacing) + 1.0, double(width + height)))
                        : int(width + height);
                }
            }
            const uint32_t done = rowsDone.fetch_add(1) + 1;
            if (progress) {
                std::lock_guard lock(progressMutex);
                if (done > reported) {
                    reported = done;
                    progress(double(done) / height);
                }
            }
        }
    });
    for (uint64_t s : rowSamples) image.irradianceSamples += s;
    markShadowEdges(image, points);
    return image;
}

}  // namespace preskin
