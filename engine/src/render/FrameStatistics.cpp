// A finished frame's figures (Renderer::frameStats): the light grid's build and shape, the
// baselines' extra passes and targets, and the GPU time of every pass from the slot's timestamp
// queries (written by Renderer::Impl::record in frame order).
#include "render/RendererImpl.h"

#include "lights/ClusterBuilder.h"
#include "vk/ContextAccess.h"

#include <algorithm>
#include <array>

namespace preskin {

FrameStats Renderer::Impl::stats(uint32_t slotIndex) const {
    FrameStats s;
    if (slotIndex >= kSlotCount) return s;
    const Slot& slot = slots[slotIndex];
    s.wallMs = slot.wallMs;
    s.lightCount = slot.lightCount;
    s.clusterOverflows = clusters->overflows(slotIndex);
    s.clusterBuildCpuMs = settings.lightLoop == LightLoop::Clustered ? clusters->buildMs(slotIndex) : 0.0;
    s.clusterBuildGpu = settings.lightLoop == LightLoop::Clustered && clusters->usesGpu(slotIndex);
    s.clusterGridBytes = settings.lightLoop == LightLoop::Clustered ? clusters->gridBytes(slotIndex) : 0;
    if (settings.lightLoop == LightLoop::Clustered) {
        s.clusterDims = clusters->shape(slotIndex).dims;
        s.clusterTileSizePx = clusters->shape(slotIndex).tileSizePx;
    }
    s.recordCpuMs = std::max(slot.recordMs - s.clusterBuildCpuMs, 0.0);
    s.eyes = slot.eyes;
    s.eyeDrawing = eyeDrawing();
    if (slot.split && screenDiffusion) {
        s.diffusionPasses = ScreenDiffusion::kPasses;
        s.diffusionTargets = screenDiffusion->targetCount();
        s.diffusionTargetBytes = screenDiffusion->targetBytes();
    }
    if (slot.texture && textureDiffusion) {
        s.diffusionPasses = textureDiffusion->passesPerFrame(layerMaterials);
        s.diffusionTargets = TextureDiffusion::kTargets;
        s.diffusionTargetBytes = textureDiffusion->targetBytes();
    }
    if (!slot.recorded || !slot.queries) return s;
    std::array<uint64_t, kQueryCount> ticks{};
    // 0..6 every frame (6: the shadow map drawn, its reduction next), the baselines' passes 7 and 8.
    const uint32_t written = slot.split || slot.texture ? kQueryCount : kQueryCount - 2;
    const VkResult r = vkGetQueryPoolResults(dev.device(), slot.queries, 0, written, written * sizeof(uint64_t),
                                             ticks.data(), sizeof(uint64_t), VK_QUERY_RESULT_64_BIT);
    if (r != VK_SUCCESS) return s;
    const double toMs = double(dev.timestampPeriodNs()) * 1e-6;
    auto ms = [&](int a, int b) { return double(ticks[size_t(b)] - ticks[size_t(a)]) * toMs; };
    s.passes = {{"deform", ms(0, 1)},           {"curvature", ms(1, 2)}, {"shadow", ms(2, 6)},
                {"shadow reduction", ms(6, 3)},  // the wide shadow map skin reads (0 without skin)
                {"clusters", ms(3, 4)},         {"forward", ms(4, 5)}};
    s.gpuMs = ms(0, 5);
    if (slot.texture) {
        s.passes[5] = {"texture irradiance", ms(4, 7)};
        s.passes.push_back({"texture blur", ms(7, 8)});
        s.passes.push_back({"forward", ms(8, 5)});
    }
    if (slot.split) {
        s.passes.push_back({"diffusion rows", ms(5, 7)});
        s.passes.push_back({"diffusion columns", ms(7, 8)});
        s.gpuMs = ms(0, 8);
    }
    return s;
}

}  // namespace preskin
