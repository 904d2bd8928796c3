#version 460
// cluster_build.comp: the compute build of the light grid (froxels), three passes selected by a
// specialization constant, recorded in this order:
//   pass 0 (kClusterPassVolumes), one invocation per local light: the light in view space, its
//     bounding sphere (the range sphere, or for spots under 60 degrees the sphere around the
//     cone's spherical sector) and the box of froxels it may touch (also on its own, 16 bytes a
//     light, for the passes that read every light's);
//   pass 2 (kClusterPassBlocks), one workgroup per block of kClusterBlockTiles^2 tiles: the
//     lights whose box meets the block, in ascending order, into the block's list (a list that
//     does not fit its share of the buffer is marked, and its tiles read every light);
//   pass 1 (kClusterPassAssign), one workgroup per screen tile, one invocation per depth slice:
//     of its block's lights, those whose box covers the tile and reaches one of the slices where
//     surfaces are in it are marked in a shared bit mask (batches of kClusterBatchLights;
//     consecutive invocations read consecutive boxes, so a workgroup's reads coalesce; a tile
//     and 32-slice chunk without surfaces tests no light), then each invocation tests them in
//     ascending order against its froxel: the bounding sphere cut to the slice, then to the row
//     (each cut bounds the light's part on the froxel's side of a plane), then against the
//     column's slab; spots also test their cone against the froxel's bounding sphere (Wronski,
//     "Cull that cone!", 2017). The first sweep counts, an atomic reserves the froxel's range, a
//     second sweep writes (the masks of the first batches kept from the first). With the
//     surfaces per froxel (slicing.z = 1, engine/src/lights/ClusterSurfaces.h) the sphere is first
//     cut to their slab, its depth slab is the part of the slice they occupy, and a froxel
//     without surfaces lists nothing.
// The same tests as the CPU build (engine/src/lights/ClusterAssign.cpp, with its sources), so
// both give the same lists up to float rounding at boundaries; both are conservative.
// Overflow rule (<preskin/ClusterGrid.h>): a froxel keeps its lowest light indices up to the
// per-froxel cap and what fits in the index list; froxels that lose lights are counted.
// Limits: ranges are reserved in workgroup order, so after an index-list overflow which froxels
// lost lights varies from run to run; counters are 32-bit.
#extension GL_GOOGLE_include_directive : require
#include "shared/gpu_types.h"
#include "shared/cluster_build.h"

layout(constant_id = kClusterSpecPass) const uint kPass = kClusterPassVolumes;
layout(local_size_x = kClusterAssignGroupSize) in;

layout(set = 0, binding = kClusterBindingParams) uniform Params { ClusterBuildParams params; };
layout(std430, set = 0, binding = kClusterBindingLights) readonly buffer Lights { GpuLight lights[]; };
layout(std430, set = 0, binding = kClusterBindingGeometry) readonly buffer Geometry { vec4 geometry[]; };
layout(std430, set = 0, binding = kClusterBindingVolumes) buffer Volumes { ClusterLightVolume volumes[]; };
layout(std430, set = 0, binding = kClusterBindingRanges) writeonly buffer Ranges { uvec2 ranges[]; };
layout(std430, set = 0, binding = kClusterBindingIndices) writeonly buffer Indices { uint indices[]; };
layout(std430, set = 0, binding = kClusterBindingCounters) buffer Counters { ClusterCounters counters; };
layout(std430, set = 0, binding = kClusterBindingSurfaces) readonly buffer Surfaces { vec4 surfaces[]; };
layout(std430, set = 0, binding = kClusterBindingTileBoxes) buffer TileBoxes { uvec4 tileBoxes[]; };
layout(std430, set = 0, binding = kClusterBindingBlockRanges) buffer BlockRanges { uvec2 blockRanges[]; };
layout(std430, set = 0, binding = kClusterBindingBlockIndices) buffer BlockIndices { uint blockIndices[]; };

// The candidates of the first kClusterCachedBatches - 1 batches, kept from the counting sweep for
// the writing sweep; later batches share the last slot and are marked again.
shared uint candidateMask[kClusterCachedBatches * kClusterAssignGroupSize];
shared uint columnMask[kClusterAssignGroupSize];
shared uint occupiedLo;  // the slices of this workgroup's chunk with surfaces in its tile
shared uint occupiedHi;

float planeDistance(vec4 plane, vec3 p) { return dot(plane.xyz, p) + plane.w; }
vec4 columnPlane(uint i) { return geometry[params.geometryOffsets.x + i]; }
vec4 rowPlane(uint j) { return geometry[params.geometryOffsets.y + j]; }
float sliceStart(uint z) { return geometry[params.geometryOffsets.z + z].x; }

uint sliceOf(float depth) {
    float s = floor(log2(max(depth, 1e-6)) * params.slicing.x + params.slicing.y);
    return uint(clamp(s, 0.0, float(params.dims.z - 1u)));
}

// family 0: columns, 1: rows.
bool slabOverlaps(uint family, uint k, vec3 c, float r) {
    uint base = family == 0u ? params.geometryOffsets.x : params.geometryOffsets.y;
    return planeDistance(geometry[base + k], c) >= -r && planeDistance(geometry[base + k + 1u], c) <= r;
}

// First and last slab the sphere overlaps (scanning inwards from both ends is conservative).
bool slabRange(uint family, vec3 c, float r, out uint first, out uint last) {
    uint count = family == 0u ? params.dims.x : params.dims.y;
    first = 1u;
    last = 0u;
    uint a = 0u;
    while (a < count && !slabOverlaps(family, a, c, r)) ++a;
    if (a >= count) return false;
    uint b = count - 1u;
    while (b > a && !slabOverlaps(family, b, c, r)) --b;
    first = a;
    last = b;
    return true;
}

void volumePass() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= params.lightInfo.y) return;
    GpuLight light = lights[params.lightInfo.x + i];
    vec3 apex = (params.viewFromWorld * vec4(light.positionRange.xyz, 1.0)).xyz;
    vec3 axis = mat3(params.viewFromWorld) * light.directionType.xyz;
    float axisLength = length(axis);
    axis = axisLength > 0.0 ? axis / axisLength : vec3(0.0, 0.0, -1.0);
    float range = light.positionRange.w;
    bool unlimited = !(range > 0.0);
    uint flags = unlimited ? kClusterVolumeUnlimited : 0u;
    vec3 center = apex;
    float radius = range;
    float centerAlongAxis = 0.0;  // the bounding sphere's centre: the apex moved this far along the axis
    float cosOuter = -1.0;
    if (uint(light.directionType.w) == kLightSpot) {
        // The attenuation saturate(cd * scale + offset) is zero from cd = -offset / scale down.
        cosOuter = clamp(-light.spotScaleOffset.y / light.spotScaleOffset.x - params.slack.z, -1.0, 1.0);
        if (cosOuter > 0.0) {
            flags |= kClusterVolumeCone;
            if (!unlimited && cosOuter > 0.5) {
                centerAlongAxis = range / (2.0 * cosOuter);
                center = apex + axis * centerAlongAxis;
                radius = centerAlongAxis;
            }
        }
    }
    uvec3 lo = uvec3(0u);
    uvec3 hi = params.dims.xyz - 1u;
    bool empty = false;
    if (!unlimited) {
        radius = radius * (1.0 + params.slack.y) + 1e-6;
        float depth = -center.z;
        float slack = 2.0 * params.slack.x;
        empty = depth + radius < params.slack.w * (1.0 - slack);
        lo.z = sliceOf((depth - radius) * (1.0 - slack));
        hi.z = sliceOf((depth + radius) * (1.0 + slack));
        if (params.lightBoundsMin.w > 0.0) {
            // The same sphere in world space (the view transform is rigid), against the scene's box,
            // before the slab scans, which most lights of a large scattered set then skip.
            vec3 centerWs = light.positionRange.xyz;
            if (centerAlongAxis > 0.0) centerWs += normalize(light.directionType.xyz) * centerAlongAxis;
            vec3 outside = max(max(params.lightBoundsMin.xyz - centerWs, centerWs - params.lightBoundsMax.xyz), 0.0);
            empty = empty || dot(outside, outside) > radius * radius;
        }
        empty = empty || !slabRange(0u, center, radius, lo.x, hi.x) || !slabRange(1u, center, radius, lo.y, hi.y);
    }
    ClusterLightVolume v;
    v.centerRadius = vec4(center, radius);
    v.apexRange = vec4(apex, range);
    v.axisCos = vec4(axis, cosOuter);
    v.box = uvec4(lo.x | (hi.x << 16), lo.y | (hi.y << 16), lo.z | (hi.z << 16), flags | (empty ? kClusterVolumeEmpty : 0u));
    volumes[i] = v;
    tileBoxes[i] = empty ? uvec4(0xffffu, 0u, 0u, 0u) : uvec4(v.box.xyz, 0u);
}

// Cuts the sphere to the inner side of a plane (inner = +1: distance >= 0, -1: <= 0).
bool cutByPlane(vec4 plane, float inner, inout vec3 c, inout float r) {
    float outside = -inner * planeDistance(plane, c);
    if (outside <= 0.0) return true;
    if (outside > r) return false;
    c += plane.xyz * (inner * outside);
    r = sqrt(max(r * r - outside * outside, 0.0));
    return true;
}

// The spot's cone against the bounding sphere of the tile's froxel between depths dA and dB.
bool coneReachesFroxel(ClusterLightVolume v, uvec2 tile, float dA, float dB) {
    vec3 lo = vec3(3.0e38);
    vec3 hi = vec3(-3.0e38);
    for (uint j = 0u; j < 2u; ++j)
        for (uint k = 0u; k < 2u; ++k) {
            uint corner = (tile.y + j) * (params.dims.x + 1u) + tile.x + k;
            vec3 origin = geometry[params.geometryOffsets.w + 2u * corner].xyz;
            vec3 dir = geometry[params.geometryOffsets.w + 2u * corner + 1u].xyz;
            vec3 a = origin + dir * dA;
            vec3 b = origin + dir * dB;
            lo = min(lo, min(a, b));
            hi = max(hi, max(a, b));
        }
    vec3 center = 0.5 * (lo + hi);
    float radius = 0.5 * length(hi - lo) * (1.0 + params.slack.y) + 1e-6;
    vec3 apexToCenter = center - v.apexRange.xyz;
    float along = dot(apexToCenter, v.axisCos.xyz);
    float across = sqrt(max(dot(apexToCenter, apexToCenter) - along * along, 0.0));
    float cosOuter = v.axisCos.w;
    float sinOuter = sqrt(max(1.0 - cosOuter * cosOuter, 0.0));
    bool limited = (v.box.w & kClusterVolumeUnlimited) == 0u;
    return !(cosOuter * across - along * sinOuter > radius || (limited && along > radius + v.apexRange.w) ||
             along < -radius);
}

// One invocation's froxel: its tile's boundary planes and its dilated depth slab [d0, d1]; with
// the surfaces, also where they are in it: depths [bandD0, bandD1] and the slab along the axis.
struct Froxel {
    uvec3 f;
    vec4 row0;
    vec4 row1;
    vec4 column0;
    vec4 column1;
    float d0;
    float d1;
    bool lastSlice;
    bool surfaces;
    float bandD0;
    float bandD1;
    vec4 slabLow;   // planes (axis, -min along it) and (axis, -max along it), used when hasSlab
    vec4 slabHigh;
    bool hasSlab;
};

// The light's bounding sphere cut to the slab (with `slab`), to the depths [d0, d1] (no far
// bound when open) and to the froxel's row: does it overlap the froxel's column?
bool sphereReaches(ClusterLightVolume v, Froxel fr, float d0, float d1, bool open, bool slab) {
    vec3 c = v.centerRadius.xyz;
    float r = v.centerRadius.w;
    if (slab && (!cutByPlane(fr.slabLow, 1.0, c, r) || !cutByPlane(fr.slabHigh, -1.0, c, r))) return false;
    float depth = -c.z;
    float h = 0.0;
    if (depth < d0) {
        h = d0 - depth;
        c.z = -d0;
    } else if (!open && depth > d1) {
        h = depth - d1;
        c.z = -d1;
    }
    if (h > r) return false;
    r = sqrt(max(r * r - h * h, 0.0));
    if (!cutByPlane(fr.row0, 1.0, c, r) || !cutByPlane(fr.row1, -1.0, c, r)) return false;
    return !(planeDistance(fr.column0, c) < -r || planeDistance(fr.column1, c) > r);
}

// Does light i (local index) touch the froxel (with the surfaces: the part of it they occupy)?
// As the CPU build: the whole froxel's test, then the surfaces' part's; a spot's cone against the
// sphere of the surfaces' depths (or of the part of the slice the light's sphere spans).
bool froxelTouched(uint i, Froxel fr) {
    uvec3 f = fr.f;
    ClusterLightVolume v = volumes[i];
    uint flags = v.box.w;
    if (f.z < (v.box.z & 0xffffu) || f.z > (v.box.z >> 16)) return false;
    bool limited = (flags & kClusterVolumeUnlimited) == 0u;
    if (limited && !sphereReaches(v, fr, fr.d0, fr.d1, fr.lastSlice, false)) return false;
    if (limited && fr.surfaces && !sphereReaches(v, fr, fr.bandD0, fr.bandD1, false, fr.hasSlab)) return false;
    if ((flags & kClusterVolumeCone) == 0u) return true;
    if (fr.surfaces) return coneReachesFroxel(v, f.xy, fr.bandD0, fr.bandD1);
    float coneD0 = fr.d0;
    float coneD1 = fr.d1;
    bool coneOpen = fr.lastSlice;
    if (limited) {
        float lightNear = -v.centerRadius.z - v.centerRadius.w;
        float lightFar = -v.centerRadius.z + v.centerRadius.w;
        coneD0 = max(fr.d0, lightNear);
        coneD1 = fr.lastSlice ? lightFar : min(fr.d1, lightFar);
        coneOpen = false;
    }
    if (coneOpen || coneD0 > coneD1) return true;
    return coneReachesFroxel(v, f.xy, coneD0, coneD1);
}

// The lights a workgroup tests: positions 0 .. count - 1 of its block's list (listOffset into
// blockIndices), or every local light (listed false: position = light).
struct Candidates {
    bool listed;
    uint listOffset;
    uint count;
};

uint candidateLight(Candidates c, uint position) { return c.listed ? blockIndices[c.listOffset + position] : position; }

// Marks which candidates of positions [base, base + kClusterBatchLights) have a froxel box that
// meets tiles rectLo..rectHi and slices zLo..zHi: bit b of word w is position base + 32 w + b, in
// mask slot `slot`. Invocation `lane` reads positions base + 32 w + lane (consecutive invocations,
// consecutive boxes) into bit w of its own column word, then makes word `lane` of the mask by
// transposing the 32 x 32 bits (no atomics). Every invocation calls this (it holds barriers).
void markCandidates(Candidates c, uint base, uint slot, uvec2 rectLo, uvec2 rectHi, uint zLo, uint zHi, uint lane) {
    barrier();
    uint column = 0u;
    for (uint w = 0u; w < kClusterAssignGroupSize; ++w) {
        uint position = base + w * 32u + lane;
        if (position >= c.count) break;
        uvec3 box = tileBoxes[candidateLight(c, position)].xyz;
        if (rectHi.x >= (box.x & 0xffffu) && rectLo.x <= (box.x >> 16) && rectHi.y >= (box.y & 0xffffu) &&
            rectLo.y <= (box.y >> 16) && zHi >= (box.z & 0xffffu) && zLo <= (box.z >> 16))
            column |= 1u << w;
    }
    columnMask[lane] = column;
    barrier();
    uint word = 0u;
    for (uint b = 0u; b < 32u; ++b) word |= ((columnMask[b] >> lane) & 1u) << b;
    candidateMask[slot * kClusterAssignGroupSize + lane] = word;
    barrier();
}

// Does the writing sweep mark batch `batch` again (its slot shared with later batches)?
bool markedAgain(uint batch, uint count) {
    return batch >= kClusterCachedBatches - 1u && count > kClusterCachedBatches * kClusterBatchLights;
}

// Where block `block`'s list range is in blockRanges (the blocks pass writes it, the assign pass reads it).
uint blockIndex(uvec2 block) {
    return block.y * ((params.dims.x + kClusterBlockTiles - 1u) / kClusterBlockTiles) + block.x;
}

// Pass 2: the local lights whose froxel box meets this workgroup's block of tiles, in ascending
// order, into the block list (a count sweep, an atomic reserving the block's range, a writing
// sweep); a block whose list does not fit is marked kClusterBlockOverflow and its tiles test
// every light.
void blocksPass() {
    uint lane = gl_LocalInvocationIndex;
    uvec2 block = gl_WorkGroupID.xy;
    uvec2 rectLo = block * kClusterBlockTiles;
    uvec2 rectHi = min(rectLo + kClusterBlockTiles - 1u, params.dims.xy - 1u);
    Candidates all = Candidates(false, 0u, params.lightInfo.y);
    uint total = 0u;
    for (uint base = 0u; base < all.count; base += kClusterBatchLights) {
        uint slot = min(base / kClusterBatchLights, kClusterCachedBatches - 1u);
        markCandidates(all, base, slot, rectLo, rectHi, 0u, params.dims.z - 1u, lane);
        for (uint w = 0u; w < kClusterAssignGroupSize; ++w) total += bitCount(candidateMask[slot * kClusterAssignGroupSize + w]);
    }
    if (lane == 0u) {
        uint offset = total > 0u ? atomicAdd(counters.values.w, total) : 0u;
        bool fits = offset + total <= params.lightInfo.w && offset + total >= offset;
        blockRanges[blockIndex(block)] = uvec2(fits ? offset : 0u, fits ? total : kClusterBlockOverflow);
        columnMask[0] = fits ? offset : kClusterBlockOverflow;
    }
    barrier();
    uint offset = columnMask[0];
    if (offset == kClusterBlockOverflow || total == 0u) return;
    uint written = 0u;
    for (uint base = 0u; base < all.count; base += kClusterBatchLights) {
        uint batch = base / kClusterBatchLights;
        uint slot = min(batch, kClusterCachedBatches - 1u);
        if (markedAgain(batch, all.count)) markCandidates(all, base, slot, rectLo, rectHi, 0u, params.dims.z - 1u, lane);
        // Word `lane`'s lights go after the lights of the words before it.
        uint before = 0u;
        uint inBatch = 0u;
        for (uint w = 0u; w < kClusterAssignGroupSize; ++w) {
            uint n = bitCount(candidateMask[slot * kClusterAssignGroupSize + w]);
            before += w < lane ? n : 0u;
            inBatch += n;
        }
        uint mask = candidateMask[slot * kClusterAssignGroupSize + lane];
        uint at = offset + written + before;
        while (mask != 0u) {
            uint bit = uint(findLSB(mask));
            mask &= mask - 1u;
            blockIndices[at++] = base + lane * 32u + bit;
        }
        written += inBatch;
    }
}

void assignPass() {
    uvec2 tile = gl_WorkGroupID.xy;
    uint lane = gl_LocalInvocationIndex;
    uint localCount = params.lightInfo.y;
    // The tile's block list (every chunk of slices reads the same).
    uvec2 listRange = blockRanges[blockIndex(tile / kClusterBlockTiles)];
    for (uint zBase = 0u; zBase < params.dims.z; zBase += kClusterAssignGroupSize) {
        uint z = zBase + lane;
        bool inGrid = z < params.dims.z;
        bool lastSlice = z + 1u >= params.dims.z;
        Froxel fr;
        fr.f = uvec3(tile, z);
        fr.row0 = rowPlane(tile.y);
        fr.row1 = rowPlane(tile.y + 1u);
        fr.column0 = columnPlane(tile.x);
        fr.column1 = columnPlane(tile.x + 1u);
        fr.d0 = inGrid ? sliceStart(z) * (1.0 - params.slack.x) : 0.0;
        fr.d1 = inGrid && !lastSlice ? sliceStart(z + 1u) * (1.0 + params.slack.x) : 0.0;
        fr.lastSlice = lastSlice;
        fr.surfaces = inGrid && params.slicing.z > 0.0;
        fr.hasSlab = false;
        bool occupied = inGrid;
        if (fr.surfaces) {
            // Only where the frame's surfaces are in this froxel (none: an empty list).
            uint tiles = params.dims.x * params.dims.y;
            vec4 extent = surfaces[z * tiles + tile.y * params.dims.x + tile.x];
            vec4 axis = surfaces[params.dims.z * tiles + tile.y * params.dims.x + tile.x];
            fr.bandD0 = max(fr.d0, extent.x);
            fr.bandD1 = lastSlice ? extent.y : min(fr.d1, extent.y);
            fr.hasSlab = axis.w > 0.0;
            fr.slabLow = vec4(axis.xyz, -extent.z);
            fr.slabHigh = vec4(axis.xyz, -extent.w);
            occupied = fr.bandD0 <= fr.bandD1;
        }

        // The chunk's occupied slices: lights reaching none of them are not candidates, and a
        // chunk without surfaces in this tile tests no light.
        barrier();
        if (lane == 0u) {
            occupiedLo = 0xffffffffu;
            occupiedHi = 0u;
        }
        barrier();
        if (occupied) {
            atomicMin(occupiedLo, z);
            atomicMax(occupiedHi, z);
        }
        barrier();
        uint zLo = occupiedLo;
        uint zHi = occupiedHi;
        Candidates c = Candidates(false, 0u, zLo <= zHi ? localCount : 0u);
        if (listRange.y != kClusterBlockOverflow) c = Candidates(true, listRange.x, zLo <= zHi ? listRange.y : 0u);

        uint found = 0u;
        for (uint base = 0u; base < c.count; base += kClusterBatchLights) {
            uint slot = min(base / kClusterBatchLights, kClusterCachedBatches - 1u);
            markCandidates(c, base, slot, tile, tile, zLo, zHi, lane);
            if (!occupied) continue;
            for (uint w = 0u; w < kClusterAssignGroupSize; ++w) {
                uint mask = candidateMask[slot * kClusterAssignGroupSize + w];
                while (mask != 0u) {
                    uint bit = uint(findLSB(mask));
                    mask &= mask - 1u;
                    if (froxelTouched(candidateLight(c, base + w * 32u + bit), fr)) ++found;
                }
            }
        }

        uint keep = 0u;
        uint offset = 0u;
        if (inGrid) {
            keep = min(found, params.dims.w);
            offset = atomicAdd(counters.values.x, keep);
            uint capacity = params.lightInfo.z;
            keep = min(keep, offset < capacity ? capacity - offset : 0u);
            if (keep < found) atomicAdd(counters.values.y, 1u);
            atomicAdd(counters.values.z, found);
            ranges[(z * params.dims.y + tile.y) * params.dims.x + tile.x] = uvec2(min(offset, capacity), keep);
        }

        uint written = 0u;
        for (uint base = 0u; base < c.count; base += kClusterBatchLights) {
            // The counting sweep's masks are still in place, but for the batches sharing the last slot.
            uint batch = base / kClusterBatchLights;
            uint slot = min(batch, kClusterCachedBatches - 1u);
            if (markedAgain(batch, c.count)) markCandidates(c, base, slot, tile, tile, zLo, zHi, lane);
            for (uint w = 0u; w < kClusterAssignGroupSize && written < keep; ++w) {
                uint mask = candidateMask[slot * kClusterAssignGroupSize + w];
                while (mask != 0u && written < keep) {
                    uint bit = uint(findLSB(mask));
                    mask &= mask - 1u;
                    uint i = candidateLight(c, base + w * 32u + bit);
                    if (froxelTouched(i, fr)) {
                        indices[offset + written] = params.lightInfo.x + i;
                        ++written;
                    }
                }
            }
        }
    }
}

void main() {
    if (kPass == kClusterPassVolumes) volumePass();
    else if (kPass == kClusterPassBlocks) blocksPass();
    else assignPass();
}
