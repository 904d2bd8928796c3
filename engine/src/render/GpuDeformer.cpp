// The per-frame deformation and curvature passes (see GpuDeformer.h).
#include "render/GpuDeformer.h"

#include <preskin/Error.h>

#include "scene/Weld.h"
#include "vk/Check.h"
#include "vk/Pipeline.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <span>
#include <string_view>
#include <utility>

namespace preskin::shaders {
std::span<const uint32_t> spirv(std::string_view fileName);
}

namespace preskin {

namespace {

constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;

bool meshDeforms(const Mesh& mesh, bool skinned) {
    if (skinned) return true;
    for (const Primitive& p : mesh.primitives)
        if (!p.targets.empty()) return true;
    return false;
}

// The mesh asks for curvature from its deformed surface: a skin primitive with per-vertex
// curvature that is not kept at its bind pose.
bool primitiveRecomputes(const Scene& scene, const Primitive& p) {
    if (p.material < 0 || size_t(p.material) >= scene.materials.size()) return false;
    const std::optional<SkinMaterial>& skin = scene.materials[size_t(p.material)].skin;
    return skin && skin->curvatureSource == CurvatureSource::Vertex &&
        skin->deformedCurvature == DeformedCurvature::Recomputed;
}

uint32_t groups(uint32_t n) { return (n + gpu::kDeformGroupSize - 1) / gpu::kDeformGroupSize; }

}  // namespace

GpuDeformer::GpuDeformer(const vk::Device& device, const Scene& scene, const vk::Buffer& restVertices,
                         const vk::Buffer& restNormalBasis, const std::vector<uint32_t>& meshFirstVertex)
    : device_(device), rest_(restVertices), restNormalBasis_(restNormalBasis), meshFirstVertex_(meshFirstVertex) {
    // Which instances deform, and the static data of their meshes.
    std::vector<bool> meshUsed(scene.meshes.size(), false), meshSkinned(scene.meshes.size(), false);
    outputOf_.assign(scene.instances.size(), -1);
    instanceMesh_.assign(scene.instances.size(), -1);
    for (size_t i = 0; i < scene.instances.size(); ++i) {
        const MeshInstance& inst = scene.instances[i];
        if (inst.mesh < 0 || size_t(inst.mesh) >= scene.meshes.size()) continue;
        const bool skinned = inst.skin >= 0 && size_t(inst.skin) < scene.skins.size();
        if (!meshDeforms(scene.meshes[size_t(inst.mesh)], skinned)) continue;
        meshUsed[size_t(inst.mesh)] = true;
        if (skinned) meshSkinned[size_t(inst.mesh)] = true;
    }
    std::vector<float> deltas;
    std::vector<gpu::DeformInfluences> influences;
    std::vector<uint32_t> topology;
    meshes_.resize(scene.meshes.size());
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        if (!meshUsed[m]) continue;
        MeshData& data = meshes_[m];
        for (const Primitive& p : scene.meshes[m].primitives) {
            PrimitiveRange r;
            r.firstVertex = data.vertexCount;
            r.vertexCount = static_cast<uint32_t>(p.vertices.size());
            r.targets = static_cast<uint32_t>(p.targets.size());
            r.deltaOffset = static_cast<uint32_t>(deltas.size());
            for (const MorphTarget& t : p.targets)
                for (size_t v = 0; v < p.vertices.size(); ++v) {
                    const glm::vec3 d[3] = {v < t.positionDeltas.size() ? t.positionDeltas[v] : glm::vec3(0.0f),
                                            v < t.normalDeltas.size() ? t.normalDeltas[v] : glm::vec3(0.0f),
                                            v < t.tangentDeltas.size() ? t.tangentDeltas[v] : glm::vec3(0.0f)};
                    for (const glm::vec3& x : d) deltas.insert(deltas.end(), {x.x, x.y, x.z});
                }
            if (meshSkinned[m] && p.influences.size() == p.vertices.size()) {
                r.influenceOffset = static_cast<uint32_t>(influences.size());
                for (const JointInfluences& in : p.influences)
                    influences.push_back({in.joints[0], in.joints[1], in.weights[0], in.weights[1]});
            }
            data.targets = std::max(data.targets, r.targets);
            data.vertexCount += r.vertexCount;
            data.primitives.push_back(r);
        }
        for (const Primitive& p : scene.meshes[m].primitives)
            data.curvature = data.curvature || primitiveRecomputes(scene, p);
        if (data.curvature) buildTopology(scene, uint32_t(m), topology);
    }

    // Per instance: its output range, weights, joints and curvature scratch.
    uint32_t scratchVec4s = 0;
    for (size_t i = 0; i < scene.instances.size(); ++i) {
        const MeshInstance& inst = scene.instances[i];
        if (inst.mesh < 0 || size_t(inst.mesh) >= meshes_.size() || !meshUsed[size_t(inst.mesh)]) continue;
        const bool skinned = inst.skin >= 0 && size_t(inst.skin) < scene.skins.size();
        if (!meshDeforms(scene.meshes[size_t(inst.mesh)], skinned)) continue;
        const MeshData& data = meshes_[size_t(inst.mesh)];
        DeformedInstance d;
        d.instance = static_cast<uint32_t>(i);
        d.mesh = static_cast<uint32_t>(inst.mesh);
        d.outputFirst = outputVertices_;
        d.weightOffset = weightCount_;
        d.skinned = skinned;
        d.jointOffset = jointCount_;
        d.jointCount = skinned ? static_cast<uint32_t>(scene.skins[size_t(inst.skin)].joints.size()) : 0;
        d.scratchOffset = scratchVec4s;
        if (data.curvature) scratchVec4s += data.scratchVec4s;
        outputOf_[i] = d.outputFirst;
        instanceMesh_[i] = inst.mesh;
        outputVertices_ += data.vertexCount;
        weightCount_ += data.targets;
        jointCount_ += d.jointCount;
        deformed_.push_back(d);
    }
    if (deformed_.empty()) return;

    auto upload = [&](vk::Buffer& buffer, const void* data, size_t bytes) {
        buffer = vk::Buffer(device_, std::max<size_t>(bytes, 16), kStorage, false);
        if (bytes > 0) buffer.upload(data, bytes);
    };
    upload(deltas_, deltas.data(), deltas.size() * sizeof(float));
    upload(influences_, influences.data(), influences.size() * sizeof(gpu::DeformInfluences));
    upload(topology_, topology.data(), topology.size() * sizeof(uint32_t));
    scratch_ = vk::Buffer(device_, std::max<size_t>(scratchVec4s, 1) * sizeof(glm::vec4), kStorage, false);
    for (Slot& s : slots_) {
        s.output = vk::Buffer(device_, VkDeviceSize(std::max(outputVertices_, 1u)) * sizeof(Vertex),
                              kStorage | VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT, false);
        s.weights = vk::Buffer(device_, std::max<VkDeviceSize>(weightCount_ * sizeof(float), 16), kStorage, true);
        s.joints = vk::Buffer(device_, std::max<VkDeviceSize>(jointCount_ * sizeof(glm::mat4), 64), kStorage, true);
        s.normalBasis =
            vk::Buffer(device_, VkDeviceSize(std::max(outputVertices_, 1u)) * gpu::kNormalBasisFloats * sizeof(float),
                       kStorage | VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT, false);
    }
    createPipelines();
}

GpuDeformer::~GpuDeformer() {
    const VkDevice d = device_.device();
    if (deformPipeline_) vkDestroyPipeline(d, deformPipeline_, nullptr);
    for (VkPipeline p : curvaturePipelines_)
        if (p) vkDestroyPipeline(d, p, nullptr);
    if (pool_) vkDestroyDescriptorPool(d, pool_, nullptr);
    if (deformLayout_) vkDestroyPipelineLayout(d, deformLayout_, nullptr);
    if (curvatureLayout_) vkDestroyPipelineLayout(d, curvatureLayout_, nullptr);
    if (setLayout_) vkDestroyDescriptorSetLayout(d, setLayout_, nullptr);
}

void GpuDeformer::buildTopology(const Scene& scene, uint32_t meshIndex, std::vector<uint32_t>& topology) {
    const Mesh& mesh = scene.meshes[meshIndex];
    MeshData& data = meshes_[meshIndex];
    std::vector<glm::vec3> positions, normals;
    std::vector<bool> keepRest;
    std::vector<uint32_t> indices;
    for (const Primitive& p : mesh.primitives) {
        const auto base = static_cast<uint32_t>(positions.size());
        const bool recompute = primitiveRecomputes(scene, p);
        for (const Vertex& v : p.vertices) {
            positions.push_back(v.positionOs);
            normals.push_back(v.normalOs);
            keepRest.push_back(!recompute);
        }
        for (uint32_t index : p.indices) indices.push_back(base + index);
    }
    const WeldedVertices weld = weldVertices(positions, normals);
    const uint32_t w = weld.weldedCount;

    // Triangles with three distinct welded corners, as computeVertexCurvature keeps them.
    std::vector<uint32_t> triangles;
    std::vector<std::pair<uint32_t, uint32_t>> edges;
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        const uint32_t a = weld.weldedOf[indices[t]], b = weld.weldedOf[indices[t + 1]],
                       c = weld.weldedOf[indices[t + 2]];
        if (a == b || b == c || c == a) continue;
        triangles.insert(triangles.end(), {a, b, c});
        for (auto [i, j] : {std::pair(a, b), std::pair(b, c), std::pair(c, a)})
            edges.emplace_back(std::min(i, j), std::max(i, j));
    }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    const uint32_t triangleCount = static_cast<uint32_t>(triangles.size() / 3);

    // Adjacency lists: start[W + 1] (relative) followed by the entries.
    auto appendLists = [&](const std::vector<std::vector<uint32_t>>& lists) {
        const auto offset = static_cast<uint32_t>(topology.size());
        uint32_t running = 0;
        for (const auto& list : lists) {
            topology.push_back(running);
            running += static_cast<uint32_t>(list.size());
        }
        topology.push_back(running);
        for (const auto& list : lists) topology.insert(topology.end(), list.begin(), list.end());
        return offset;
    };
    std::vector<std::vector<uint32_t>> members(w), incident(w), neighbours(w);
    for (uint32_t v = 0; v < positions.size(); ++v)
        members[weld.weldedOf[v]].push_back(v | (keepRest[v] ? gpu::kCurvatureKeepRest : 0u));
    for (uint32_t t = 0; t < triangleCount; ++t)
        for (int k = 0; k < 3; ++k) incident[triangles[size_t(3 * t + k)]].push_back(t);
    for (const auto& [i, j] : edges) {
        neighbours[i].push_back(j);
        neighbours[j].push_back(i);
    }
    gpu::CurvaturePush& push = data.topology;
    push.counts = glm::uvec4(w, triangleCount, 0u, 0u);
    push.topology.x = appendLists(members);
    push.topology.y = appendLists(incident);
    push.topology.z = appendLists(neighbours);
    push.topology.w = static_cast<uint32_t>(topology.size());
    topology.insert(topology.end(), triangles.begin(), triangles.end());
    data.scratchVec4s = 3 * w + triangleCount;
}

void GpuDeformer::createPipelines() {
    const VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
    const vk::Binding bindings[] = {
        {gpu::kDeformBindingRest, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs},
        {gpu::kDeformBindingDeltas, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs},
        {gpu::kDeformBindingInfluences, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs},
        {gpu::kDeformBindingWeights, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs},
        {gpu::kDeformBindingJoints, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs},
        {gpu::kDeformBindingOutput, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs},
        {gpu::kDeformBindingTopology, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs},
        {gpu::kDeformBindingScratch, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs},
        {gpu::kDeformBindingRestNormalBasis, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs},
        {gpu::kDeformBindingNormalBasis, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs},
    };
    setLayout_ = vk::createSetLayout(device_, bindings);
    deformLayout_ = vk::createPipelineLayout(device_, std::span(&setLayout_, 1), sizeof(gpu::DeformPush), cs);
    curvatureLayout_ = vk::createPipelineLayout(device_, std::span(&setLayout_, 1), sizeof(gpu::CurvaturePush), cs);
    constexpr uint32_t kBindings = 10;
    const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kBindings * kSlots};
    pool_ = vk::createDescriptorPool(device_, std::span(&size, 1), kSlots);
    for (Slot& s : slots_) {
        s.set = vk::allocateDescriptorSet(device_, pool_, setLayout_);
        const VkBuffer buffers[kBindings] = {rest_.handle(),        deltas_.handle(),  influences_.handle(),
                                             s.weights.handle(),    s.joints.handle(), s.output.handle(),
                                             topology_.handle(),    scratch_.handle(), restNormalBasis_.handle(),
                                             s.normalBasis.handle()};
        VkDescriptorBufferInfo infos[kBindings];
        VkWriteDescriptorSet writes[kBindings];
        for (uint32_t b = 0; b < kBindings; ++b) {
            infos[b] = {buffers[b], 0, VK_WHOLE_SIZE};
            writes[b] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
            writes[b].dstSet = s.set;
            writes[b].dstBinding = b;
            writes[b].descriptorCount = 1;
            writes[b].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
            writes[b].pBufferInfo = &infos[b];
        }
        vkUpdateDescriptorSets(device_.device(), kBindings, writes, 0, nullptr);
    }
    const auto deformCode = shaders::spirv("deform.comp");
    const auto curvatureCode = shaders::spirv("curvature.comp");
    if (deformCode.empty() || curvatureCode.empty())
        throw Error("internal: the deformation shaders are not compiled into the library");
    deformPipeline_ = vk::createComputePipeline(device_, deformCode, deformLayout_);
    for (uint32_t step = 0; step < 4; ++step) {
        vk::Specialization spec;
        spec.values = {step};
        curvaturePipelines_[step] = vk::createComputePipeline(device_, curvatureCode, curvatureLayout_, spec);
    }
}

int32_t GpuDeformer::vertexShift(uint32_t instance) const {
    if (!deforms(instance)) return 0;
    const int mesh = instanceMesh_[instance];
    return static_cast<int32_t>(outputOf_[instance] - int64_t(meshFirstVertex_[size_t(mesh)]));
}

uint32_t GpuDeformer::curvatureInstances() const {
    uint32_t n = 0;
    for (const DeformedInstance& d : deformed_) n += meshes_[d.mesh].curvature ? 1 : 0;
    return n;
}

void GpuDeformer::check(const ScenePose& pose) const {
    if (pose.instances.size() != outputOf_.size())
        throw Error(fmt::format("pose: {} instances for a scene of {}", pose.instances.size(), outputOf_.size()));
    for (const DeformedInstance& d : deformed_) {
        const InstancePose& p = pose.instances[d.instance];
        for (size_t t = 0; t < p.morphWeights.size(); ++t)
            if (!std::isfinite(p.morphWeights[t]))
                throw Error(fmt::format("pose: instance {}: morph weight {} is not finite", d.instance, t));
        if (!d.skinned) continue;
        if (p.jointMatrices.size() != d.jointCount)
            throw Error(fmt::format("pose: instance {}: {} joint matrices for a skin of {} joints", d.instance,
                                    p.jointMatrices.size(), d.jointCount));
        for (uint32_t j = 0; j < d.jointCount; ++j) {
            const glm::mat4& m = p.jointMatrices[j];
            for (int c = 0; c < 4; ++c)
                if (!std::isfinite(m[c][0] + m[c][1] + m[c][2] + m[c][3]))
                    throw Error(fmt::format("pose: instance {}: joint matrix {} is not finite", d.instance, j));
        }
    }
}

void GpuDeformer::prepare(uint32_t slotIndex, const ScenePose& pose) {
    if (deformed_.empty()) return;
    Slot& slot = slots_[slotIndex];
    auto* weights = static_cast<float*>(slot.weights.mapped());
    auto* joints = static_cast<glm::mat4*>(slot.joints.mapped());
    for (const DeformedInstance& d : deformed_) {
        const InstancePose& p = pose.instances[d.instance];
        for (uint32_t t = 0; t < meshes_[d.mesh].targets; ++t)
            weights[d.weightOffset + t] = t < p.morphWeights.size() ? p.morphWeights[t] : 0.0f;
        if (d.skinned) std::memcpy(joints + d.jointOffset, p.jointMatrices.data(), d.jointCount * sizeof(glm::mat4));
    }
}

void GpuDeformer::recordDeformation(VkCommandBuffer cmd, uint32_t slotIndex) {
    if (deformed_.empty()) return;
    Slot& slot = slots_[slotIndex];
    // The previous frame's draws from this slot's vertices, and its curvature scratch, are done.
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_VERTEX_ATTRIBUTE_INPUT_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT |
                          VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, deformLayout_, 0, 1, &slot.set, 0, nullptr);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, deformPipeline_);
    for (const DeformedInstance& d : deformed_) {
        const uint32_t meshFirst = meshFirstVertex_[d.mesh];
        for (const PrimitiveRange& r : meshes_[d.mesh].primitives) {
            if (r.vertexCount == 0) continue;
            gpu::DeformPush push{};
            push.vertices =
                glm::uvec4(meshFirst + r.firstVertex, d.outputFirst + r.firstVertex, r.vertexCount, r.targets);
            push.offsets =
                glm::uvec4(r.deltaOffset, d.skinned ? r.influenceOffset : 0xffffffffu, d.weightOffset, d.jointOffset);
            vkCmdPushConstants(cmd, deformLayout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
            vkCmdDispatch(cmd, groups(r.vertexCount), 1, 1);
        }
    }
}

void GpuDeformer::recordCurvature(VkCommandBuffer cmd, uint32_t slotIndex) {
    if (deformed_.empty()) return;
    Slot& slot = slots_[slotIndex];
    if (curvatureInstances() > 0) {
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, curvatureLayout_, 0, 1, &slot.set, 0, nullptr);
        for (uint32_t step = 0; step < 4; ++step) {
            vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                              VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                              VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, curvaturePipelines_[step]);
            for (const DeformedInstance& d : deformed_) {
                const MeshData& data = meshes_[d.mesh];
                if (!data.curvature) continue;
                gpu::CurvaturePush push = data.topology;
                push.counts.z = d.outputFirst;
                const uint32_t w = push.counts.x, t = push.counts.y;
                push.scratch = glm::uvec4(d.scratchOffset, d.scratchOffset + w, d.scratchOffset + 2 * w,
                                          d.scratchOffset + 2 * w + t);
                vkCmdPushConstants(cmd, curvatureLayout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
                vkCmdDispatch(cmd, groups(step == gpu::kCurvatureStepTriangles ? t : w), 1, 1);
            }
        }
    }
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_VERTEX_ATTRIBUTE_INPUT_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
                      VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT);
}

}  // namespace preskin
