// Conservative world bounds of a posed scene (see PoseBounds.h).
#include "render/PoseBounds.h"

#include <algorithm>
#include <cmath>

namespace preskin {

namespace {

Bounds transformed(const Bounds& b, const glm::mat4& m) {
    Bounds out;
    if (b.empty()) return out;
    for (int i = 0; i < 8; ++i)
        out.extend(glm::vec3(
            m *
            glm::vec4((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y, (i & 4) ? b.max.z : b.min.z, 1.0f)));
    return out;
}

Bounds grown(Bounds b, float by) {
    if (b.empty() || !(by > 0.0f)) return b;
    b.min -= glm::vec3(by);
    b.max += glm::vec3(by);
    return b;
}

}  // namespace

PoseBounds::PoseBounds(const Scene& scene, const PrimitiveFilter& include) {
    meshes_.resize(scene.meshes.size());
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        MeshBounds& mb = meshes_[m];
        for (const Primitive& p : scene.meshes[m].primitives) {
            if (include && !include(p)) continue;
            mb.object.extend(p.boundsOs);
            mb.targetReach.resize(std::max(mb.targetReach.size(), p.targets.size()), 0.0f);
            for (size_t t = 0; t < p.targets.size(); ++t)
                for (const glm::vec3& d : p.targets[t].positionDeltas)
                    mb.targetReach[t] = std::max(mb.targetReach[t], glm::length(d));
            for (size_t v = 0; v < p.influences.size() && v < p.vertices.size(); ++v)
                for (int set = 0; set < 2; ++set)
                    for (int k = 0; k < 4; ++k) {
                        if (!(p.influences[v].weights[set][k] > 0.0f)) continue;
                        const uint32_t joint = p.influences[v].joints[set][k];
                        if (joint >= mb.jointBounds.size()) mb.jointBounds.resize(joint + 1);
                        mb.jointBounds[joint].extend(p.vertices[v].positionOs);
                    }
        }
    }
    for (const MeshInstance& inst : scene.instances) {
        const bool valid = inst.mesh >= 0 && size_t(inst.mesh) < scene.meshes.size();
        instanceMesh_.push_back(valid ? inst.mesh : -1);
        instanceSkinned_.push_back(valid && inst.skin >= 0 && size_t(inst.skin) < scene.skins.size());
    }
}

Bounds PoseBounds::worldBounds(const ScenePose& pose) const {
    Bounds world;
    for (size_t i = 0; i < instanceMesh_.size() && i < pose.instances.size(); ++i) {
        if (instanceMesh_[i] < 0) continue;
        const MeshBounds& mb = meshes_[size_t(instanceMesh_[i])];
        const InstancePose& p = pose.instances[i];
        float reach = 0.0f;
        for (size_t t = 0; t < mb.targetReach.size() && t < p.morphWeights.size(); ++t)
            reach += std::abs(p.morphWeights[t]) * mb.targetReach[t];
        if (instanceSkinned_[i]) {
            for (size_t j = 0; j < mb.jointBounds.size() && j < p.jointMatrices.size(); ++j)
                world.extend(transformed(grown(mb.jointBounds[j], reach), p.jointMatrices[j]));
        } else {
            world.extend(transformed(grown(mb.object, reach), p.worldFromObject));
        }
    }
    return world;
}

}  // namespace preskin
