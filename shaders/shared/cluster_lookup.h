// The light grid's froxel lookup: the list a fragment at a world position reads, written once for
// C++ (ClusterGrid::froxelAt) and GLSL (forward.frag), as lut_mapping.h is for the LUTs. Grid
// rules and the overflow rule: engine/include/preskin/ClusterGrid.h.
//
// clusterFromWorld: rows clip x, clip y, view depth, clip w of the grid's camera (ClusterCamera);
// scale: x, y tiles per unit of the camera's NDC (tile = (ndc + 1) * xy), z, w the depth slice
// = log2(view depth) * z + w (ClusterGridShape::lookupScale); dims: x, y, z froxels (w unused).
// Positions outside the grid clamp to its nearest froxel.
#ifndef PRESKIN_SHARED_CLUSTER_LOOKUP_H
#define PRESKIN_SHARED_CLUSTER_LOOKUP_H

#include "shared/common.h"

#ifdef __cplusplus
#define PRESKIN_CLUSTER_FN inline
#else
#define PRESKIN_CLUSTER_FN
#endif

PRESKIN_GPU_BEGIN

PRESKIN_CLUSTER_FN uint preskinFroxelIndex(mat4 clusterFromWorld, vec4 scale, uvec4 dims, vec3 positionWs) {
    vec4 g = clusterFromWorld * vec4(positionWs, 1.0f);
    vec2 tile = (vec2(g) / g.w + 1.0f) * vec2(scale);
    float slice = log2(max(g.z, 1e-6f)) * scale.z + scale.w;
    uvec3 c = uvec3(clamp(ivec3(ivec2(tile), int(floor(slice))), ivec3(0), ivec3(dims) - 1));
    return (c.z * dims.y + c.y) * dims.x + c.x;
}

PRESKIN_GPU_END

#endif
