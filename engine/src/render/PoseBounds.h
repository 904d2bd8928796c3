// Conservative world bounds of a scene in a pose (<preskin/Animation.h>), for what is fitted to the
// scene every frame (the shadow map, the light grid's depth slices), computed on the CPU before
// the GPU deforms anything:
//  - a rigid instance: its mesh's object bounds through its transform;
//  - morph targets: object bounds grown by sum_t |w_t| * (largest position delta of target t);
//  - a skinned instance: a skinned vertex is a convex combination (weights >= 0, summing to 1) of
//    its joints' transforms of its morphed position, so it lies in the union, over joints j, of
//    jointMatrix_j applied to the (grown) object bounds of the vertices joint j influences.
// A filter limits the bounds to some primitives (the skin, for the shadow map's receivers).
// Limits: boxes through matrices (8 corners), so rotated bounds are looser than the mesh.
#pragma once

#include <preskin/Animation.h>
#include <preskin/Scene.h>

#include <functional>
#include <vector>

namespace preskin {

class PoseBounds {
public:
    using PrimitiveFilter = std::function<bool(const Primitive&)>;
    // Bounds of the primitives `include` accepts (every primitive without a filter).
    explicit PoseBounds(const Scene& scene, const PrimitiveFilter& include = {});
    Bounds worldBounds(const ScenePose& pose) const;

private:
    struct MeshBounds {
        Bounds object;                    // all primitives
        std::vector<float> targetReach;   // per morph target: the largest |position delta|
        std::vector<Bounds> jointBounds;  // per skin joint index: vertices it influences
    };
    std::vector<MeshBounds> meshes_;
    std::vector<int> instanceMesh_;
    std::vector<bool> instanceSkinned_;
};

}  // namespace preskin
