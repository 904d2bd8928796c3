// Light clustering (froxels): the view frustum is cut into screen tiles times depth slices
// (the first slice ends at nearSliceM, the rest are logarithmic up to the view's far distance).
// Each local light (point, spot) is assigned to every froxel its volume may touch: its range
// sphere against the froxel's view-space bounding box (conservative), then, for spots, the cone
// against the froxel's bounding sphere (Wronski, "Cull that cone!", 2017). Lights with
// unlimited range go to every froxel. Per froxel: (offset, count) into one index list.
// Overflow rule: a froxel keeps at most maxLightsPerCluster lights, the lowest light indices
// first; the froxels that dropped lights are counted (FrameStats::clusterOverflows).
// The build runs on the CPU; see the README ("Light clustering") for why and the figures.
#pragma once

#include <preskin/Renderer.h>

#include "shared/gpu_types.h"
#include "vk/Resources.h"

#include <array>
#include <span>
#include <vector>

namespace preskin {

struct ClusterGridShape {
    glm::uvec3 dims{1u};
    uint32_t tileSizePx = 64;
    float nearSliceM = 0.05f;
    float farM = 100.0f;
    // Slice of a view depth d: floor(log2(d) * sliceScale + sliceBias), clamped to [0, dims.z).
    float sliceScale = 1.0f;
    float sliceBias = 0.0f;
};

struct ClusterLists {
    ClusterGridShape shape;
    std::vector<glm::uvec2> ranges;  // per froxel (offset, count), x fastest, then y, then z
    std::vector<uint32_t> indices;   // light indices into the full light array
    uint32_t overflows = 0;
};

ClusterGridShape clusterGridShape(const ClusterSettings& settings, const View& view, VkExtent2D extent);
// View-space bounding box of one froxel.
void froxelBounds(const ClusterGridShape& shape, const View& view, VkExtent2D extent, glm::uvec3 froxel,
                  glm::vec3& minVs, glm::vec3& maxVs);
// Lights [firstLocal, lights.size()) are clustered; directional ones before firstLocal are not.
ClusterLists buildClusters(const ClusterSettings& settings, const View& view, VkExtent2D extent,
                           std::span<const gpu::GpuLight> lights, uint32_t firstLocal);

class ClusterBuilder {
public:
    explicit ClusterBuilder(const vk::Device& device) : device_(device) {}
    // Builds the lists for this frame and uploads them into the slot's buffers; fills the
    // cluster fields of `frame`.
    void build(uint32_t slot, const ClusterSettings& settings, const View& view, VkExtent2D extent,
               std::span<const gpu::GpuLight> lights, uint32_t firstLocal, gpu::FrameUniforms& frame);
    const vk::Buffer& ranges(uint32_t slot);
    const vk::Buffer& indices(uint32_t slot);
    uint32_t overflows(uint32_t slot) const { return overflows_[slot]; }
    double buildMs(uint32_t slot) const { return buildMs_[slot]; }

private:
    const vk::Device& device_;
    std::array<vk::Buffer, 2> ranges_;
    std::array<vk::Buffer, 2> indices_;
    std::array<uint32_t, 2> overflows_{};
    std::array<double, 2> buildMs_{};
};

}  // namespace preskin
