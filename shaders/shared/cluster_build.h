// The compute build of the light grid (shaders/cluster_build.comp): its bindings, parameters and
// per-light scratch, read by C++ (engine/src/lights/ClusterBuilder.cpp) and GLSL. The lists it
// writes are the ones the forward pass reads (gpu_types.h: kBindingClusterRanges / Indices).
#ifndef PRESKIN_SHARED_CLUSTER_BUILD_H
#define PRESKIN_SHARED_CLUSTER_BUILD_H

#include "shared/common.h"

PRESKIN_GPU_BEGIN

// ---- descriptor set 0 of cluster_build.comp ----------------------------------------------------
PRESKIN_CONST(uint, kClusterBindingParams, 0)    // ClusterBuildParams (uniform buffer)
PRESKIN_CONST(uint, kClusterBindingLights, 1)    // GpuLight[] (the frame's light buffer)
PRESKIN_CONST(uint, kClusterBindingGeometry, 2)  // vec4[]: grid geometry (see ClusterBuildParams)
PRESKIN_CONST(uint, kClusterBindingVolumes, 3)   // ClusterLightVolume[] (pass 0 writes, pass 1 reads)
PRESKIN_CONST(uint, kClusterBindingRanges, 4)    // uvec2 (offset, count) per froxel
PRESKIN_CONST(uint, kClusterBindingIndices, 5)   // uint light indices
PRESKIN_CONST(uint, kClusterBindingCounters, 6)  // ClusterCounters
PRESKIN_CONST(uint, kClusterBindingSurfaces, 7)  // vec4[]: where the surfaces are (slicing.z = 1): per froxel
                                                 // (depth min, max, along min, max), then per tile the
                                                 // slab's axis (w = 1; 0: none), engine/src/lights/ClusterSurfaces.h
PRESKIN_CONST(uint, kClusterBindingTileBoxes, 8)  // uvec4 per local light: ClusterLightVolume.box's xyz, the
                                                  // froxel box (pass 0 writes; empty: lo.x > hi.x), which
                                                  // the blocks pass reads for every block, packed apart
PRESKIN_CONST(uint, kClusterBindingBlockRanges, 9)    // uvec2 (offset, count) per block of tiles into the block
                                                      // list; count kClusterBlockOverflow: the list did not fit
PRESKIN_CONST(uint, kClusterBindingBlockIndices, 10)  // uint: per block, the local lights whose box meets it, ascending

// Specialization constant 0 selects the pass.
PRESKIN_CONST(uint, kClusterSpecPass, 0)
PRESKIN_CONST(uint, kClusterPassVolumes, 0)  // one invocation per local light
PRESKIN_CONST(uint, kClusterPassAssign, 1)   // one workgroup per screen tile, one invocation per slice
PRESKIN_CONST(uint, kClusterPassBlocks, 2)   // one workgroup per block of kClusterBlockTiles^2 tiles
PRESKIN_CONST(uint, kClusterVolumeGroupSize, 64)
PRESKIN_CONST(uint, kClusterAssignGroupSize, 32)
// Lights tested against a tile per batch: kClusterAssignGroupSize words of 32 bits.
PRESKIN_CONST(uint, kClusterBatchLights, 1024)
// Batches whose candidates the assign pass keeps in shared memory between its two sweeps (8 KiB:
// 65,536 lights marked once; beyond, the last slot's batches are marked again).
PRESKIN_CONST(uint, kClusterCachedBatches, 64)
// A block's side in tiles: the blocks pass lists each block's lights, the assign pass reads a
// tile's candidates from its block's list.
PRESKIN_CONST(uint, kClusterBlockTiles, 8)
PRESKIN_CONST(uint, kClusterBlockOverflow, 0xffffffff)

// ClusterLightVolume.box.w flags.
PRESKIN_CONST(uint, kClusterVolumeCone, 1)
PRESKIN_CONST(uint, kClusterVolumeUnlimited, 2)
PRESKIN_CONST(uint, kClusterVolumeEmpty, 4)

struct ClusterBuildParams {
    mat4 viewFromWorld;
    uvec4 dims;             // xyz froxels; w: max lights per cluster
    uvec4 lightInfo;        // x: first local light in the light buffer, y: local lights, z: index capacity,
                            // w: block list capacity
    uvec4 geometryOffsets;  // vec4 offsets in the geometry buffer: x column planes (dims.x + 1),
                            // y row planes (dims.y + 1), z slice starts in .x (dims.z + 1),
                            // w corner lines: origin, direction interleaved ((dims.x + 1) * (dims.y + 1) pairs)
    vec4 slack;             // x depth, y radius (relative), z cone cosine; w: view near plane (m)
    vec4 slicing;           // x slice scale, y slice bias (slice = log2(depth) * x + y); z: 1 when the
                            // surfaces bound each froxel (kClusterBindingSurfaces), 0: whole froxels
    vec4 lightBoundsMin;    // world box a light's sphere must reach to be listed; w: 1 when used, 0: every light
    vec4 lightBoundsMax;
};
PRESKIN_CHECK_SIZE(ClusterBuildParams, 64 + 7 * 16)

// One local light in view space (pass 0 output).
struct ClusterLightVolume {
    vec4 centerRadius;  // bounding sphere (m); radius unused when unlimited
    vec4 apexRange;     // cone apex, range (m; unused when unlimited)
    vec4 axisCos;       // cone axis (unit), cosine of the (widened) outer angle
    uvec4 box;          // froxel box: x = lo.x | hi.x << 16, y and z likewise; w: kClusterVolume* flags
};
PRESKIN_CHECK_SIZE(ClusterLightVolume, 64)

struct ClusterCounters {
    uvec4 values;  // x: index entries reserved (may pass the capacity), y: froxels that lost lights,
                   // z: entries requested before the caps, w: block list entries reserved
};
PRESKIN_CHECK_SIZE(ClusterCounters, 16)

PRESKIN_GPU_END

#endif
