// The forward pass of the sample renderer: its pipelines (one per material model, alpha mode,
// sidedness, target and depth format, debug view, skin techniques, light loop, eye count,
// samples and eye drawing), its own attachments (depth unless the host's, multisampled colour),
// and the recording of every draw of every eye into the host's or the headless target.
#include "render/RendererImpl.h"

#include "render/DisplayFormat.h"

#include <preskin/LightRecord.h>
#include <preskin/NormalBasis.h>
#include <preskin/Tonemap.h>

#include "shared/gpu_types.h"
#include "vk/Check.h"
#include "vk/Pipeline.h"

#include <fmt/core.h>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <bit>

namespace preskin {

namespace {

constexpr VkColorComponentFlags kAllComponents =
    VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;

VkImageAspectFlags depthAspect(VkFormat format) {
    switch (format) {
    case VK_FORMAT_D16_UNORM_S8_UINT:
    case VK_FORMAT_D24_UNORM_S8_UINT:
    case VK_FORMAT_D32_SFLOAT_S8_UINT: return VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT;
    default: return VK_IMAGE_ASPECT_DEPTH_BIT;
    }
}

}  // namespace

// The area light types among `lights`: bit (type - kLightSphere) each, a directional light with an
// angular radius of kCapShadingMinAngularRadius or more as a sphere, and kAreaLightSizedShadow for
// a shadow light with any (kSpecAreaLights).
uint32_t areaLightTypes(const std::vector<Light>& lights) {
    uint32_t bits = 0;
    for (const Light& l : lights) {
        if (isAreaLight(l.type)) bits |= 1u << (uint32_t(l.type) - uint32_t(LightType::Sphere));
        if (l.type == LightType::Directional && l.angularRadius >= kCapShadingMinAngularRadius) bits |= 1u;
    }
    const int shadow = shadowLightIndex(lights);
    if (shadow >= 0 && lights[size_t(shadow)].angularRadius > 0.0f) bits |= gpu::kAreaLightSizedShadow;
    return bits;
}

uint32_t Renderer::Impl::skinMask(const GpuMaterial& m) const {
    // The baselines replace skin's diffusion: Lambert diffuse, one normal, plain shadows and
    // Lambert's SH; the skin's specular, transmission and opposing light stay.
    const uint32_t techniques = splitDiffusion() || textureDiffusionFrame()
        ? settings.skin.mask() & (gpu::kSkinTransmission | gpu::kSkinOpposingLight | gpu::kSkinDualSpecular)
        : settings.skin.mask();
    // The tier's techniques, and the table for the other lights where asked (lutOtherLights) in a
    // tier that reads it for the shadow light.
    const uint32_t tier = skinQualityMask(settings.skinQuality.value_or(m.quality));
    const uint32_t otherLights = (tier & gpu::kSkinLutShadowLight) != 0u ? gpu::kSkinLutOtherLights : 0u;
    uint32_t mask = (tier | otherLights) & techniques;
    // A frame without a shadow map has no shadow light to tell the key light by: the shadow
    // light's table goes to every light (a host without shadows keeps the table on its key).
    if (shadowMapLight() < 0 && (mask & gpu::kSkinLutShadowLight) != 0u) mask |= gpu::kSkinLutOtherLights;
    return mask;
}

PipelineKey Renderer::Impl::pipelineKey(const GpuMaterial& m, VkFormat format, VkFormat depthFormat,
                                        uint32_t eyes) const {
    const bool skin = m.skin && luts->valid();
    const uint32_t mode = splitDiffusion() ? kForwardSplit : textureDiffusionFrame() ? kForwardTexture : kForwardPlain;
    return PipelineKey{
        skin ? gpu::kModelSkin : gpu::kModelStandard,
        static_cast<uint32_t>(m.alphaMode),
        m.doubleSided ? 1u : 0u,
        static_cast<uint32_t>(format),
        static_cast<uint32_t>(depthFormat),
        static_cast<uint32_t>(settings.debugView),
        skin ? skinMask(m) : 0u,
        settings.lightLoop == LightLoop::Clustered ? gpu::kLightLoopClustered : gpu::kLightLoopAll,
        !settings.specular         ? gpu::kSpecularOff
            : settings.specularIbl ? gpu::kSpecularIbl
                                   : gpu::kSpecularSh,
        eyes,
        settings.msaaSamples,
        eyeDrawing() == EyeDrawing::InstancedLayers ? 1u : 0u,
        skin ? m.profileMix : 1u,
        skin ? m.skinInputBits() | (settings.skinTermsPerVertex ? 0u : gpu::kSkinInputTermsPerFragment) : 0u,
        settings.shadows ? frameAreaLightTypes : frameAreaLightTypes & ~gpu::kAreaLightSizedShadow,
        mode,
        skin ? std::bit_cast<std::array<uint32_t, 32>>(m.lutMapping) : std::array<uint32_t, 32>{}};
}

VkPipeline Renderer::Impl::pipeline(const PipelineKey& key) {
    auto it = pipelines.find(key);
    if (it != pipelines.end()) return it->second;
    VkPipeline p = createPipeline(key);
    pipelines.emplace(key, p);
    return p;
}

VkPipeline Renderer::Impl::createPipeline(const PipelineKey& key) const {
    return key.model == gpu::kModelBackground ? createBackgroundPipeline(key) : createForwardPipeline(key);
}

// What every pipeline of the forward pass shares: the target's formats and output mode, the
// eyes, the samples and the layout.
vk::GraphicsPipelineDesc Renderer::Impl::forwardPassDesc(const PipelineKey& key) const {
    const VkFormat format = static_cast<VkFormat>(key.format);
    vk::GraphicsPipelineDesc desc;
    desc.specialization.values.resize(gpu::kSpecCount);
    desc.specialization.values[gpu::kSpecOutputMode] =
        isDisplayFormat(format) ? gpu::kOutputTonemapped : gpu::kOutputLinear;
    desc.colorFormats = {format};
    if (key.split == kForwardSplit)
        desc.colorFormats.insert(desc.colorFormats.end(),
                                 {ScreenDiffusion::kDiffuseFormat, ScreenDiffusion::kSurfaceFormat});
    if (key.split == kTextureIrradiance) desc.colorFormats = {format, TextureDiffusion::kStretchFormat};
    desc.depthFormat = static_cast<VkFormat>(key.depthFormat);
    desc.viewMask = key.layered ? 0u : (1u << key.eyes) - 1u;
    desc.samples = static_cast<VkSampleCountFlagBits>(key.samples);
    desc.layout = forwardLayout;
    return desc;
}

VkPipeline Renderer::Impl::createForwardPipeline(const PipelineKey& key) const {
    vk::GraphicsPipelineDesc desc = forwardPassDesc(key);
    const bool irradiance = key.split == kTextureIrradiance;
    desc.vertexSpirv = shader(irradiance        ? "texture_irradiance.vert"
                                  : key.layered ? "forward_layers.vert"
                                                : "forward.vert");
    desc.fragmentSpirv = shader(key.split == kForwardSplit         ? "forward_split.frag"
                                    : key.split == kForwardTexture ? "forward_texture.frag"
                                    : irradiance                   ? "texture_irradiance.frag"
                                                                   : "forward.frag");
    desc.specialization.values[gpu::kSpecMaterialModel] = key.model;
    desc.specialization.values[gpu::kSpecDebugView] = key.debugView;
    desc.specialization.values[gpu::kSpecAlphaMode] = key.alphaMode;
    desc.specialization.values[gpu::kSpecSkinFeatures] = key.skinMask;
    desc.specialization.values[gpu::kSpecLightLoop] = key.lightLoop;
    desc.specialization.values[gpu::kSpecSpecular] = key.specular;
    desc.specialization.values[gpu::kSpecProfileMix] = key.profileMix;
    desc.specialization.values[gpu::kSpecSkinInputs] = key.skinInputs;
    desc.specialization.values[gpu::kSpecAreaLights] = key.areaLights;
    std::copy(key.lutMapping.begin(), key.lutMapping.end(), desc.specialization.values.begin() + gpu::kSpecLutMapping);
    const AlphaMode alphaMode = static_cast<AlphaMode>(key.alphaMode);
    const bool alphaToCoverage = key.samples > 1 && alphaMode == AlphaMode::Mask;
    desc.specialization.values[gpu::kSpecAlphaToCoverage] = alphaToCoverage ? 1u : 0u;
    desc.vertexBindings = {{0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX},
                           {1, sizeof(NormalBasis), VK_VERTEX_INPUT_RATE_VERTEX}};
    desc.vertexAttributes = {
        {gpu::kAttributePosition, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, positionOs)},
        {gpu::kAttributeNormal, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, normalOs)},
        {gpu::kAttributeTangent, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Vertex, tangentOs)},
        {gpu::kAttributeUv0, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(Vertex, uv0)},
        {gpu::kAttributeCurvature, 0, VK_FORMAT_R32_SFLOAT, offsetof(Vertex, curvaturePerM)},
    };
    for (uint32_t b = 0; b < gpu::kNormalBasisCount; ++b) {
        desc.vertexAttributes.push_back({gpu::kAttributeNormalBasis + b, 1, VK_FORMAT_R32G32B32_SFLOAT,
                                         uint32_t(offsetof(NormalBasis, averaged) + b * sizeof(glm::vec3))});
        desc.vertexAttributes.push_back({gpu::kAttributeOpposing + b, 1, VK_FORMAT_R32G32B32_SFLOAT,
                                         uint32_t(offsetof(NormalBasis, opposing) + b * sizeof(glm::vec3))});
    }
    desc.vertexAttributes.push_back({gpu::kAttributeOpposingCentroid, 1, VK_FORMAT_R32G32B32_SFLOAT,
                                     uint32_t(offsetof(NormalBasis, opposingCentroid))});
    desc.alphaToCoverage = alphaToCoverage;
    desc.alphaToOne = alphaToCoverage && dev.alphaToOne();
    desc.cullMode = key.doubleSided ? VK_CULL_MODE_NONE : VK_CULL_MODE_BACK_BIT;
    desc.depthWrite = alphaMode != AlphaMode::Blend;
    desc.alphaBlend = alphaMode == AlphaMode::Blend;
    if (key.split == kForwardSplit && desc.alphaBlend)
        desc.colorWriteMasks = {kAllComponents, 0, 0};  // skin's targets stay
    if (irradiance) {                                   // every texel of the UV layout, whichever way it faces
        desc.cullMode = VK_CULL_MODE_NONE;
        desc.depthTest = desc.depthWrite = desc.alphaBlend = false;
        desc.viewMask = 0;  // one layer, no multiview
    }
    if (key.depthOnly != 0u) {  // the depth prepass: the same vertex stage, no fragment stage, no colour
        desc.fragmentSpirv = {};
        desc.colorWriteMasks.assign(desc.colorFormats.size(), 0);
        desc.alphaBlend = desc.alphaToCoverage = desc.alphaToOne = false;
    }
    return vk::createGraphicsPipeline(dev, desc);
}

// The depth prepass's pipeline for a draw of `shading`'s: what the pass's attachments, the eyes and
// the sidedness need, and nothing of the material's shading, so every opaque material shares one.
// The vertex stage is the standard material's: its position is the skin one's (the same precise
// arithmetic of the same inputs), and it needs no normal basis.
PipelineKey Renderer::Impl::depthPrepassKey(const PipelineKey& shading) const {
    PipelineKey key{};
    key.model = gpu::kModelStandard;
    key.doubleSided = shading.doubleSided;
    key.format = shading.format;
    key.depthFormat = shading.depthFormat;
    key.eyes = shading.eyes;
    key.samples = shading.samples;
    key.layered = shading.layered;
    key.split = shading.split;
    key.profileMix = 1u;  // as any standard material's
    key.depthOnly = 1u;
    return key;
}

PipelineKey Renderer::Impl::backgroundKey(VkFormat format, VkFormat depthFormat, uint32_t eyes) const {
    PipelineKey key{};
    key.model = gpu::kModelBackground;
    key.format = static_cast<uint32_t>(format);
    key.depthFormat = static_cast<uint32_t>(depthFormat);
    key.eyes = eyes;
    key.samples = settings.msaaSamples;
    key.layered = eyeDrawing() == EyeDrawing::InstancedLayers ? 1u : 0u;
    key.split = splitDiffusion() ? kForwardSplit : kForwardPlain;
    return key;
}

VkPipeline Renderer::Impl::createBackgroundPipeline(const PipelineKey& key) const {
    vk::GraphicsPipelineDesc desc = forwardPassDesc(key);
    desc.vertexSpirv = shader(key.layered ? "background_layers.vert" : "background.vert");
    desc.fragmentSpirv = shader("background.frag");
    desc.cullMode = VK_CULL_MODE_NONE;
    desc.depthWrite = false;  // at the far plane: drawn only where the depth is still cleared
    if (key.split == kForwardSplit) desc.colorWriteMasks = {kAllComponents, 0, 0};  // no skin, no depth there (cleared)
    return vk::createGraphicsPipeline(dev, desc);
}

void Renderer::Impl::ensureAttachments(VkExtent2D extent, uint32_t eyes, VkFormat colorFormat, bool ownDepth,
                                       bool ownMsaaColor, uint32_t slotIndex) {
    if (!ownMsaaColor) retire(msaaColor, slotIndex);
    const auto matches = [&](const vk::Image& image, VkFormat format) {
        const vk::ImageDesc& d = image.desc();
        return image && d.width == extent.width && d.height == extent.height && d.layers == eyes &&
            d.samples == samples() && d.format == format;
    };
    const bool msaa = settings.msaaSamples > 1 && ownMsaaColor;
    if ((!ownDepth || matches(depth, kDepthFormat)) && (!msaa || matches(msaaColor, colorFormat))) return;
    retire(depth, slotIndex);
    retire(msaaColor, slotIndex);
    vk::ImageDesc d{kDepthFormat,
                    extent.width,
                    extent.height,
                    1,
                    VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                    VK_IMAGE_ASPECT_DEPTH_BIT,
                    eyes,
                    samples()};
    if (ownDepth) depth = vk::Image(dev, d);
    if (msaa) {
        d.format = colorFormat;
        d.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT;
        d.aspect = VK_IMAGE_ASPECT_COLOR_BIT;
        msaaColor = vk::Image(dev, d);
    }
}

void Renderer::Impl::recordForwardPass(VkCommandBuffer cmd, Slot& slot, uint32_t slotIndex, const RenderTarget& target,
                                       const View& view, std::span<const ScreenDiffusion::Attachment> split,
                                       bool splitTonemapped) {
    const uint32_t eyes = view.eyeCount();
    const bool msaa = settings.msaaSamples > 1;
    constexpr VkPipelineStageFlags2 kDepthStages =
        VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
    constexpr VkAccessFlags2 kColorAccess =
        VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT;
    vk::imageBarrier(cmd, target.image, VK_IMAGE_ASPECT_COLOR_BIT, target.layoutBefore,
                     VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                     VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, kColorAccess, eyes);
    // The multisampled colour: the renderer's, or the baseline's (its scene target's format).
    const vk::Image& msaaScene = split.empty() ? msaaColor : screenDiffusion->sceneMultisampled();
    auto toAttachment = [&](VkImage image) {
        vk::imageBarrier(cmd, image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                         VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                         VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                         VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                         kColorAccess, eyes);
    };
    if (msaa) toAttachment(msaaScene.handle());
    for (const ScreenDiffusion::Attachment& a : split) {
        toAttachment(a.resolved->handle());
        if (a.multisampled) toAttachment(a.multisampled->handle());
    }
    constexpr VkAccessFlags2 kDepthAccess =
        VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    const bool hostDepth = target.depth.image != VK_NULL_HANDLE;
    const VkImageLayout depthLayout =
        hostDepth ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL : VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    if (hostDepth)
        vk::imageBarrier(cmd, target.depth.image, depthAspect(target.depth.format), target.depth.layoutBefore,
                         depthLayout, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                         VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT, kDepthStages, kDepthAccess, eyes);
    else
        vk::imageBarrier(cmd, depth.handle(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED, depthLayout,
                         kDepthStages, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, kDepthStages, kDepthAccess,
                         eyes);
    VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    color.imageView = msaa ? msaaScene.view() : target.view;
    color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    color.loadOp = target.loadColor ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_CLEAR;
    color.storeOp = msaa ? VK_ATTACHMENT_STORE_OP_DONT_CARE : VK_ATTACHMENT_STORE_OP_STORE;
    const Background& background = settings.background;
    const glm::vec4 clear = background.mode == BackgroundMode::Color ? glm::vec4(background.color, 1.0f)
        : background.mode == BackgroundMode::Transparent             ? glm::vec4(0.0f)
                                                                     : glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    // The baseline's last pass tone-maps the whole frame for a display target: the clear colour,
    // meant for the display as it is, goes in as what maps to it.
    const glm::vec3 clearRgb = splitTonemapped && background.mode == BackgroundMode::Color
        ? glm::vec3(tonemapNeutralInverse(glm::dvec3(clear)))
        : glm::vec3(clear);
    color.clearValue.color = {{clearRgb.r, clearRgb.g, clearRgb.b, clear.a}};
    if (msaa) {
        color.resolveMode = VK_RESOLVE_MODE_AVERAGE_BIT;
        color.resolveImageView = target.view;
        color.resolveImageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    }
    VkRenderingAttachmentInfo depthAttachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depthAttachment.imageView = hostDepth ? target.depth.view : depth.view();
    depthAttachment.imageLayout = depthLayout;
    depthAttachment.loadOp = hostDepth && target.depth.load ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_CLEAR;
    depthAttachment.storeOp = hostDepth ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_DONT_CARE;
    depthAttachment.clearValue.depthStencil = {0.0f, 0};  // reversed Z
    VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
    info.renderArea = {{0, 0}, target.extent};
    // Every eye in one pass: one view per eye, or one layer per eye drawn by instances.
    const bool layered = eyeDrawing() == EyeDrawing::InstancedLayers;
    info.viewMask = layered ? 0u : (1u << eyes) - 1u;
    info.layerCount = layered ? eyes : 1u;
    // The baseline's attachments: cleared to 0 (no skin, no depth), resolved like the colour.
    std::vector<VkRenderingAttachmentInfo> colors{color};
    for (const ScreenDiffusion::Attachment& a : split) {
        VkRenderingAttachmentInfo extra = color;
        extra.imageView = a.multisampled ? a.multisampled->view() : a.resolved->view();
        extra.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        extra.clearValue.color = {{0.0f, 0.0f, 0.0f, 0.0f}};
        if (a.multisampled) extra.resolveImageView = a.resolved->view();
        colors.push_back(extra);
    }
    info.colorAttachmentCount = uint32_t(colors.size());
    info.pColorAttachments = colors.data();
    info.pDepthAttachment = &depthAttachment;
    vkCmdBeginRendering(cmd, &info);
    const VkViewport viewport{0.0f, 0.0f, float(target.extent.width), float(target.extent.height), 0.0f, 1.0f};
    const VkRect2D scissor{{0, 0}, target.extent};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    VkBuffer boundVertices = VK_NULL_HANDLE;
    bindGeometry(cmd, boundVertices);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, forwardLayout, 0, 1, &slot.set, 0, nullptr);

    // Opaque and masked first, then blended ones back to front (from the eyes' mean position).
    glm::vec3 eyeCenter(0.0f);
    for (const Eye& e : view.eyes) eyeCenter += e.positionWs / float(eyes);
    std::vector<const DrawItem*> order;
    for (const DrawItem& d : scene->draws) order.push_back(&d);
    auto blended = [&](const DrawItem* d) { return scene->materials[d->material].alphaMode == AlphaMode::Blend; };
    std::stable_sort(order.begin(), order.end(), [&](const DrawItem* a, const DrawItem* b) {
        if (blended(a) != blended(b)) return !blended(a);
        if (!blended(a)) return a->material < b->material;
        return glm::distance(a->centerWs, eyeCenter) > glm::distance(b->centerWs, eyeCenter);
    });
    VkPipeline bound = VK_NULL_HANDLE;
    uint32_t boundMaterial = UINT32_MAX;
    const VkFormat depthFormat = hostDepth ? target.depth.format : kDepthFormat;
    // The backdrop after the opaque and masked draws (the depth test leaves only what they did
    // not cover), before the blended ones (which blend over it).
    bool backgroundDrawn = background.mode != BackgroundMode::Environment;
    auto drawBackground = [&] {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                          pipeline(backgroundKey(target.format, depthFormat, eyes)));
        bound = VK_NULL_HANDLE;
        vkCmdDraw(cmd, 3, layered ? eyes : 1u, 0, 0);
        backgroundDrawn = true;
    };
    // Each draw's pipeline key, found once for both of its draws.
    std::vector<PipelineKey> keys;
    keys.reserve(order.size());
    for (const DrawItem* d : order)
        keys.push_back(pipelineKey(scene->materials[d->material], target.format, depthFormat, eyes));
    auto draw = [&](const DrawItem* d, const PipelineKey& key) {
        VkPipeline p = pipeline(key);
        if (p != bound) {
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p);
            bound = p;
        }
        if (d->material != boundMaterial) {
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, forwardLayout, 1, 1,
                                    &scene->materials[d->material].set, 0, nullptr);
            boundMaterial = d->material;
        }
        const uint32_t layer = drawLayers.empty() ? 0u : drawLayers[size_t(d - scene->draws.data())];
        const gpu::DrawPush push{glm::uvec4(d->instance, d->material, layer, 0)};
        vkCmdPushConstants(cmd, forwardLayout, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                           sizeof(push), &push);
        const int32_t vertexOffset = bindDrawVertices(cmd, slotIndex, *d, boundVertices);
        vkCmdDrawIndexed(cmd, d->indexCount, layered ? eyes : 1u, d->firstIndex, vertexOffset, 0);
    };
    // The depth prepass: the opaque draws' depth first, so that the shading draws below run their
    // fragment stage only where a surface is seen (the depth test, GREATER_OR_EQUAL, passes the
    // equal depth; masked materials' depth depends on their texture's alpha, blended ones write
    // none). The fragment stage is what the frame's time goes to, skin's most.
    if (settings.depthPrepass)
        for (size_t i = 0; i < order.size(); ++i)
            if (scene->materials[order[i]->material].alphaMode == AlphaMode::Opaque)
                draw(order[i], depthPrepassKey(keys[i]));
    for (size_t i = 0; i < order.size(); ++i) {
        if (!backgroundDrawn && scene->materials[order[i]->material].alphaMode == AlphaMode::Blend) drawBackground();
        draw(order[i], keys[i]);
    }
    if (!backgroundDrawn) drawBackground();
    vkCmdEndRendering(cmd);
    for (const ScreenDiffusion::Attachment& a : split)
        vk::imageBarrier(cmd, a.resolved->handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                         VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                         VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                         VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, eyes);
    vk::imageBarrier(cmd, target.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                     target.layoutAfter, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                     VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                     VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT, eyes);
    if (hostDepth && target.depth.layoutAfter != depthLayout)
        vk::imageBarrier(cmd, target.depth.image, depthAspect(target.depth.format), depthLayout,
                         target.depth.layoutAfter, kDepthStages, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                         VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                         VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT, eyes);
}

// Throws preskin::Error unless `record` can draw into the host's target as described.
void Renderer::Impl::checkTarget(const RenderTarget& target) const {
    if (target.loadColor && splitDiffusion())
        throw Error(
            "RenderTarget: loadColor needs RenderSettings::diffusion PreIntegrated (the screen-space baseline "
            "composites the whole frame)");
    if (target.loadColor && settings.msaaSamples > 1)
        throw Error(
            "RenderTarget: loadColor needs msaaSamples 1 (with MSAA preskin draws into its own "
            "multisampled colour and resolves it over the target)");
    if (target.loadColor && target.layoutBefore == VK_IMAGE_LAYOUT_UNDEFINED)
        throw Error("RenderTarget: loadColor needs the layout the host's colour is in (layoutBefore is UNDEFINED)");
    const DepthTarget& d = target.depth;
    if (!d.image) return;
    if (!d.view) throw Error("RenderTarget: depth: an image without a view");
    if (d.load && d.layoutBefore == VK_IMAGE_LAYOUT_UNDEFINED)
        throw Error("RenderTarget: depth: load needs the layout the host's depth is in (layoutBefore is UNDEFINED)");
    if (!dev.supportsFormat(d.format, VK_FORMAT_FEATURE_2_DEPTH_STENCIL_ATTACHMENT_BIT))
        throw Error(fmt::format("RenderTarget: depth: format {} is not a depth format {} can render",
                                static_cast<int>(d.format), dev.properties().deviceName));
}

}  // namespace preskin
