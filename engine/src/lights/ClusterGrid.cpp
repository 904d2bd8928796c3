// Public CPU entry point of the light grid (<preskin/ClusterGrid.h>): the renderer's CPU build
// for hosts that shade with their own forward pass.
#include <preskin/ClusterGrid.h>

#include "lights/ClusterAssign.h"
#include "lights/ClusterGeometry.h"

#include <algorithm>
#include <cmath>

namespace preskin {

uint32_t ClusterGrid::froxelAt(const glm::vec3& positionWs) const {
    // forward.frag's froxel lookup, operation for operation in float.
    const glm::vec4 c = camera.clusterFromWorld() * glm::vec4(positionWs, 1.0f);
    const glm::vec2 scale = 0.5f * glm::vec2(shape.extentPx) / float(shape.tileSizePx);
    const glm::vec2 tile = (glm::vec2(c) / c.w + 1.0f) * scale;
    const float slice = std::log2(std::max(c.z, 1e-6f)) * shape.sliceScale + shape.sliceBias;
    const glm::ivec3 cell = glm::clamp(glm::ivec3(glm::ivec2(tile), int(std::floor(slice))), glm::ivec3(0),
                                       glm::ivec3(shape.dims) - 1);
    return shape.froxelIndex(uint32_t(cell.x), uint32_t(cell.y), uint32_t(cell.z));
}

ClusterGrid buildClusterGrid(const ClusterSettings& settings, const View& view, uint32_t widthPx, uint32_t heightPx,
                             const Bounds& sceneBounds, std::span<const Light> lights) {
    const ClusterCamera camera = clusterCamera(view, widthPx, heightPx);
    const ClusterGeometry geometry = clusterGeometry(clusterGridShape(settings, camera, sceneBounds), camera.eye);
    std::vector<ClusterLight> local;
    local.reserve(lights.size());
    for (size_t i = 0; i < lights.size(); ++i) {
        const Light& l = lights[i];
        if (l.type == LightType::Directional) continue;
        ClusterLight c;
        c.positionWs = l.positionWs;
        c.rangeM = l.range;
        c.directionWs = glm::length(l.directionWs) > 0.0f ? glm::normalize(l.directionWs) : glm::vec3(0.0f, 0.0f, -1.0f);
        c.spot = l.type == LightType::Spot;
        c.cosOuter = c.spot ? std::cos(l.outerConeAngle) : -1.0f;
        c.index = static_cast<uint32_t>(i);
        local.push_back(c);
    }
    ClusterGrid grid;
    grid.camera = camera;
    ClusterAssigner assigner;
    assigner.build(settings, geometry, camera.eye.viewFromWorld, local, grid);
    return grid;
}

}  // namespace preskin
