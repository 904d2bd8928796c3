#include "lights/ClusterBuilder.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace preskin {

namespace {

// View depth d (metres, > 0) -> NDC depth of the view's projection.
float ndcDepth(const glm::mat4& clipFromView, float d) {
    const glm::vec4 clip = clipFromView * glm::vec4(0.0f, 0.0f, -d, 1.0f);
    return clip.z / clip.w;
}

float sliceNear(const ClusterGridShape& s, uint32_t z, float nearM) {
    if (z == 0) return nearM;
    return std::exp2((float(z) - s.sliceBias) / s.sliceScale);
}

bool sphereIntersectsBox(const glm::vec3& c, float r, const glm::vec3& lo, const glm::vec3& hi) {
    const glm::vec3 q = glm::clamp(c, lo, hi);
    const glm::vec3 d = c - q;
    return glm::dot(d, d) <= r * r;
}

// Cone (apex, unit axis, half angle, range) against a sphere; false only when disjoint.
bool coneIntersectsSphere(const glm::vec3& apex, const glm::vec3& axis, float cosAngle, float sinAngle, float range,
                          const glm::vec3& center, float radius) {
    const glm::vec3 v = center - apex;
    const float lenSq = glm::dot(v, v);
    const float along = glm::dot(v, axis);
    const float closest = cosAngle * std::sqrt(std::max(lenSq - along * along, 0.0f)) - along * sinAngle;
    const bool angleCull = closest > radius;
    const bool frontCull = along > radius + range;
    const bool backCull = along < -radius;
    return !(angleCull || frontCull || backCull);
}

}  // namespace

ClusterGridShape clusterGridShape(const ClusterSettings& settings, const View& view, VkExtent2D extent) {
    ClusterGridShape s;
    s.tileSizePx = std::clamp<uint32_t>(settings.tileSizePx, 8, 1024);
    s.dims.x = (extent.width + s.tileSizePx - 1) / s.tileSizePx;
    s.dims.y = (extent.height + s.tileSizePx - 1) / s.tileSizePx;
    s.dims.z = std::clamp<uint32_t>(settings.depthSlices, 2, 128);
    s.farM = std::max(view.farM, view.nearM * 4.0f);
    s.nearSliceM = std::clamp(settings.nearSliceM, view.nearM * 1.001f, s.farM * 0.5f);
    // Slice 1 starts at nearSliceM, slice dims.z ends at farM.
    s.sliceScale = float(s.dims.z - 1) / std::log2(s.farM / s.nearSliceM);
    s.sliceBias = 1.0f - std::log2(s.nearSliceM) * s.sliceScale;
    return s;
}

void froxelBounds(const ClusterGridShape& s, const View& view, VkExtent2D extent, glm::uvec3 f, glm::vec3& minVs,
                  glm::vec3& maxVs) {
    const glm::mat4 viewFromClip = glm::inverse(view.clipFromView);
    const float x0 = float(f.x * s.tileSizePx) / float(extent.width) * 2.0f - 1.0f;
    const float x1 = std::min(float((f.x + 1) * s.tileSizePx) / float(extent.width), 1.0f) * 2.0f - 1.0f;
    const float y0 = float(f.y * s.tileSizePx) / float(extent.height) * 2.0f - 1.0f;
    const float y1 = std::min(float((f.y + 1) * s.tileSizePx) / float(extent.height), 1.0f) * 2.0f - 1.0f;
    const float d0 = sliceNear(s, f.z, view.nearM);
    // The last slice reaches to infinity: fragments beyond farM are clamped into it.
    const float d1 = f.z + 1 >= s.dims.z ? std::numeric_limits<float>::infinity() : sliceNear(s, f.z + 1, view.nearM);
    minVs = glm::vec3(std::numeric_limits<float>::max());
    maxVs = glm::vec3(-std::numeric_limits<float>::max());
    for (float d : {d0, std::min(d1, s.farM * 1e3f)}) {
        const float z = ndcDepth(view.clipFromView, d);
        for (float x : {x0, x1})
            for (float y : {y0, y1}) {
                glm::vec4 p = viewFromClip * glm::vec4(x, y, z, 1.0f);
                p /= p.w;
                minVs = glm::min(minVs, glm::vec3(p));
                maxVs = glm::max(maxVs, glm::vec3(p));
            }
    }
    if (std::isinf(d1)) minVs.z = -std::numeric_limits<float>::max();
}

ClusterLists buildClusters(const ClusterSettings& settings, const View& view, VkExtent2D extent,
                           std::span<const gpu::GpuLight> lights, uint32_t firstLocal) {
    ClusterLists out;
    const ClusterGridShape s = clusterGridShape(settings, view, extent);
    out.shape = s;
    const uint32_t count = s.dims.x * s.dims.y * s.dims.z;
    std::vector<glm::vec3> boxMin(count), boxMax(count), sphereCenter(count);
    std::vector<float> sphereRadius(count);
    for (uint32_t z = 0; z < s.dims.z; ++z)
        for (uint32_t y = 0; y < s.dims.y; ++y)
            for (uint32_t x = 0; x < s.dims.x; ++x) {
                const uint32_t i = (z * s.dims.y + y) * s.dims.x + x;
                froxelBounds(s, view, extent, {x, y, z}, boxMin[i], boxMax[i]);
                sphereCenter[i] = 0.5f * (boxMin[i] + boxMax[i]);
                sphereRadius[i] = 0.5f * glm::length(boxMax[i] - boxMin[i]);
            }

    std::vector<std::vector<uint32_t>> lists(count);
    const glm::mat3 viewRot(view.viewFromWorld);
    for (uint32_t li = firstLocal; li < lights.size(); ++li) {
        const gpu::GpuLight& light = lights[li];
        const float range = light.positionRange.w;
        const glm::vec3 centerVs = glm::vec3(view.viewFromWorld * glm::vec4(glm::vec3(light.positionRange), 1.0f));
        const bool spot = uint32_t(light.directionType.w) == gpu::kLightSpot;
        const glm::vec3 axisVs = glm::normalize(viewRot * glm::vec3(light.directionType));
        // Half angle of the cone from the attenuation scale/offset: zero at cos(outer) = -offset/scale.
        const float cosOuter = std::clamp(-light.spotScaleOffset.y / light.spotScaleOffset.x, -1.0f, 1.0f);
        const float sinOuter = std::sqrt(std::max(1.0f - cosOuter * cosOuter, 0.0f));
        for (uint32_t i = 0; i < count; ++i) {
            if (range > 0.0f) {
                if (!sphereIntersectsBox(centerVs, range, boxMin[i], boxMax[i])) continue;
                if (spot && !coneIntersectsSphere(centerVs, axisVs, cosOuter, sinOuter, range, sphereCenter[i],
                                                  sphereRadius[i]))
                    continue;
            }
            lists[i].push_back(li);
        }
    }
    out.ranges.resize(count);
    const uint32_t cap = std::max<uint32_t>(settings.maxLightsPerCluster, 1);
    for (uint32_t i = 0; i < count; ++i) {
        const uint32_t n = std::min<uint32_t>(static_cast<uint32_t>(lists[i].size()), cap);
        if (lists[i].size() > cap) ++out.overflows;
        out.ranges[i] = glm::uvec2(static_cast<uint32_t>(out.indices.size()), n);
        out.indices.insert(out.indices.end(), lists[i].begin(), lists[i].begin() + n);
    }
    return out;
}

void ClusterBuilder::build(uint32_t slot, const ClusterSettings& settings, const View& view, VkExtent2D extent,
                           std::span<const gpu::GpuLight> lights, uint32_t firstLocal, gpu::FrameUniforms& frame) {
    const auto start = std::chrono::steady_clock::now();
    const ClusterLists lists = buildClusters(settings, view, extent, lights, firstLocal);
    auto upload = [&](vk::Buffer& buffer, const void* data, size_t bytes) {
        if (!buffer || buffer.size() < std::max<size_t>(bytes, 16))
            buffer = vk::Buffer(device_, std::max<size_t>(bytes, 16) * 2, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
        buffer.upload(data, bytes);
    };
    upload(ranges_[slot], lists.ranges.data(), lists.ranges.size() * sizeof(glm::uvec2));
    upload(indices_[slot], lists.indices.data(), lists.indices.size() * sizeof(uint32_t));
    overflows_[slot] = lists.overflows;
    const ClusterGridShape& s = lists.shape;
    frame.clusterScale = glm::vec4(1.0f / float(s.tileSizePx), 1.0f / float(s.tileSizePx), s.sliceScale, s.sliceBias);
    frame.clusterDims = glm::uvec4(s.dims, std::max<uint32_t>(settings.maxLightsPerCluster, 1));
    frame.lightCounts.z = static_cast<uint32_t>(lists.indices.size());
    buildMs_[slot] = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

const vk::Buffer& ClusterBuilder::ranges(uint32_t slot) {
    if (!ranges_[slot]) ranges_[slot] = vk::Buffer(device_, 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
    return ranges_[slot];
}

const vk::Buffer& ClusterBuilder::indices(uint32_t slot) {
    if (!indices_[slot]) indices_[slot] = vk::Buffer(device_, 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
    return indices_[slot];
}

}  // namespace preskin
