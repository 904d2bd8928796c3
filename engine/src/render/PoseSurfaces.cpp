// The drawn triangles in world space in a pose; see PoseSurfaces.h.
#include "render/PoseSurfaces.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace preskin {

PoseSurfaces::PoseSurfaces(const Scene& scene) {
    size_t base = 0;
    for (size_t n = 0; n < scene.instances.size(); ++n) {
        const MeshInstance& inst = scene.instances[n];
        restWorldFromObject_.push_back(inst.worldFromObject);
        if (inst.mesh < 0 || size_t(inst.mesh) >= scene.meshes.size()) continue;
        const bool skinned = inst.skin >= 0 && size_t(inst.skin) < scene.skins.size();
        for (const Primitive& p : scene.meshes[size_t(inst.mesh)].primitives) {
            Part part;
            part.instance = n;
            part.firstVertex = base;
            part.rest.reserve(p.vertices.size());
            for (const Vertex& v : p.vertices) part.rest.push_back(v.positionOs);
            for (const MorphTarget& t : p.targets) part.delta.push_back(t.positionDeltas);
            if (skinned && p.influences.size() == p.vertices.size()) part.influences = p.influences;
            for (const uint32_t i : p.indices) indices_.push_back(static_cast<uint32_t>(base + i));
            const bool doubleSided = p.material >= 0 && size_t(p.material) < scene.materials.size() &&
                scene.materials[size_t(p.material)].doubleSided;
            backFaceCulled_.resize(indices_.size() / 3, doubleSided ? 0 : 1);
            base += p.vertices.size();
            parts_.push_back(std::move(part));
        }
    }
    positions_.resize(base);
}

ClusterSurfaces PoseSurfaces::surfaces(const ScenePose& pose) {
    for (const Part& part : parts_) {
        const InstancePose* ip = part.instance < pose.instances.size() ? &pose.instances[part.instance] : nullptr;
        const glm::mat4 worldFromObject = ip ? ip->worldFromObject : restWorldFromObject_[part.instance];
        const bool skinned = ip && !part.influences.empty() && !ip->jointMatrices.empty();
        glm::vec3* out = positions_.data() + part.firstVertex;
        const auto deform = [&](const tbb::blocked_range<size_t>& r) {
            for (size_t v = r.begin(); v < r.end(); ++v) {
                glm::vec3 position = part.rest[v];
                if (ip)
                    for (size_t t = 0; t < part.delta.size() && t < ip->morphWeights.size(); ++t) {
                        const float w = ip->morphWeights[t];
                        if (w != 0.0f && v < part.delta[t].size()) position += w * part.delta[t][v];
                    }
                if (skinned) {
                    glm::mat4 m(0.0f);
                    for (int set = 0; set < 2; ++set)
                        for (int k = 0; k < 4; ++k) {
                            const float w = part.influences[v].weights[set][k];
                            const uint32_t j = part.influences[v].joints[set][k];
                            if (w != 0.0f && j < ip->jointMatrices.size()) m += w * ip->jointMatrices[j];
                        }
                    position = glm::vec3(m * glm::vec4(position, 1.0f));
                }
                out[v] = glm::vec3(worldFromObject * glm::vec4(position, 1.0f));
            }
        };
        tbb::parallel_for(tbb::blocked_range<size_t>(0, part.rest.size(), 4096), deform);
    }
    return ClusterSurfaces{positions_, indices_, backFaceCulled_};
}

}  // namespace preskin
