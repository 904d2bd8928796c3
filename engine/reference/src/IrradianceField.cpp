// Irradiance at surface points for the diffusion reference (see IrradianceField.h).
#include "IrradianceField.h"
#include "AreaLightIrradiance.h"
#include "PointHash.h"

#include <preskin/LightRecord.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace preskin::reference {

void lightIncidence(const gpu::GpuLight& light, const glm::dvec3& positionWs, glm::dvec3& L, glm::dvec3& irradiance) {
    const uint32_t type = uint32_t(light.directionType.w);
    const glm::dvec3 color(light.colorIntensity);
    if (type == gpu::kLightDirectional) {
        L = -glm::dvec3(light.directionType);
        irradiance = color;
        return;
    }
    const glm::dvec3 toLight = glm::dvec3(light.positionRange) - positionWs;
    const double d2 = std::max(glm::dot(toLight, toLight), 1e-8);
    L = toLight / std::sqrt(d2);
    double attenuation = 1.0 / d2;
    const double range = light.positionRange.w;
    if (range > 0.0) {
        const double r = d2 / (range * range);
        const double window = std::clamp(1.0 - r * r, 0.0, 1.0);
        attenuation *= window * window;
    }
    if (type == gpu::kLightSpot) {
        const double cd = glm::dot(glm::dvec3(light.directionType), -L);
        const double a = std::clamp(cd * double(light.spotScaleOffset.x) + double(light.spotScaleOffset.y), 0.0, 1.0);
        attenuation *= a * a;
    }
    irradiance = color * attenuation;
}

IrradianceField::IrradianceField(const ReferenceMesh& mesh, const RayScene& rays, const ReferenceMaterials& materials,
                                 const std::vector<Light>& lights, const ShRgb& radianceSh, bool shadows,
                                 const TracedEnvironment* traced)
    : mesh_(mesh), rays_(rays), materials_(materials), radianceSh_(radianceSh), traced_(traced) {
    const int shadowLight = shadows ? shadowLightIndex(lights) : -1;
    for (size_t i = 0; i < lights.size(); ++i) {
        if (int(i) == shadowLight) shadowLight_ = int(lights_.size());
        lights_.push_back(toGpuLight(lights[i], int(i) == shadowLight));
        sceneLights_.push_back(lights[i]);
    }
    if (!traced_) return;
    // Rays leave each vertex a thousandth of its longest edge off the surface.
    std::vector<double> edge(mesh_.positionsWs.size(), 0.0);
    for (const MeshTriangle& t : mesh_.triangles)
        for (int k = 0; k < 3; ++k) {
            const double l =
                glm::length(mesh_.positionsWs[t.v[size_t(k)]] - mesh_.positionsWs[t.v[size_t((k + 1) % 3)]]);
            edge[t.v[size_t(k)]] = std::max(edge[t.v[size_t(k)]], l);
            edge[t.v[size_t((k + 1) % 3)]] = std::max(edge[t.v[size_t((k + 1) % 3)]], l);
        }
    vertexAmbient_.assign(mesh_.positionsWs.size(), glm::dvec3(0.0));
    tbb::parallel_for(tbb::blocked_range<size_t>(0, vertexAmbient_.size(), 16), [&](const auto& range) {
        for (size_t v = range.begin(); v != range.end(); ++v) {
            const glm::dvec3 n = mesh_.normalsWs[v];
            if (!(glm::dot(n, n) > 0.0)) continue;
            vertexAmbient_[v] = traced_->irradiance(rays_, mesh_.positionsWs[v] + n * (1e-3 * edge[v]), n, uint64_t(v));
        }
    });
}

glm::dvec3 IrradianceField::shadowRayOrigin(const SurfacePoint& p, const glm::dvec3& normal, bool flipNormal) const {
    const MeshTriangle& t = mesh_.triangles[p.triangle];
    const glm::dvec3 position = mesh_.position(p);
    const double sign = flipNormal ? -1.0 : 1.0;
    glm::dvec3 lifted = position;
    double longestEdge = 0.0;
    for (int k = 0; k < 3; ++k) {
        const glm::dvec3& corner = mesh_.positionsWs[t.v[size_t(k)]];
        const glm::dvec3 n = sign * mesh_.normalsWs[t.v[size_t(k)]];
        lifted -= p.bary[k] * std::min(0.0, glm::dot(position - corner, n)) * n;
        longestEdge = std::max(longestEdge, glm::length(mesh_.positionsWs[t.v[size_t((k + 1) % 3)]] - corner));
    }
    glm::dvec3 face = mesh_.faceNormal(p.triangle);
    if (glm::dot(face, normal) < 0.0) face = -face;
    const double magnitude = std::max({std::abs(lifted.x), std::abs(lifted.y), std::abs(lifted.z)});
    return lifted + face * (1e-4 * longestEdge + 1e-6 * magnitude);
}

glm::dvec3 IrradianceField::sunIrradiance(const Light& light, const SurfacePoint& p, const glm::dvec3& n,
                                          bool flipNormal, ShadowState& shadow) const {
    // The cap's directions uniform in solid angle, k x k strata of (cos theta, phi), jittered per
    // point (a hash of the point, so the error is noise the profile's integral averages).
    constexpr int k = 8;
    const double sigma = double(light.angularRadius), cosSigma = std::cos(sigma), s = std::sin(sigma);
    const glm::dvec3 axis = -glm::normalize(glm::dvec3(light.directionWs));
    const glm::dvec3 e1 = glm::normalize(
        glm::cross(axis, std::abs(axis.x) < 0.9 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 1.0, 0.0)));
    const glm::dvec3 e2 = glm::cross(axis, e1);
    const glm::dvec3 origin = shadowRayOrigin(p, n, flipNormal);
    uint64_t state = pointKey(p);
    const auto uniform = [&state] {  // the SplitMix64 sequence from the point's key
        const double u = unitInterval(splitMix64(state));
        state += 0x9E3779B97F4A7C15ull;
        return u;
    };
    const double solidAngle = 2.0 * std::numbers::pi * (1.0 - cosSigma);
    double visible = 0.0, facing = 0.0;
    for (int a = 0; a < k; ++a)
        for (int b = 0; b < k; ++b) {
            const double cosTheta = 1.0 - (1.0 - cosSigma) * (a + uniform()) / k;
            const double phi = 2.0 * std::numbers::pi * (b + uniform()) / k;
            const double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
            const glm::dvec3 w = cosTheta * axis + sinTheta * (std::cos(phi) * e1 + std::sin(phi) * e2);
            const double cosine = glm::dot(n, w);
            if (!(cosine > 0.0)) continue;
            facing += cosine;
            if (!rays_.occluded(origin, w, 0.0, std::numeric_limits<double>::infinity())) visible += cosine;
        }
    if (!(facing > 0.0)) return glm::dvec3(0.0);
    shadow = visible >= 0.5 * facing ? ShadowState::Lit : ShadowState::CastShadow;
    const double radiance = 1.0 / (std::numbers::pi * s * s);
    return glm::dvec3(light.color) * double(light.intensity) * (radiance * visible * solidAngle / (k * k));
}

std::optional<double> IrradianceField::shadowLightCosine(const SurfacePoint& p, bool flipNormal) const {
    if (shadowLight_ < 0) return std::nullopt;
    glm::dvec3 L, irradiance;
    lightIncidence(lights_[size_t(shadowLight_)], mesh_.position(p), L, irradiance);
    return glm::dot(flipNormal ? -mesh_.normal(p) : mesh_.normal(p), L);
}

IrradianceSample IrradianceField::at(const SurfacePoint& p, bool flipNormal) const {
    IrradianceSample out;
    const glm::dvec3 position = mesh_.position(p);
    glm::dvec3 n = mesh_.normal(p);
    if (flipNormal) n = -n;
    for (size_t i = 0; i < lights_.size(); ++i) {
        const Light& light = sceneLights_[i];
        const bool sun = light.type == LightType::Directional && light.angularRadius > 0.0f;
        if (sun && int(i) == shadowLight_) {
            out.irradiance += sunIrradiance(light, p, n, flipNormal, out.shadow);
            continue;
        }
        if (isAreaLight(light.type) || sun) {
            out.irradiance += areaLightIrradiance(light, position, n);
            continue;
        }
        glm::dvec3 L, irradiance;
        lightIncidence(lights_[i], position, L, irradiance);
        const double NoL = glm::dot(n, L);
        if (!(NoL > 0.0)) continue;
        if (int(i) == shadowLight_) {
            if (rays_.occluded(shadowRayOrigin(p, n, flipNormal), L, 0.0, std::numeric_limits<double>::infinity())) {
                out.shadow = ShadowState::CastShadow;
                continue;
            }
            out.shadow = ShadowState::Lit;
        }
        out.irradiance += irradiance * NoL;
    }
    if (traced_) {
        const MeshTriangle& t = mesh_.triangles[p.triangle];
        if (!flipNormal) {
            for (int k = 0; k < 3; ++k) out.irradiance += p.bary[k] * vertexAmbient_[t.v[size_t(k)]];
        } else {  // the back of a double-sided surface: traced at the point itself
            out.irradiance += traced_->irradiance(rays_, shadowRayOrigin(p, n, flipNormal), n, pointKey(p));
        }
        return out;
    }
    const glm::dvec3 ambient =
        glm::max(glm::dvec3(evaluateSh(radianceSh_, glm::vec3(n), kLambertBands)), glm::dvec3(0.0));
    const uint32_t material = mesh_.triangles[p.triangle].material;
    out.irradiance +=
        ambient * materials_.occlusion(material, UvFootprint{mesh_.uv(p), glm::dvec2(0.0), glm::dvec2(0.0)});
    return out;
}

}  // namespace preskin::reference
