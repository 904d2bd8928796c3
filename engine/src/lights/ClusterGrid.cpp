// Public CPU entry point of the light grid (<preskin/ClusterGrid.h>): the renderer's CPU build
// for hosts that shade with their own forward pass.
#include <preskin/ClusterGrid.h>

#include "lights/ClusterAssign.h"
#include "lights/ClusterGeometry.h"
#include "lights/ClusterSurfaces.h"
#include "shared/cluster_lookup.h"

namespace preskin {

uint32_t ClusterGrid::froxelAt(const glm::vec3& positionWs) const {
    return gpu::preskinFroxelIndex(camera.clusterFromWorld(), shape.lookupScale(), glm::uvec4(shape.dims, 0u),
                                   positionWs);
}

ClusterGrid buildClusterGrid(const ClusterSettings& settings, const View& view, uint32_t widthPx, uint32_t heightPx,
                             const Bounds& sceneBounds, std::span<const Light> lights,
                             const ClusterSurfaces& surfaces) {
    const ClusterCamera camera = clusterCamera(view, widthPx, heightPx);
    std::vector<ClusterLight> local;
    local.reserve(lights.size());
    for (size_t i = 0; i < lights.size(); ++i)
        if (lights[i].type != LightType::Directional)
            local.push_back(clusterLight(lights[i], static_cast<uint32_t>(i)));
    const ClusterGeometry geometry = clusterGeometry(
        clusterGridShape(settings, camera, sceneBounds, std::span<const ClusterLight>(local)), camera.eye);
    ClusterGrid grid;
    grid.camera = camera;
    FroxelSurfaces froxels;
    if (settings.fitListsToSurfaces && !surfaces.empty()) froxelSurfaces(geometry.shape, camera, surfaces, froxels);
    ClusterAssigner assigner;
    assigner.build(settings, geometry, camera.eye.viewFromWorld, local, froxels, grid);
    return grid;
}

}  // namespace preskin
