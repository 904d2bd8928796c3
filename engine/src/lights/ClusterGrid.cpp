// Public CPU entry point of the light grid (<preskin/ClusterGrid.h>): the renderer's CPU build
// for hosts that shade with their own forward pass.
#include <preskin/ClusterGrid.h>

#include "lights/ClusterAssign.h"
#include "lights/ClusterGeometry.h"

#include <cmath>

namespace preskin {

ClusterGrid buildClusterGrid(const ClusterSettings& settings, const View& view, uint32_t widthPx, uint32_t heightPx,
                             const Bounds& sceneBounds, std::span<const Light> lights) {
    const ClusterGeometry geometry = clusterGeometry(clusterGridShape(settings, view, widthPx, heightPx, sceneBounds), view);
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
    ClusterAssigner assigner;
    assigner.build(settings, geometry, view.viewFromWorld, local, grid);
    return grid;
}

}  // namespace preskin
