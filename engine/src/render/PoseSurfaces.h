// The triangles the forward pass draws, in world space in a pose: what the light grid bounds its
// lists by (ClusterSurfaces, <preskin/ClusterGrid.h>). Rigid instances go through their
// transforms; morphed and skinned vertices are deformed on the CPU as shaders/deform.comp deforms
// them (the morph targets' position deltas by this pose's weights, then the weighted sum of the
// joint matrices), so the grid follows an animated mesh exactly, up to float rounding. Keeps a
// copy of what it reads (positions, position deltas, joint influences): the scene need not outlive it.
#pragma once

#include <preskin/Animation.h>
#include <preskin/ClusterGrid.h>
#include <preskin/Scene.h>

#include <vector>

namespace preskin {

class PoseSurfaces {
public:
    explicit PoseSurfaces(const Scene& scene);
    // The scene's triangles in `pose` (valid until the next call).
    ClusterSurfaces surfaces(const ScenePose& pose);

private:
    struct Part {  // one primitive of one instance
        size_t instance = 0;
        size_t firstVertex = 0;                     // in positions_
        std::vector<glm::vec3> rest;                // object-space positions
        std::vector<std::vector<glm::vec3>> delta;  // per morph target, per vertex (may be shorter)
        std::vector<JointInfluences> influences;    // skinned: one per vertex; else empty
    };
    std::vector<Part> parts_;
    std::vector<glm::mat4> restWorldFromObject_;  // per instance
    std::vector<glm::vec3> positions_;
    std::vector<uint32_t> indices_;        // the scene's triangle lists, offset per part
    std::vector<uint8_t> backFaceCulled_;  // per triangle: its material is single-sided
};

}  // namespace preskin
