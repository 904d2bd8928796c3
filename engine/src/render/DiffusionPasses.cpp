// The baselines' parts of a frame (RenderSettings::diffusion, docs/baselines.md): the screen-space
// baseline's targets and kernels made ready (render/ScreenDiffusion.h; its passes follow the
// forward pass), and the texture-space baseline's (render/TextureDiffusion.h): its textures and
// kernels, the irradiance pass (every skin draw into its layer, laid out by TEXCOORD_0, with the
// forward pass's lights, shadows and ambient) and the blur, before the forward pass reads them.
#include "render/RendererImpl.h"

#include "shared/gpu_types.h"
#include "vk/Pipeline.h"

#include <preskin/Error.h>

#include <fmt/core.h>

namespace preskin {

ScreenDiffusion& Renderer::Impl::prepareScreenDiffusion(const RenderTarget& target, uint32_t eyes, uint32_t slotIndex) {
    if (!screenDiffusion)
        screenDiffusion = std::make_unique<ScreenDiffusion>(
            dev, [this](const char* name) { return shader(name); }, kSlotCount);
    if (diffusionKernelsStale || screenDiffusion->taps() != settings.screenDiffusionTaps) {
        screenDiffusion->setKernels(scene->sceneMaterials(), luts->layers(), settings.screenDiffusionTaps);
        diffusionKernelsStale = false;
    }
    screenDiffusion->ensureTargets(target.extent, eyes, settings.msaaSamples,
                                   [&](vk::Image& image) { retire(image, slotIndex); });
    return *screenDiffusion;
}

void Renderer::Impl::checkTextureDiffusion() const {
    if (!scene->skinWithoutUvLayout.empty())
        throw Error(fmt::format(
            "{}: {}: texture-space diffusion (--diffusion texture) lays skin out in TEXCOORD_0, and this skin "
            "material has no UV layout (no TEXCOORD_0, or every UV the same); use pre-integrated or screen-space "
            "diffusion",
            sceneName, scene->skinWithoutUvLayout.front()));
    constexpr uint64_t kMaxBytes = uint64_t(2) << 30;  // what the textures of all skin draws may hold
    uint64_t skinDraws = 0;
    for (const DrawItem& d : scene->draws) skinDraws += scene->materials[d.material].skin ? 1 : 0;
    const uint64_t size = settings.textureDiffusionSize;
    const uint64_t bytes = size * size * skinDraws * TextureDiffusion::kBytesPerTexel;
    if (bytes > kMaxBytes)
        throw Error(
            fmt::format("RenderSettings: textureDiffusionSize {}: the scene's {} skin draws would need {:.1f} "
                        "GB of irradiance textures (at most 2 GB); use a smaller size",
                        size, skinDraws, double(bytes) / double(uint64_t(1) << 30)));
}

void Renderer::Impl::prepareTextureDiffusion() {
    if (!textureDiffusion)
        textureDiffusion = std::make_unique<TextureDiffusion>(
            dev, [this](const char* name) { return shader(name); }, kSlotCount);
    if (textureKernelsStale) {
        textureDiffusion->setKernels(scene->sceneMaterials(), luts->layers());
        textureKernelsStale = false;
    }
    drawLayers.assign(scene->draws.size(), 0u);
    layerMaterials.clear();
    for (size_t i = 0; i < scene->draws.size(); ++i) {
        const uint32_t material = scene->draws[i].material;
        if (!scene->materials[material].skin) continue;
        drawLayers[i] = uint32_t(layerMaterials.size());
        layerMaterials.emplace_back(drawLayers[i], material);
    }
    textureDiffusion->ensureTargets(settings.textureDiffusionSize, uint32_t(layerMaterials.size()));
}

void Renderer::Impl::recordTextureDiffusion(VkCommandBuffer cmd, Slot& slot, uint32_t slotIndex) {
    TextureDiffusion& texture = *textureDiffusion;
    texture.beginIrradiance(cmd);
    VkBuffer boundVertices = VK_NULL_HANDLE;
    bindGeometry(cmd, boundVertices);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, forwardLayout, 0, 1, &slot.set, 0, nullptr);
    const uint32_t size = texture.size();
    for (size_t i = 0; i < scene->draws.size(); ++i) {
        const DrawItem& d = scene->draws[i];
        const GpuMaterial& m = scene->materials[d.material];
        if (!m.skin) continue;
        const std::array<VkImageView, 2> views = texture.irradianceViews(drawLayers[i]);
        std::array<VkRenderingAttachmentInfo, 2> colors{};
        for (size_t a = 0; a < 2; ++a) {
            colors[a] = {VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
            colors[a].imageView = views[a];
            colors[a].imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
            colors[a].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;  // texels off the mesh: coverage 0
            colors[a].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        }
        vk::beginColorRendering(cmd, {size, size}, colors);
        PipelineKey key = pipelineKey(m, TextureDiffusion::kIrradianceFormat, VK_FORMAT_UNDEFINED, 1);
        key.split = kTextureIrradiance;
        key.samples = 1;
        key.layered = 0;
        key.lightLoop = gpu::kLightLoopAll;  // texels anywhere on the mesh, not only in the light grid's view
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline(key));
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, forwardLayout, 1, 1, &m.set, 0, nullptr);
        const gpu::DrawPush push{glm::uvec4(d.instance, d.material, drawLayers[i], 0)};
        vkCmdPushConstants(cmd, forwardLayout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                           sizeof(push), &push);
        const int32_t vertexOffset = bindDrawVertices(cmd, slotIndex, d, boundVertices);
        vkCmdDrawIndexed(cmd, d.indexCount, 1, d.firstIndex, vertexOffset, 0);
        vkCmdEndRendering(cmd);
    }
    timestamp(cmd, slot, 7);
    texture.recordBlur(cmd, slotIndex, layerMaterials);
}

}  // namespace preskin
