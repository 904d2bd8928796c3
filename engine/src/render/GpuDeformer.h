// The renderer's per-frame deformation of animated mesh instances (skinned, or with morph targets):
// a compute pass writes each such instance's vertices in this frame's pose into a per-frame
// vertex buffer (shaders/deform.comp), the skin's normal basis moved like the normals into a
// second one, then, for meshes with skin materials that ask for it
// (SkinMaterial::deformedCurvature), recomputes per-vertex curvature from the deformed surface
// (shaders/curvature.comp). The shadow and forward passes of every eye then draw those vertices.
// Static instances are not touched: they keep drawing the scene's rest vertices.
//
// Layout: an instance's output range mirrors its mesh's range in the rest vertex buffer (same
// order, primitive after primitive), so a draw of a deformed instance only changes vertex
// buffer and vertex offset (DrawItem indices are unchanged).
// Built at load: morph deltas and joint influences per primitive; per mesh that recomputes
// curvature, the welded topology (welded vertices and their members, triangles, incident
// triangles and one-ring neighbours as adjacency lists) so every step is a gather.
#pragma once

#include <preskin/Animation.h>
#include <preskin/Scene.h>

#include "shared/deform.h"
#include "vk/Resources.h"

#include <array>
#include <cstdint>
#include <vector>

namespace preskin {

class GpuDeformer {
public:
    static constexpr uint32_t kSlots = 2;

    // `meshFirstVertex`: where each mesh's vertices start in `restVertices` (the scene's vertex
    // buffer, laid out mesh after mesh, primitive after primitive); `restNormalBasis`: the skin's
    // normal basis laid out like it (GpuScene::normalBasis).
    GpuDeformer(const vk::Device& device, const Scene& scene, const vk::Buffer& restVertices,
                const vk::Buffer& restNormalBasis, const std::vector<uint32_t>& meshFirstVertex);
    ~GpuDeformer();
    GpuDeformer(const GpuDeformer&) = delete;
    GpuDeformer& operator=(const GpuDeformer&) = delete;

    // No instance of the scene deforms.
    bool empty() const { return deformed_.empty(); }
    bool deforms(uint32_t instance) const { return instance < outputOf_.size() && outputOf_[instance] >= 0; }
    // Vertex offset to add to a rest draw's vertexOffset to draw the instance's deformed vertices
    // from output(slot).
    int32_t vertexShift(uint32_t instance) const;
    const vk::Buffer& output(uint32_t slot) const { return slots_[slot].output; }
    // This frame's normal basis of the deformed instances (vertex binding 1), laid out like output(slot).
    const vk::Buffer& normalBasisOutput(uint32_t slot) const { return slots_[slot].normalBasis; }
    uint32_t deformedInstances() const { return static_cast<uint32_t>(deformed_.size()); }
    uint32_t curvatureInstances() const;

    // Throws preskin::Error unless the pose fits the scene (instance count, a joint matrix per
    // joint of each skinned instance, finite weights and matrices).
    void check(const ScenePose& pose) const;
    // This frame's morph weights and joint matrices for `slot`, from a checked pose.
    void prepare(uint32_t slot, const ScenePose& pose);
    // Records the deformation dispatches of the slot's last prepare(), then (recordCurvature) the
    // curvature steps, ending with a barrier that makes the vertices visible to vertex input.
    void recordDeformation(VkCommandBuffer cmd, uint32_t slot);
    void recordCurvature(VkCommandBuffer cmd, uint32_t slot);

private:
    struct PrimitiveRange {
        uint32_t firstVertex = 0;  // within the mesh
        uint32_t vertexCount = 0;
        uint32_t targets = 0;
        uint32_t deltaOffset = 0;                // float index in the delta buffer
        uint32_t influenceOffset = 0xffffffffu;  // DeformInfluences index, or none
    };
    struct MeshData {
        std::vector<PrimitiveRange> primitives;
        uint32_t vertexCount = 0;
        uint32_t targets = 0;
        bool curvature = false;         // recomputes curvature
        gpu::CurvaturePush topology{};  // counts.x/y and the topology offsets; the rest per instance
        uint32_t scratchVec4s = 0;      // 3 W + T
    };
    struct DeformedInstance {
        uint32_t instance = 0;
        uint32_t mesh = 0;
        uint32_t outputFirst = 0;
        uint32_t weightOffset = 0;
        uint32_t jointOffset = 0;
        uint32_t jointCount = 0;
        bool skinned = false;
        uint32_t scratchOffset = 0;
    };
    struct Slot {
        vk::Buffer output, weights, joints, normalBasis;
        VkDescriptorSet set = VK_NULL_HANDLE;
    };

    void buildTopology(const Scene& scene, uint32_t meshIndex, std::vector<uint32_t>& topology);
    void createPipelines();

    const vk::Device& device_;
    const vk::Buffer& rest_;
    const vk::Buffer& restNormalBasis_;
    std::vector<uint32_t> meshFirstVertex_;
    std::vector<MeshData> meshes_;
    std::vector<int64_t> outputOf_;  // per scene instance: first output vertex, or -1
    std::vector<int> instanceMesh_;  // per scene instance: its mesh when deformed
    std::vector<DeformedInstance> deformed_;
    uint32_t weightCount_ = 0;
    uint32_t jointCount_ = 0;
    uint32_t outputVertices_ = 0;
    vk::Buffer deltas_, influences_, topology_, scratch_;
    std::array<Slot, kSlots> slots_;
    VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
    VkPipelineLayout deformLayout_ = VK_NULL_HANDLE;
    VkPipelineLayout curvatureLayout_ = VK_NULL_HANDLE;
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    VkPipeline deformPipeline_ = VK_NULL_HANDLE;
    std::array<VkPipeline, 4> curvaturePipelines_{};
};

}  // namespace preskin
