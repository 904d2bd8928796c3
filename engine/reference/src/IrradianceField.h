// IrradianceField: the irradiance E(y) at a surface point for the diffusion reference, from the
// renderer's own light definitions (toGpuLight and the falloff of shaders/preskin/lights.glsl):
// every punctual light times max(N.L, 0) with N the interpolated vertex normal, every area light
// its integral of max(N.omega, 0) over the light (AreaLightIrradiance.h); the shadow
// light (shadowLightIndex) only where a ray towards it is unoccluded; the environment's L2 SH
// irradiance (Lambert's zonal coefficients, clamped at zero as forward.frag does) times the
// material's occlusion texture.
// Shadow rays start from the point lifted onto the surface the vertex normals imply (Hanika,
// "Hacking the Shadow Terminator", Ray Tracing Gems II, 2021: the point moved off each corner's
// tangent plane it lies below, blended by the barycentric weights), plus a relative epsilon along
// the face normal, so a coarse tessellation does not shadow itself where its smooth normals
// still face the light.
// With a TracedEnvironment the environment's light is traced instead of taken from the SH: its
// irradiance, visibility included, found once per vertex (rays from the vertex, nudged off the
// surface along its normal) and interpolated across each triangle; the occlusion texture is not
// applied (the rays see what it stands for).
// A shadow light with an angular radius (a sun) is sampled over its cap, 64 shadow rays per point,
// jittered per point; the point counts as in its cast shadow when less than half the cap's
// cosine-weighted directions reach it.
// Limits: the other lights are unshadowed (as in the renderer); a shadow light without an angular
// radius is a sharp point-like source; SH ambient is unshadowed (as in the renderer); traced ambient is linear
// across triangles (refine the mesh to resolve occlusion finer than it).
#pragma once

#include "RayScene.h"
#include "ReferenceMaterials.h"
#include "ReferenceMesh.h"
#include "TracedEnvironment.h"
#include "shared/gpu_types.h"

#include <preskin/Environment.h>
#include <preskin/Scene.h>

#include <cstdint>
#include <optional>
#include <vector>

namespace preskin::reference {

enum class ShadowState : int8_t {
    NotFacing = -1,  // no shadow light, or N.L <= 0 for it
    Lit = 0,         // facing the shadow light and visible from it
    CastShadow = 1,  // facing the shadow light but occluded
};

struct IrradianceSample {
    glm::dvec3 irradiance{0.0};
    ShadowState shadow = ShadowState::NotFacing;
};

class IrradianceField {
public:
    // traced: the environment traced (its per-vertex irradiance is found here), or null for the SH.
    IrradianceField(const ReferenceMesh& mesh, const RayScene& rays, const ReferenceMaterials& materials,
                    const std::vector<Light>& lights, const ShRgb& radianceSh, bool shadows,
                    const TracedEnvironment* traced = nullptr);

    // flipNormal: the point is shaded from the back of a double-sided surface.
    IrradianceSample at(const SurfacePoint& p, bool flipNormal) const;
    // The cosine of the point's normal (flipped as above) to the shadow light; none without one.
    std::optional<double> shadowLightCosine(const SurfacePoint& p, bool flipNormal) const;

private:
    glm::dvec3 shadowRayOrigin(const SurfacePoint& p, const glm::dvec3& normal, bool flipNormal) const;
    // The shadow light with an angular radius: its cap sampled with shadow rays (64 per point).
    glm::dvec3 sunIrradiance(const Light& light, const SurfacePoint& p, const glm::dvec3& n, bool flipNormal,
                             ShadowState& shadow) const;

    const ReferenceMesh& mesh_;
    const RayScene& rays_;
    const ReferenceMaterials& materials_;
    std::vector<gpu::GpuLight> lights_;
    std::vector<Light> sceneLights_;  // the same lights as the scene has them (area lights)
    int shadowLight_ = -1;            // index into lights_
    ShRgb radianceSh_;
    const TracedEnvironment* traced_ = nullptr;
    std::vector<glm::dvec3> vertexAmbient_;  // traced: the environment's irradiance per vertex
};

// Direction to the light and the irradiance normal to it at a point (lights.glsl's
// preskinLightIncidence in double precision).
void lightIncidence(const gpu::GpuLight& light, const glm::dvec3& positionWs, glm::dvec3& L, glm::dvec3& irradiance);

}  // namespace preskin::reference
