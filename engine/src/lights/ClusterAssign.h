// CPU light assignment for the froxel grid (see <preskin/ClusterGrid.h> for the rules).
//
// Per light: a view-space bounding sphere (the range sphere; for spots narrower than 60 degrees
// the smallest sphere around the cone's spherical sector, centre apex + axis * range / (2 cos),
// radius range / (2 cos)). Per depth slice the sphere is cut down to one bounding the part
// inside the slice (centre moved onto the nearer slice plane, radius sqrt(r^2 - h^2)), then per
// row of tiles likewise against the row's boundary planes, and the columns whose slab the
// remaining sphere overlaps are the light's froxels in that row (the refinement of E. Persson,
// "Practical Clustered Shading", SIGGRAPH 2015). Each step bounds the light's volume inside
// the froxel from outside, so no touched froxel is missed. Spots then test their cone against
// each froxel's bounding sphere (B. Wronski, "Cull that cone!", 2017), which only rejects
// froxels the cone cannot reach.
//
// Work is split by depth slice (TBB): a slice's froxels are disjoint from every other slice's,
// so the result does not depend on the thread count. Lists hold ascending light indices.
//
// With the surfaces' froxels (ClusterSurfaces.h) a froxel's volume is the part of it its surfaces
// occupy: the light's sphere is cut to their slab, to their depth interval (within the slice) and
// to the tile's row, then tested against its column; froxels without surfaces list nothing.
#pragma once

#include "lights/ClusterGeometry.h"
#include "lights/ClusterSurfaces.h"

#include <preskin/ClusterGrid.h>

#include <shared/gpu_types.h>

#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace preskin {

// One local light, world space, as the renderer shades it.
struct ClusterLight {
    glm::vec3 positionWs{0.0f};
    float rangeM = 0.0f;  // <= 0: unlimited
    glm::vec3 directionWs{0.0f, 0.0f, -1.0f};
    float cosOuter = -1.0f;  // spot: cosine of the outer cone angle (the attenuation's zero)
    bool spot = false;
    uint32_t index = 0;  // the value written into the lists
};

// A point or spot light as the grid bounds it, `index` the value its lists hold (LightRecord.cpp,
// beside the GPU record: the one place a scene light is converted).
ClusterLight clusterLight(const Light& light, uint32_t index);

// A frame's light array as the shaders read it, `records`: the shadow light (`shadowLight`, -1:
// none) first, the other directional lights, then the point and spot lights in their order; and
// those point and spot lights as the grid bounds them, `local` (`index`: the entry in `records`).
// Returns the number of directional entries. Converted in parallel: a frame may hold 65,536.
uint32_t frameLightRecords(std::span<const Light> lights, int shadowLight, std::vector<gpu::GpuLight>& records,
                           std::vector<ClusterLight>& local);

// A spot's cone in view space, for the froxels' cone test.
struct ClusterCone {
    glm::vec3 apexVs{0.0f};
    float rangeM = 0.0f;  // infinity for unlimited lights
    glm::vec3 axisVs{0.0f, 0.0f, -1.0f};
    float cosOuter = -1.0f;
    float sinOuter = 0.0f;
};

// A light in view space with its bounding sphere and the box of froxels it may touch.
struct ClusterLightBounds {
    glm::vec3 centerVs{0.0f};
    float radiusM = 0.0f;  // infinity for unlimited lights
    glm::uvec3 lo{1u};     // inclusive froxel box; empty when any lo > hi
    glm::uvec3 hi{0u};
    uint32_t index = 0;
    bool cone = false;  // a spot with a cone narrower than a half space, written to `cone`
};

// How far along a spot's axis its bounding sphere's centre lies, the sphere's radius then: the
// smallest sphere around a cone narrower than 60 degrees. 0: the range sphere about the apex.
float clusterSphereOffsetM(const ClusterLight& light);
// That sphere in world space: xyz its centre, w its radius (infinite for an unlimited light),
// before the float slack.
glm::vec4 clusterLightSphereWs(const ClusterLight& light);
// Whether a sphere reaches a box (the box's nearest point lies within the radius).
bool sphereReachesBox(const Bounds& box, const glm::vec3& center, float radius);

// Bounds of one light for this grid (view transform and geometry); a cone's also into `cone`.
ClusterLightBounds clusterLightBounds(const ClusterLight& light, const glm::mat4& viewFromWorld,
                                      const ClusterGeometry& geometry, ClusterCone& cone);

// Keeps its scratch memory between builds.
class ClusterAssigner {
public:
    // Fills grid.ranges / indices / overflow counts; grid.shape must equal geometry.shape.
    // `surfaces`: where the surfaces are (froxelSurfaces), or empty for whole froxels.
    void build(const ClusterSettings& settings, const ClusterGeometry& geometry, const glm::mat4& viewFromWorld,
               std::span<const ClusterLight> lights, const FroxelSurfaces& surfaces, ClusterGrid& grid);

private:
    // A light as a slice scans it: what its froxel tests read, copied so that a slice reads its
    // candidates in sequence.
    static constexpr uint32_t kNoCone = ~0u;
    struct Candidate {
        glm::vec3 centerVs;
        float radiusM;
        glm::uvec2 columns;  // the froxel box's first and last column
        glm::uvec2 rows;     // and row
        uint32_t index;      // the value the lists hold
        uint32_t cone;       // the light's cone (cones_) for a cone, else kNoCone
    };
    struct SliceScratch {
        std::vector<Candidate> candidates;  // the lights whose froxel box reaches the slice, in light order
        std::vector<uint32_t> froxel;       // froxel within the slice (y * dims.x + x), per entry
        std::vector<uint32_t> light;        // light index, per entry
        std::vector<uint32_t> count;        // entries per froxel of the slice
        uint32_t largest = 0;               // the largest count
        std::vector<glm::vec4> sphere;      // bounding sphere per froxel of the slice, for spots
        std::vector<uint32_t> sphereStamp;  // with surfaces: the build that computed `sphere`
    };
    std::vector<ClusterLightBounds> bounds_;
    std::vector<ClusterCone> cones_;  // written for the lights whose bounds have `cone`
    uint32_t stamp_ = 0;
    std::vector<SliceScratch> slices_;
};

}  // namespace preskin
