// The renderer's light grid per frame slot: builds the froxel lists on the CPU (ClusterAssigner,
// uploaded into host-visible buffers) or records the compute build (shaders/cluster_build.comp,
// device-local buffers), per ClusterSettings::build; Auto picks the CPU on CPU devices such as
// lavapipe, where it measured faster (docs/clustering.md), and the compute pass elsewhere.
// With the frame's surfaces both builds bound each froxel's list by the depths its surfaces
// occupy (ClusterSurfaces.h). Grid rules and the overflow rule: <preskin/ClusterGrid.h>.
#pragma once

#include <preskin/ClusterGrid.h>

#include "lights/ClusterAssign.h"
#include "lights/ClusterGeometry.h"
#include "lights/ClusterSurfaces.h"
#include "vk/Resources.h"

#include <array>
#include <span>
#include <vector>

namespace preskin {

class ClusterBuilder {
public:
    static constexpr uint32_t kSlots = 2;

    explicit ClusterBuilder(const vk::Device& device);
    ~ClusterBuilder();
    ClusterBuilder(const ClusterBuilder&) = delete;
    ClusterBuilder& operator=(const ClusterBuilder&) = delete;

    // What the forward pass needs to read the lists of one prepare(): the froxel lookup's
    // parameters (shared/cluster_lookup.h) and the index list's capacity.
    struct FrameGrid {
        glm::mat4 clusterFromWorld{1.0f};
        glm::vec4 lookupScale{1.0f};
        glm::uvec4 dims{1u};  // xyz froxels, w the per-froxel cap
        uint32_t indexCapacity = 0;
    };

    // This frame's lists for `slot`, for the cluster camera of the frame's view: the CPU build
    // runs (and uploads) here; the compute build's inputs are written here and its passes
    // recorded by record(). `lights` are the frame's point and spot lights as the grid bounds
    // them (clusterLight), written with their records in the light array the shaders read
    // (`lightBuffer`): light i is entry firstLocal + i, its `index`.
    // `surfaces`: the triangles the forward pass draws this frame (ClusterSurfaces; may be empty).
    FrameGrid prepare(uint32_t slot, const ClusterSettings& settings, const ClusterCamera& camera,
                      const Bounds& sceneBounds, std::span<const ClusterLight> lights, uint32_t firstLocal,
                      const vk::Buffer& lightBuffer, const ClusterSurfaces& surfaces = {});
    // Records the compute build of the last prepare() of this slot (nothing for a CPU build),
    // ending with a barrier that makes the lists visible to fragment shaders.
    void record(VkCommandBuffer cmd, uint32_t slot);

    const vk::Buffer& ranges(uint32_t slot);
    const vk::Buffer& indices(uint32_t slot);
    bool usesGpu(uint32_t slot) const { return slots_[slot].gpu; }
    // Froxels that lost lights in the slot's last frame (the compute build's counter is read
    // back, so call it once that frame has finished).
    uint32_t overflows(uint32_t slot) const;
    // Bytes of the slot's light-grid buffers as allocated (froxel ranges and light indices, where
    // the surfaces are per froxel; for the compute build also its per-light volumes), headroom included.
    uint64_t gridBytes(uint32_t slot) const;
    // The compute build's block lists (the lights meeting each block of tiles) hold at most this
    // many entries from the next build on; a block whose list does not fit has its tiles test
    // every light. The default fits every frame's lists but the most crowded; tests lower it.
    void limitBlockList(uint32_t entries) { blockListLimit_ = entries; }
    // The grid shape of the slot's last prepare() (its tile size the automatic one where chosen).
    const ClusterGridShape& shape(uint32_t slot) const { return slots_[slot].shape; }
    // CPU time of the last prepare() of the slot (the whole build, or the compute build's setup).
    double buildMs(uint32_t slot) const { return slots_[slot].buildMs; }
    // The slot's last lists, read back from whichever build made them (waits for the device).
    ClusterGrid readBack(uint32_t slot);

private:
    struct Slot {
        bool gpu = false;
        bool pending = false;  // a compute build to record
        double buildMs = 0.0;
        uint32_t overflows = 0;  // CPU build
        ClusterCamera camera;
        ClusterGridShape shape;
        uint32_t localLights = 0;
        uint32_t indexCapacity = 0;
        vk::Buffer cpuRanges, cpuIndices;           // host-visible, CPU build
        vk::Buffer params, geometry, counters;      // host-visible, compute build
        vk::Buffer surfaces;                        // host-visible, compute build: per froxel (ClusterSurfaces.h)
        vk::Buffer volumes, gpuRanges, gpuIndices;  // device-local, compute build
        vk::Buffer tileBoxes;                       // device-local, compute build: each light's tile box
        vk::Buffer blockRanges, blockIndices;       // device-local, compute build: the lights of each block of tiles
        glm::uvec2 blocks{0u};                      // blocks across, down
        VkDescriptorSet set = VK_NULL_HANDLE;
    };

    bool useGpu(const ClusterSettings& settings) const;
    void createPipelines();
    void prepareGpu(Slot& s, const ClusterSettings& settings, const ClusterGeometry& geometry, const Eye& camera,
                    uint32_t firstLocal, uint32_t localCount, const vk::Buffer& lightBuffer);

    const vk::Device& device_;
    ClusterGeometry geometry_;  // this frame's, its memory kept between frames
    ClusterAssigner assigner_;
    ClusterGrid cpuGrid_;
    FroxelSurfaces froxelSurfaces_;  // this frame's (empty: none)
    // What froxelSurfaces_ was computed from (ClusterSurfaces::version 0: never reused).
    struct SurfacesKey {
        uint64_t version = 0;
        float outsidePx = 0.0f;
        glm::mat4 viewFromWorld{0.0f};
        glm::mat4 clipFromView{0.0f};
        glm::uvec2 extentPx{0u};
        std::vector<glm::vec4> viewpoints;
        glm::uvec3 dims{0u};
        uint32_t tileSizePx = 0;
        glm::vec4 depths{0.0f};  // near, log start, log end
        bool operator==(const SurfacesKey&) const = default;
    };
    SurfacesKey surfacesKey_;
    std::array<Slot, kSlots> slots_;
    VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
    VkPipelineLayout pipelineLayout_ = VK_NULL_HANDLE;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    VkPipeline volumePipeline_ = VK_NULL_HANDLE;
    VkPipeline assignPipeline_ = VK_NULL_HANDLE;
    VkPipeline blocksPipeline_ = VK_NULL_HANDLE;
    uint32_t blockListLimit_ = 0xffffffffu;
};

}  // namespace preskin
