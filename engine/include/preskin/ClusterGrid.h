// The clustered light grid ("froxels"): the view frustum cut into screen tiles times depth
// slices, and per froxel the list of local (point and spot) lights whose volume may touch it.
// The renderer builds one per frame (on the CPU or in a compute pass, ClusterSettings::build)
// and the forward pass shades each fragment with its froxel's list only.
//
// One grid serves every eye of a view. It is built for a cluster camera (clusterCamera): for
// one eye that eye itself; for several (stereo), one perspective camera whose frustum holds
// every eye's frustum. A fragment of any eye finds its froxel by projecting its world position
// with the cluster camera (ClusterGrid::froxelAt, the same arithmetic as the forward shader),
// so every light touching that position is in the list it reads, in either eye.
//
// Depth slicing: slice 0 covers view depths [near, logStartM); slices 1 .. dims.z - 1 split
// [logStartM, logEndM] logarithmically (every froxel about as deep as it is wide); the last slice
// also holds everything beyond logEndM. A fragment at view depth d is in slice
//   clamp(floor(log2(d) * sliceScale + sliceBias), 0, dims.z - 1)
// and in tile floor(fragCoord.xy / tileSizePx). With fitDepthToScene the logarithmic range is
// the view-depth range of the scene's bounding box (clamped to [nearSliceM, view farM]), since
// no fragment lies outside it, and lights whose bounding sphere misses that box are listed
// nowhere (they reach no geometry: ClusterGridShape::lightBounds).
//
// Assignment is conservative: a light is listed in every froxel its volume (range sphere, and
// for spots the cone) touches; it may also be listed in a few it only nearly touches. Lights
// with unlimited range (range 0) are listed in every froxel (spots: every froxel their cone
// reaches). Directional lights are not clustered; shaders evaluate them for every fragment.
// With the frame's surfaces (ClusterSurfaces) "froxel" means the part of it they occupy: the
// depth interval of their triangles in its tile and slice; froxels they miss list nothing.
//
// Overflow rule (the same for the CPU and the compute build):
//  - a froxel keeps at most maxLightsPerCluster lights: the lowest light indices;
//  - the index list holds at most maxLightIndices entries: a froxel whose list would end past
//    that keeps only what fits (possibly nothing). The CPU build fills froxels in index order
//    (x fastest, then y, then z), so the last froxels lose out; the compute build reserves space
//    in whatever order its workgroups run, so which froxels lose out is unspecified there.
// Either way every froxel's list is the first entries (lowest indices) of its complete list,
// and ClusterGrid::overflowedClusters / FrameStats::clusterOverflows counts the froxels that
// lost lights. Details and figures: docs/clustering.md.
#pragma once

#include <preskin/Export.h>
#include <preskin/Scene.h>
#include <preskin/View.h>

#include <preskin/Glm.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace preskin {

// Where the light lists are built. Auto: on the CPU for CPU devices (lavapipe), where the CPU
// build measured faster (docs/clustering.md), and in a compute pass on other devices.
enum class ClusterBuild { Auto, Cpu, Gpu };

struct ClusterSettings {
    // Screen tile edge, clamped to 4..256. 0: chosen each frame from the lights, the largest of 16,
    // 8 and 4 px that the median light's bounding sphere spans 8 tiles in radius (projected at its
    // depth), so that a light is not listed for many pixels it misses; a tile under 16 px takes
    // at most 16 depth slices and the grid at most 2^20 froxels (else larger tiles).
    uint32_t tileSizePx = 0;
    uint32_t depthSlices = 32;            // clamped to 2..256
    float nearSliceM = 0.05f;             // slice 0 ends here at the earliest
    bool fitDepthToScene = true;          // slices span the scene's depth range; lights missing it unlisted
    bool fitListsToSurfaces = true;       // with ClusterSurfaces: lists bounded by where the surfaces are
    bool reuseSurfaces = true;            // renderer: a still view of an unchanged pose reuses them (version)
    uint32_t maxLightsPerCluster = 256;   // per-froxel cap (overflow rule above), >= 1
    uint32_t maxLightIndices = 1u << 23;  // capacity of the index list (overflow rule above), >= 1
    ClusterBuild build = ClusterBuild::Auto;
};

// The surfaces whose fragments read a grid's lists: triangles in world space, in the pose the
// frame draws. Given them (and ClusterSettings::fitListsToSurfaces), a froxel lists only the
// lights that reach the interval of view depths its surfaces occupy (tile by tile, slice by
// slice), and froxels no surface crosses list nothing. Fragments must then lie on these triangles'
// planes within outsidePx of the triangles: geometry drawn with the lists but not given here may
// miss lights.
struct ClusterSurfaces {
    std::span<const glm::vec3> positionsWs;
    std::span<const uint32_t> indices;  // triangle list into positionsWs
    // Per triangle, 1 where the pass culls its back face (a single-sided material; front faces
    // wind counter-clockwise seen from the eye): a triangle facing away from every eye then holds
    // no fragment. Empty: every triangle may be seen from either side.
    std::span<const uint8_t> backFaceCulled;
    // How far (pixels) a fragment's position may lie outside its triangle: 0 without MSAA (pixel
    // centres inside it); with MSAA a pixel it covers in part is shaded at the centre, up to 0.71
    // pixels away, in any eye (a stereo eye's pixels are about the cluster camera's): 1.
    float outsidePx = 1.0f;
    // Nonzero: the same version promises the same triangles, so a builder may reuse what it found
    // for them when the camera and grid are unchanged too (a static scene seen from a still view).
    uint64_t version = 0;

    bool empty() const { return indices.size() < 3; }
};

// The camera a grid is built for, and the image it covers (see clusterCamera).
struct ClusterCamera {
    Eye eye;
    glm::uvec2 extentPx{1u};
    // Where the view's eyes see from, for the surfaces' back faces (ClusterSurfaces): per eye
    // (position, 1) when perspective, (unit direction towards the eye, 0) when orthographic.
    std::vector<glm::vec4> viewpoints;

    // Rows: clip x, clip y, view depth, clip w of the camera. A world point p maps to
    // c = clusterFromWorld() * p: tile from (c.xy / c.w + 1) / 2 * extentPx, slice from c.z.
    PRESKIN_API glm::mat4 clusterFromWorld() const;
};

// The cluster camera of a view whose eyes each draw eyeWidthPx x eyeHeightPx pixels.
//  - One eye: that eye and its image.
//  - Several eyes (all perspective): a perspective camera looking along the eyes' mean
//    direction, whose angles are the union of every eye's edge directions (plus a margin of
//    1e-3 of the span, and always including the mean direction) and whose apex is moved back
//    along that direction just far enough that every eye's apex lies inside its frustum, so the
//    frustum holds every eye's whole frustum (a frustum is convex and contains an eye's apex and
//    every direction of that eye). Merging the eyes' frusta plane by plane would cut off parts
//    of asymmetric frusta; this does not. Its near plane is the nearest eye near-plane corner,
//    its image keeps eye 0's pixels per unit of tangent, so tiles keep their angular size.
// Throws preskin::Error for a view without eyes, or several eyes with an orthographic one or
// spanning 180 degrees or more together.
PRESKIN_API ClusterCamera clusterCamera(const View& view, uint32_t eyeWidthPx, uint32_t eyeHeightPx);

struct ClusterGridShape {
    glm::uvec3 dims{1u};  // tiles across, tiles down, depth slices
    uint32_t tileSizePx = 16;
    glm::uvec2 extentPx{1u};  // the image the grid covers
    float nearM = 0.01f;      // slice 0 starts here (the view's near plane)
    float logStartM = 0.05f;  // slice 1 starts here
    float logEndM = 100.0f;   // slice dims.z - 1 ends here (and also holds everything beyond)
    float sliceScale = 1.0f;
    float sliceBias = 0.0f;
    // The world box a light's bounding sphere must reach to be listed: the scene's bounds with
    // fitDepthToScene (a light that reaches no geometry lights nothing); empty: every light is.
    Bounds lightBounds;

    uint32_t froxelCount() const { return dims.x * dims.y * dims.z; }
    uint32_t froxelIndex(uint32_t x, uint32_t y, uint32_t z) const { return (z * dims.y + y) * dims.x + x; }
    // View depth where slice z begins (z = 0: nearM; z = dims.z: infinity).
    float sliceStartM(uint32_t z) const {
        if (z == 0) return nearM;
        if (z >= dims.z) return std::numeric_limits<float>::infinity();
        return std::exp2((float(z) - sliceBias) / sliceScale);
    }
    // The froxel lookup's scale (shared/cluster_lookup.h): x, y tiles per unit of NDC, z, w the
    // slices' log2 scale and bias.
    glm::vec4 lookupScale() const {
        const glm::vec2 tilesPerNdc = 0.5f * glm::vec2(extentPx) / float(tileSizePx);
        return glm::vec4(tilesPerNdc, sliceScale, sliceBias);
    }
    // The slice of a view depth, exactly as the forward shader computes it.
    uint32_t sliceOf(float viewDepthM) const {
        const float s = std::floor(std::log2(std::max(viewDepthM, 1e-6f)) * sliceScale + sliceBias);
        if (!(s > 0.0f)) return 0;
        return s >= float(dims.z - 1) ? dims.z - 1 : static_cast<uint32_t>(s);
    }
};

struct ClusterGrid {
    ClusterCamera camera;
    ClusterGridShape shape;
    std::vector<glm::uvec2> ranges;   // per froxel (offset, count) into `indices`; x fastest, then y, z
    std::vector<uint32_t> indices;    // light indices into the array given to the build
    uint32_t overflowedClusters = 0;  // froxels that lost lights to either cap
    uint64_t requestedIndices = 0;    // entries before either cap applied

    // The froxel whose list a fragment at this world position reads, computed as the forward
    // shader computes it (out-of-grid positions clamp to the nearest froxel).
    PRESKIN_API uint32_t froxelAt(const glm::vec3& positionWs) const;
};

// The grid's shape for a cluster camera. `sceneBounds` (world space) fits the logarithmic
// slices, and becomes the box lights must reach to be listed (lightBounds), when
// settings.fitDepthToScene is set and the bounds are not empty. `lights` choose the tile size
// when settings.tileSizePx is 0 (none: 16 px).
PRESKIN_API ClusterGridShape clusterGridShape(const ClusterSettings& settings, const ClusterCamera& camera,
                                              const Bounds& sceneBounds, std::span<const Light> lights = {});

// Builds the light lists on the CPU for every eye of `view` (each eye widthPx x heightPx).
// List entries are indices into `lights`; directional lights are skipped. This is the CPU
// build the renderer uses, for hosts that shade with their own forward pass; `surfaces` (the
// triangles the pass draws) bound the lists by the depths they occupy (ClusterSurfaces).
PRESKIN_API ClusterGrid buildClusterGrid(const ClusterSettings& settings, const View& view, uint32_t widthPx,
                                         uint32_t heightPx, const Bounds& sceneBounds, std::span<const Light> lights,
                                         const ClusterSurfaces& surfaces = {});

}  // namespace preskin
