// The renderer's light grid per frame slot (see ClusterBuilder.h): CPU build and upload, or the
// compute build's inputs, passes and barriers.
#include "lights/ClusterBuilder.h"

#include <preskin/Error.h>

#include "shared/cluster_build.h"
#include "vk/Check.h"
#include "vk/Pipeline.h"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cstring>

namespace preskin::shaders {
std::span<const uint32_t> spirv(std::string_view fileName);
}

namespace preskin {

namespace {

constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;

// Grows `buffer` to at least `bytes` (with headroom) when it is smaller.
void ensureBuffer(const vk::Device& device, vk::Buffer& buffer, VkDeviceSize bytes, VkBufferUsageFlags usage,
                  bool hostVisible) {
    bytes = std::max<VkDeviceSize>(bytes, 16);
    if (buffer && buffer.size() >= bytes) return;
    buffer = vk::Buffer(device, bytes + bytes / 2, usage, hostVisible);
}

}  // namespace

ClusterBuilder::ClusterBuilder(const vk::Device& device) : device_(device) {}

ClusterBuilder::~ClusterBuilder() {
    const VkDevice d = device_.device();
    if (volumePipeline_) vkDestroyPipeline(d, volumePipeline_, nullptr);
    if (assignPipeline_) vkDestroyPipeline(d, assignPipeline_, nullptr);
    if (blocksPipeline_) vkDestroyPipeline(d, blocksPipeline_, nullptr);
    if (pool_) vkDestroyDescriptorPool(d, pool_, nullptr);
    if (pipelineLayout_) vkDestroyPipelineLayout(d, pipelineLayout_, nullptr);
    if (setLayout_) vkDestroyDescriptorSetLayout(d, setLayout_, nullptr);
}

bool ClusterBuilder::useGpu(const ClusterSettings& settings) const {
    if (settings.build == ClusterBuild::Gpu) return true;
    if (settings.build == ClusterBuild::Cpu) return false;
    return device_.properties().deviceType != VK_PHYSICAL_DEVICE_TYPE_CPU;
}

void ClusterBuilder::createPipelines() {
    if (assignPipeline_) return;
    const VkShaderStageFlags cs = VK_SHADER_STAGE_COMPUTE_BIT;
    const vk::Binding bindings[] = {
        {gpu::kClusterBindingParams, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, cs},
        {gpu::kClusterBindingLights, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs},
        {gpu::kClusterBindingGeometry, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs},
        {gpu::kClusterBindingVolumes, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs},
        {gpu::kClusterBindingRanges, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs},
        {gpu::kClusterBindingIndices, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs},
        {gpu::kClusterBindingCounters, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs},
        {gpu::kClusterBindingSurfaces, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs},
        {gpu::kClusterBindingTileBoxes, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs},
        {gpu::kClusterBindingBlockRanges, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs},
        {gpu::kClusterBindingBlockIndices, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cs},
    };
    setLayout_ = vk::createSetLayout(device_, bindings);
    pipelineLayout_ = vk::createPipelineLayout(device_, std::span(&setLayout_, 1), 0, 0);
    const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kSlots},
                                          {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 10 * kSlots}};
    pool_ = vk::createDescriptorPool(device_, sizes, kSlots);
    for (Slot& s : slots_) s.set = vk::allocateDescriptorSet(device_, pool_, setLayout_);
    const auto code = shaders::spirv("cluster_build.comp");
    if (code.empty()) throw Error("internal: shader cluster_build.comp is not compiled into the library");
    vk::Specialization spec;
    spec.values = {gpu::kClusterPassVolumes};
    volumePipeline_ = vk::createComputePipeline(device_, code, pipelineLayout_, spec);
    spec.values = {gpu::kClusterPassAssign};
    assignPipeline_ = vk::createComputePipeline(device_, code, pipelineLayout_, spec);
    spec.values = {gpu::kClusterPassBlocks};
    blocksPipeline_ = vk::createComputePipeline(device_, code, pipelineLayout_, spec);
}

ClusterBuilder::FrameGrid ClusterBuilder::prepare(uint32_t slot, const ClusterSettings& settings,
                                                  const ClusterCamera& camera, const Bounds& sceneBounds,
                                                  std::span<const ClusterLight> lights, uint32_t firstLocal,
                                                  const vk::Buffer& lightBuffer, const ClusterSurfaces& surfaces) {
    const auto start = std::chrono::steady_clock::now();
    Slot& s = slots_[slot];
    const Eye& view = camera.eye;
    clusterGeometry(clusterGridShape(settings, camera, sceneBounds, lights), view, geometry_);
    const ClusterGeometry& geometry = geometry_;
    s.camera = camera;
    s.shape = geometry.shape;
    s.localLights = static_cast<uint32_t>(lights.size());
    s.gpu = useGpu(settings);
    s.pending = false;
    if (!settings.fitListsToSurfaces || surfaces.empty()) {
        froxelSurfaces_.values.clear();
        surfacesKey_ = {};
    } else {
        // The same triangles seen by the same camera into the same grid: last frame's work holds.
        const SurfacesKey key{surfaces.version,
                              surfaces.outsidePx,
                              camera.eye.viewFromWorld,
                              camera.eye.clipFromView,
                              camera.extentPx,
                              camera.viewpoints,
                              geometry.shape.dims,
                              geometry.shape.tileSizePx,
                              glm::vec4(geometry.shape.nearM, geometry.shape.logStartM, geometry.shape.logEndM, 0.0f)};
        if (surfaces.version == 0 || !(key == surfacesKey_) || froxelSurfaces_.empty()) {
            froxelSurfaces(geometry.shape, camera, surfaces, froxelSurfaces_);
            surfacesKey_ = key;
        }
    }
    if (s.gpu) {
        prepareGpu(s, settings, geometry, view, firstLocal, s.localLights, lightBuffer);
    } else {
        assigner_.build(settings, geometry, view.viewFromWorld, lights, froxelSurfaces_, cpuGrid_);
        ensureBuffer(device_, s.cpuRanges, cpuGrid_.ranges.size() * sizeof(glm::uvec2), kStorage, true);
        ensureBuffer(device_, s.cpuIndices, cpuGrid_.indices.size() * sizeof(uint32_t), kStorage, true);
        s.cpuRanges.upload(cpuGrid_.ranges.data(), cpuGrid_.ranges.size() * sizeof(glm::uvec2));
        s.cpuIndices.upload(cpuGrid_.indices.data(), cpuGrid_.indices.size() * sizeof(uint32_t));
        s.overflows = cpuGrid_.overflowedClusters;
        s.indexCapacity = static_cast<uint32_t>(cpuGrid_.indices.size());
    }
    FrameGrid grid;
    grid.clusterFromWorld = camera.clusterFromWorld();
    grid.lookupScale = geometry.shape.lookupScale();
    grid.dims = glm::uvec4(geometry.shape.dims, std::max<uint32_t>(settings.maxLightsPerCluster, 1));
    grid.indexCapacity = s.indexCapacity;
    s.buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return grid;
}

void ClusterBuilder::prepareGpu(Slot& s, const ClusterSettings& settings, const ClusterGeometry& g, const Eye& view,
                                uint32_t firstLocal, uint32_t localCount, const vk::Buffer& lightBuffer) {
    createPipelines();
    const ClusterGridShape& shape = g.shape;
    const uint64_t froxels = shape.froxelCount();
    const uint64_t perCluster = std::max<uint32_t>(settings.maxLightsPerCluster, 1);
    // The index list never needs more than every froxel full.
    const uint64_t needed = froxels * std::min<uint64_t>(perCluster, localCount);
    s.indexCapacity =
        static_cast<uint32_t>(std::max<uint64_t>(std::min<uint64_t>(settings.maxLightIndices, needed), 1));

    // Geometry: column planes, row planes, slice starts, corner lines (origin, direction).
    std::vector<glm::vec4> data;
    data.reserve(g.xPlanes.size() + g.yPlanes.size() + g.sliceStartM.size() + 2 * g.cornerOrigin.size());
    gpu::ClusterBuildParams p{};
    p.geometryOffsets.x = static_cast<uint32_t>(data.size());
    data.insert(data.end(), g.xPlanes.begin(), g.xPlanes.end());
    p.geometryOffsets.y = static_cast<uint32_t>(data.size());
    data.insert(data.end(), g.yPlanes.begin(), g.yPlanes.end());
    p.geometryOffsets.z = static_cast<uint32_t>(data.size());
    for (float d : g.sliceStartM) data.emplace_back(std::min(d, 3.0e38f), 0.0f, 0.0f, 0.0f);
    p.geometryOffsets.w = static_cast<uint32_t>(data.size());
    for (size_t i = 0; i < g.cornerOrigin.size(); ++i) {
        data.push_back(g.cornerOrigin[i]);
        data.push_back(g.cornerDir[i]);
    }
    p.viewFromWorld = view.viewFromWorld;
    p.dims = glm::uvec4(shape.dims, static_cast<uint32_t>(perCluster));
    // Blocks of tiles and their lists: a light's box meets a few blocks; a list that does not fit
    // makes its block's tiles test every light (the shader's overflow rule), so this bounds memory.
    s.blocks = (glm::uvec2(shape.dims) + gpu::kClusterBlockTiles - 1u) / gpu::kClusterBlockTiles;
    const uint64_t blockCount = uint64_t(s.blocks.x) * s.blocks.y;
    const auto blockCapacity = static_cast<uint32_t>(std::max<uint64_t>(
        std::min<uint64_t>({blockCount * localCount, 16ull * localCount + 65536ull, blockListLimit_}), 1));
    p.lightInfo = glm::uvec4(firstLocal, localCount, s.indexCapacity, blockCapacity);
    p.slack = glm::vec4(kClusterDepthSlack, kClusterRadiusSlack, kClusterConeSlack, shape.nearM);
    p.slicing = glm::vec4(shape.sliceScale, shape.sliceBias, 0.0f, 0.0f);
    if (!shape.lightBounds.empty()) {
        p.lightBoundsMin = glm::vec4(shape.lightBounds.min, 1.0f);
        p.lightBoundsMax = glm::vec4(shape.lightBounds.max, 0.0f);
    }
    p.slicing.z = froxelSurfaces_.empty() ? 0.0f : 1.0f;

    ensureBuffer(device_, s.params, sizeof(p), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true);
    ensureBuffer(device_, s.geometry, data.size() * sizeof(glm::vec4), kStorage, true);
    ensureBuffer(device_, s.counters, sizeof(gpu::ClusterCounters), kStorage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    ensureBuffer(device_, s.volumes, VkDeviceSize(std::max(localCount, 1u)) * sizeof(gpu::ClusterLightVolume), kStorage,
                 false);
    ensureBuffer(device_, s.tileBoxes, VkDeviceSize(std::max(localCount, 1u)) * sizeof(glm::uvec4), kStorage, false);
    ensureBuffer(device_, s.blockRanges, blockCount * sizeof(glm::uvec2), kStorage, false);
    ensureBuffer(device_, s.blockIndices, VkDeviceSize(blockCapacity) * sizeof(uint32_t), kStorage, false);
    ensureBuffer(device_, s.gpuRanges, froxels * sizeof(glm::uvec2), kStorage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                 false);
    ensureBuffer(device_, s.gpuIndices, VkDeviceSize(s.indexCapacity) * sizeof(uint32_t),
                 kStorage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT, false);
    ensureBuffer(device_, s.surfaces, std::max<size_t>(froxelSurfaces_.values.size(), 1) * sizeof(glm::vec4), kStorage,
                 true);
    s.params.upload(&p, sizeof(p));
    s.geometry.upload(data.data(), data.size() * sizeof(glm::vec4));
    froxelSurfaces_.fillOutsideSpans();  // the compute build reads every froxel
    if (!froxelSurfaces_.empty())
        s.surfaces.upload(froxelSurfaces_.values.data(), froxelSurfaces_.values.size() * sizeof(glm::vec4));

    const VkDescriptorBufferInfo infos[] = {
        {s.params.handle(), 0, sizeof(p)},           {lightBuffer.handle(), 0, VK_WHOLE_SIZE},
        {s.geometry.handle(), 0, VK_WHOLE_SIZE},     {s.volumes.handle(), 0, VK_WHOLE_SIZE},
        {s.gpuRanges.handle(), 0, VK_WHOLE_SIZE},    {s.gpuIndices.handle(), 0, VK_WHOLE_SIZE},
        {s.counters.handle(), 0, VK_WHOLE_SIZE},     {s.surfaces.handle(), 0, VK_WHOLE_SIZE},
        {s.tileBoxes.handle(), 0, VK_WHOLE_SIZE},    {s.blockRanges.handle(), 0, VK_WHOLE_SIZE},
        {s.blockIndices.handle(), 0, VK_WHOLE_SIZE},
    };
    const uint32_t bindings[] = {
        gpu::kClusterBindingParams,      gpu::kClusterBindingLights,      gpu::kClusterBindingGeometry,
        gpu::kClusterBindingVolumes,     gpu::kClusterBindingRanges,      gpu::kClusterBindingIndices,
        gpu::kClusterBindingCounters,    gpu::kClusterBindingSurfaces,    gpu::kClusterBindingTileBoxes,
        gpu::kClusterBindingBlockRanges, gpu::kClusterBindingBlockIndices};
    std::array<VkWriteDescriptorSet, 11> writes{};
    for (size_t i = 0; i < writes.size(); ++i) {
        writes[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        writes[i].dstSet = s.set;
        writes[i].dstBinding = bindings[i];
        writes[i].descriptorCount = 1;
        writes[i].descriptorType = i == 0 ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        writes[i].pBufferInfo = &infos[i];
    }
    vkUpdateDescriptorSets(device_.device(), static_cast<uint32_t>(writes.size()), writes.data(), 0, nullptr);
    s.pending = true;
}

void ClusterBuilder::record(VkCommandBuffer cmd, uint32_t slot) {
    Slot& s = slots_[slot];
    if (!s.gpu || !s.pending) return;
    s.pending = false;
    vkCmdFillBuffer(cmd, s.counters.handle(), 0, sizeof(gpu::ClusterCounters), 0);
    // The counters' reset, and the previous frame's reads of this slot's lists, before the build.
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                      VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelineLayout_, 0, 1, &s.set, 0, nullptr);
    if (s.localLights > 0) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, volumePipeline_);
        vkCmdDispatch(cmd, (s.localLights + gpu::kClusterAssignGroupSize - 1) / gpu::kClusterAssignGroupSize, 1, 1);
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    }
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, blocksPipeline_);
    vkCmdDispatch(cmd, s.blocks.x, s.blocks.y, 1);
    vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, assignPipeline_);
    vkCmdDispatch(cmd, s.shape.dims.x, s.shape.dims.y, 1);
    vk::memoryBarrier(
        cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
        VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_HOST_BIT,
        VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT | VK_ACCESS_2_HOST_READ_BIT);
}

const vk::Buffer& ClusterBuilder::ranges(uint32_t slot) {
    Slot& s = slots_[slot];
    vk::Buffer& b = s.gpu ? s.gpuRanges : s.cpuRanges;
    if (!b) ensureBuffer(device_, b, 16, kStorage, true);
    return b;
}

const vk::Buffer& ClusterBuilder::indices(uint32_t slot) {
    Slot& s = slots_[slot];
    vk::Buffer& b = s.gpu ? s.gpuIndices : s.cpuIndices;
    if (!b) ensureBuffer(device_, b, 16, kStorage, true);
    return b;
}

uint64_t ClusterBuilder::gridBytes(uint32_t slot) const {
    const Slot& s = slots_[slot];
    auto bytes = [](const vk::Buffer& b) -> uint64_t { return b ? b.size() : 0; };
    if (s.gpu)
        return bytes(s.gpuRanges) + bytes(s.gpuIndices) + bytes(s.volumes) + bytes(s.tileBoxes) + bytes(s.blockRanges) +
            bytes(s.blockIndices) + bytes(s.surfaces);
    return bytes(s.cpuRanges) + bytes(s.cpuIndices) + froxelSurfaces_.values.capacity() * sizeof(glm::vec4) +
        froxelSurfaces_.occupiedBits.capacity() * sizeof(uint64_t);
}

uint32_t ClusterBuilder::overflows(uint32_t slot) const {
    const Slot& s = slots_[slot];
    if (!s.gpu) return s.overflows;
    if (!s.counters) return 0;
    gpu::ClusterCounters c{};
    std::memcpy(&c, s.counters.mapped(), sizeof(c));
    return c.values.y;
}

ClusterGrid ClusterBuilder::readBack(uint32_t slot) {
    Slot& s = slots_[slot];
    ClusterGrid grid;
    if (!s.gpu) grid = cpuGrid_;
    grid.camera = s.camera;
    grid.shape = s.shape;
    if (!s.gpu) return grid;
    vkDeviceWaitIdle(device_.device());
    gpu::ClusterCounters c{};
    std::memcpy(&c, s.counters.mapped(), sizeof(c));
    grid.overflowedClusters = c.values.y;
    grid.requestedIndices = c.values.z;
    const VkDeviceSize rangeBytes = VkDeviceSize(s.shape.froxelCount()) * sizeof(glm::uvec2);
    const VkDeviceSize indexBytes = VkDeviceSize(s.indexCapacity) * sizeof(uint32_t);
    vk::Buffer host(device_, rangeBytes + indexBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    device_.submitAndWait([&](VkCommandBuffer cmd) {
        const VkBufferCopy rangeCopy{0, 0, rangeBytes};
        vkCmdCopyBuffer(cmd, s.gpuRanges.handle(), host.handle(), 1, &rangeCopy);
        const VkBufferCopy indexCopy{0, rangeBytes, indexBytes};
        vkCmdCopyBuffer(cmd, s.gpuIndices.handle(), host.handle(), 1, &indexCopy);
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    });
    grid.ranges.resize(s.shape.froxelCount());
    std::memcpy(grid.ranges.data(), host.mapped(), rangeBytes);
    grid.indices.resize(s.indexCapacity);
    std::memcpy(grid.indices.data(), static_cast<const char*>(host.mapped()) + rangeBytes, indexBytes);
    grid.indices.resize(std::min(c.values.x, s.indexCapacity));  // the entries reserved, up to the capacity
    return grid;
}

}  // namespace preskin
