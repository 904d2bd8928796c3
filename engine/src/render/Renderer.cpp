// Frame ordering of the sample renderer (see <preskin/Renderer.h>):
//   deformation -> curvature -> shadow pass (ShadowPass.cpp) -> light clustering (compute)
//   -> forward pass (ForwardPass.cpp); the per-frame data and the public API.
// Per-frame data (uniforms, lights, cluster lists, timestamps) lives in two slots so a host can
// keep one frame in flight while recording the next.
#include "render/RendererImpl.h"

#include <preskin/ClusterGrid.h>
#include <preskin/Error.h>
#include <preskin/ProfileLibrary.h>

#include <preskin/LightRecord.h>
#include "lights/ClusterBuilder.h"
#include "render/DisplayFormat.h"
#include "render/GpuDeformer.h"
#include "render/GpuLuts.h"
#include "render/GpuScene.h"
#include "render/InputChecks.h"
#include "render/MultiviewProbe.h"
#include "render/PoseBounds.h"
#include "render/ShadowFit.h"
#include "shared/gpu_types.h"
#include "vk/Check.h"
#include "vk/ContextAccess.h"
#include "vk/Pipeline.h"
#include "vk/Resources.h"

#include <fmt/core.h>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <glm/gtc/matrix_access.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <map>
#include <span>
#include <tuple>
#include <utility>

namespace preskin::shaders {
std::span<const uint32_t> spirv(std::string_view fileName);
}

namespace preskin {

namespace {

std::span<const uint32_t> builtinShader(const char* name) {
    auto code = shaders::spirv(name);
    if (code.empty()) throw Error(fmt::format("internal: shader {} is not compiled into the library", name));
    return code;
}

}  // namespace

static_assert(gpu::kMaxEyes == kMaxEyes, "shaders/shared and <preskin/View.h> disagree on the eye limit");
static_assert(gpu::kSkinWideShadowBits == (gpu::kSkinPenumbra | gpu::kSkinWidePenumbra));
// The enum codes the shaders branch on (shared/constants.h) are the C++ enums' values.
static_assert(gpu::kAlphaOpaque == uint32_t(AlphaMode::Opaque) && gpu::kAlphaMask == uint32_t(AlphaMode::Mask) &&
              gpu::kAlphaBlend == uint32_t(AlphaMode::Blend));
static_assert(gpu::kCurvatureSourceVertex == uint32_t(CurvatureSource::Vertex) &&
              gpu::kCurvatureSourceTexture == uint32_t(CurvatureSource::Texture) &&
              gpu::kCurvatureSourceDerivatives == uint32_t(CurvatureSource::Derivatives));
static_assert(gpu::kDebugNone == uint32_t(DebugView::None) && gpu::kDebugCurvature == uint32_t(DebugView::Curvature) &&
              gpu::kDebugNormals == uint32_t(DebugView::Normals) && gpu::kDebugShadow == uint32_t(DebugView::Shadow) &&
              gpu::kDebugPenumbra == uint32_t(DebugView::Penumbra) &&
              gpu::kDebugLightCount == uint32_t(DebugView::LightCount) &&
              gpu::kDebugShAmbient == uint32_t(DebugView::ShAmbient) &&
              gpu::kDebugTransmission == uint32_t(DebugView::Transmission));

bool finite(const glm::mat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return true;
}

uint32_t skinQualityMask(SkinQuality quality) {
    return quality == SkinQuality::Low   ? gpu::kSkinQualityLow
        : quality == SkinQuality::Medium ? gpu::kSkinQualityMedium
                                         : gpu::kSkinQualityHigh;
}

SkinFeatures skinQualityFeatures(SkinQuality quality) {
    const uint32_t m = skinQualityMask(quality);
    SkinFeatures f;
    f.lutDiffuse = (m & gpu::kSkinLutDiffuse) != 0u;
    f.normalPrefilter = (m & gpu::kSkinNormalPrefilter) != 0u;
    f.penumbra = (m & gpu::kSkinPenumbra) != 0u;
    f.shAmbient = (m & gpu::kSkinShAmbient) != 0u;
    f.transmission = (m & gpu::kSkinTransmission) != 0u;
    f.dualSpecular = (m & gpu::kSkinDualSpecular) != 0u;
    f.opposingLight = (m & gpu::kSkinOpposingLight) != 0u;
    f.normalMapLevels = (m & gpu::kSkinNormalMapLevels) != 0u;
    f.widePenumbra = (m & gpu::kSkinWidePenumbra) != 0u;
    f.lutShadowLight = (m & gpu::kSkinLutShadowLight) != 0u;
    f.fullShadowFilter = (m & gpu::kSkinFullShadowFilter) != 0u;
    f.lightCurvature = (m & gpu::kSkinLightCurvature) != 0u;
    return f;
}

uint32_t SkinFeatures::mask() const {
    return (lutDiffuse ? gpu::kSkinLutDiffuse : 0u) | (normalPrefilter ? gpu::kSkinNormalPrefilter : 0u) |
        (penumbra ? gpu::kSkinPenumbra : 0u) | (shAmbient ? gpu::kSkinShAmbient : 0u) |
        (transmission ? gpu::kSkinTransmission : 0u) | (dualSpecular ? gpu::kSkinDualSpecular : 0u) |
        (opposingLight ? gpu::kSkinOpposingLight : 0u) | (normalMapLevels ? gpu::kSkinNormalMapLevels : 0u) |
        (widePenumbra ? gpu::kSkinWidePenumbra : 0u) | (lutShadowLight ? gpu::kSkinLutShadowLight : 0u) |
        (fullShadowFilter ? gpu::kSkinFullShadowFilter : 0u) | (lutOtherLights ? gpu::kSkinLutOtherLights : 0u) |
        (lightCurvature ? gpu::kSkinLightCurvature : 0u);
}

Renderer::Impl::Impl(Context& ctx, const Scene& s, const Environment& env, const std::vector<const LutSet*>& lutLayers,
                     const RenderSettings& rs)
    : context(ctx),
      dev(ContextAccess::core(ctx)),
      settings(rs),
      lights(s.lights),
      environment(env.downsampled(kEnvironmentKeptWidth)),
      bounds(s.worldBounds()),
      sceneName(s.sourcePath.empty() ? std::string("scene") : s.sourcePath.string()) {
    checkRenderSettings(rs);
    checkLights(s.lights);
    updateEnvironmentLights(true);
    scene = std::make_unique<GpuScene>(dev, s);
    sceneHasSkin =
        std::any_of(s.materials.begin(), s.materials.end(), [](const Material& m) { return m.skin.has_value(); });
    poseBounds = std::make_unique<PoseBounds>(s);
    poseSurfaces = std::make_unique<PoseSurfaces>(s);
    surfacesPose = UINT64_MAX;
    receiverPoseBounds = std::make_unique<PoseBounds>(skinReceiverBounds(s));
    deformer = std::make_unique<GpuDeformer>(dev, s, scene->vertices, scene->normalBasis, scene->meshFirstVertex);
    setPose(restPose(s));
    setLutLayers(lutLayers);
    clusters = std::make_unique<ClusterBuilder>(dev);
    createLayouts();
    dev.submitAndWait([&](VkCommandBuffer cmd) {
        createShadowMap(cmd, 0);
        createWideShadowMap(cmd, 0);
    });
    resolveEyeDrawing();
}

Renderer::Impl::~Impl() {
    const VkDevice d = dev.device();
    vkDeviceWaitIdle(d);
    for (auto& [key, p] : pipelines) vkDestroyPipeline(d, p, nullptr);
    if (shadowPipeline) vkDestroyPipeline(d, shadowPipeline, nullptr);
    if (shadowMaskPipeline) vkDestroyPipeline(d, shadowMaskPipeline, nullptr);
    for (Slot& s : slots)
        if (s.queries) vkDestroyQueryPool(d, s.queries, nullptr);
    if (framePool) vkDestroyDescriptorPool(d, framePool, nullptr);
    if (forwardLayout) vkDestroyPipelineLayout(d, forwardLayout, nullptr);
    if (shadowLayout) vkDestroyPipelineLayout(d, shadowLayout, nullptr);
    if (frameLayout) vkDestroyDescriptorSetLayout(d, frameLayout, nullptr);
    if (shadowSampler) vkDestroySampler(d, shadowSampler, nullptr);
    if (reducePipeline) vkDestroyPipeline(d, reducePipeline, nullptr);
    if (reduceLayout) vkDestroyPipelineLayout(d, reduceLayout, nullptr);
    if (reduceSetLayout) vkDestroyDescriptorSetLayout(d, reduceSetLayout, nullptr);
}

void Renderer::Impl::createLayouts() {
    const VkDevice d = dev.device();
    const VkShaderStageFlags fs = VK_SHADER_STAGE_FRAGMENT_BIT;
    const VkShaderStageFlags all = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    const vk::Binding bindings[] = {
        {gpu::kBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, all},
        {gpu::kBindingLights, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, fs},
        {gpu::kBindingInstances, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_VERTEX_BIT},
        {gpu::kBindingShadowMap, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, fs},
        {gpu::kBindingDiffuseLut, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, all},  // per-vertex row fit
        {gpu::kBindingPenumbraLut, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, fs},
        {gpu::kBindingShTransferLut, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, all},     // per-vertex SH transfer
        {gpu::kBindingTransmittanceLut, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, all},  // per-vertex sphere term
        {gpu::kBindingClusterRanges, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, fs},
        {gpu::kBindingClusterIndices, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, fs},
        {gpu::kBindingWideShadowMap, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, fs},
        {gpu::kBindingEnvironmentImage, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, fs},
        {gpu::kBindingPrefilteredEnvironment, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, fs},
        {gpu::kBindingDfgTable, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, fs},
        {gpu::kBindingDiffusionTexture, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, fs},
    };
    frameLayout = vk::createSetLayout(dev, bindings);
    const VkDescriptorSetLayout forwardSets[] = {frameLayout, scene->materialLayout()};
    forwardLayout = vk::createPipelineLayout(dev, forwardSets, sizeof(gpu::DrawPush), all);
    shadowLayout = vk::createPipelineLayout(dev, std::span(forwardSets, 1), sizeof(gpu::DrawPush), all);

    // The wide shadow map's reduction: the shadow map in, the wide map out.
    const vk::Binding reduceBindings[] = {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_COMPUTE_BIT},
                                          {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT}};
    reduceSetLayout = vk::createSetLayout(dev, reduceBindings);
    reduceLayout =
        vk::createPipelineLayout(dev, std::span(&reduceSetLayout, 1), sizeof(uint32_t), VK_SHADER_STAGE_COMPUTE_BIT);
    reducePipeline = vk::createComputePipeline(dev, shader("shadow_reduce.comp"), reduceLayout);

    // Per slot: the frame's set (10 images) and the reduction's (1 image in, 1 out).
    const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kSlotCount},
                                          {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 4 * kSlotCount},
                                          {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 11 * kSlotCount},
                                          {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, kSlotCount}};
    framePool = vk::createDescriptorPool(dev, sizes, 2 * kSlotCount);
    for (Slot& s : slots) {
        s.set = vk::allocateDescriptorSet(dev, framePool, frameLayout);
        s.reduceSet = vk::allocateDescriptorSet(dev, framePool, reduceSetLayout);
        s.frameUniforms = vk::Buffer(dev, sizeof(gpu::FrameUniforms), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true);
        s.lights = vk::Buffer(dev, 64 * sizeof(gpu::GpuLight), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
        s.instances = vk::Buffer(dev, std::max<size_t>(scene->restInstances.size(), 1) * sizeof(gpu::GpuInstance),
                                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
        if (dev.timestampsSupported()) {
            VkQueryPoolCreateInfo q{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
            q.queryType = VK_QUERY_TYPE_TIMESTAMP;
            q.queryCount = kQueryCount;
            PRESKIN_VK(vkCreateQueryPool(d, &q, nullptr, &s.queries));
        }
    }
    VkSamplerCreateInfo nearest{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    nearest.magFilter = VK_FILTER_NEAREST;
    nearest.minFilter = VK_FILTER_NEAREST;
    nearest.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    nearest.addressModeU = nearest.addressModeV = nearest.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    PRESKIN_VK(vkCreateSampler(d, &nearest, nullptr, &shadowSampler));
}

void Renderer::Impl::updateEnvironmentLights(bool environmentChanged) {
    const int count = settings.environmentLights >= 0 ? settings.environmentLights : (lights.empty() ? 1 : 0);
    if (environmentChanged || count != extractedCount) {
        extracted = extractEnvironmentLights(environment, uint32_t(count));
        extractedCount = count;
        if (!environmentMaps) environmentMaps = std::make_unique<GpuEnvironment>(dev);
        environmentMaps->set(environment, extracted.residualImage);
    }
    frameLights = withEnvironmentLights(lights, extracted, settings.environmentLightSizes);
    extractedLights.assign(frameLights.begin() + std::ptrdiff_t(lights.size()), frameLights.end());
    frameAreaLightTypes = areaLightTypes(frameLights);
    frameShadowLight = shadowLightIndex(frameLights);
}

// Replaces an attachment without waiting: the old image lives on until every other slot
// whose last frame was recorded with it has been recorded again (the host's slot contract).
void Renderer::Impl::retire(vk::Image& image, uint32_t slotIndex) {
    uint32_t inFlight = 0;
    for (uint32_t s = 0; s < kSlotCount; ++s)
        if (s != slotIndex && slots[s].recorded) inFlight |= 1u << s;
    if (image && inFlight) retired.push_back({std::move(image), inFlight});
    image = vk::Image();
}

// Recording into `slotIndex` means its previous frame finished: nothing retired waits on it.
void Renderer::Impl::releaseRetired(uint32_t slotIndex) {
    for (Retired& r : retired) r.slotsInFlight &= ~(1u << slotIndex);
    std::erase_if(retired, [](const Retired& r) { return r.slotsInFlight == 0; });
}

std::span<const uint32_t> Renderer::Impl::shader(const char* name) const {
    auto it = shaderOverrides.find(name);
    return it != shaderOverrides.end() ? std::span<const uint32_t>(it->second) : builtinShader(name);
}

void Renderer::Impl::resolveEyeDrawing() {
    resolvedEyeDrawing = settings.eyeDrawing;
    if (resolvedEyeDrawing == EyeDrawing::Auto)
        resolvedEyeDrawing = dev.shaderOutputLayer() && !multiviewClipsEveryView(dev) ? EyeDrawing::InstancedLayers
                                                                                      : EyeDrawing::Multiview;
}

void Renderer::Impl::setShaderOverrides(const std::map<std::string, std::vector<uint32_t>>& spirv) {
    vkDeviceWaitIdle(dev.device());
    auto previous = std::exchange(shaderOverrides, spirv);
    std::map<PipelineKey, VkPipeline> rebuilt;
    VkPipeline rebuiltShadow = VK_NULL_HANDLE, rebuiltShadowMask = VK_NULL_HANDLE;
    try {
        for (const auto& [key, p] : pipelines) rebuilt.emplace(key, createPipeline(key));
        rebuiltShadow = createShadowPipeline(false);
        if (shadowMaskPipeline) rebuiltShadowMask = createShadowPipeline(true);
    } catch (...) {
        for (auto& [key, p] : rebuilt) vkDestroyPipeline(dev.device(), p, nullptr);
        if (rebuiltShadow) vkDestroyPipeline(dev.device(), rebuiltShadow, nullptr);
        shaderOverrides = std::move(previous);
        throw;
    }
    if (screenDiffusion || textureDiffusion) {
        try {
            if (screenDiffusion) screenDiffusion->rebuildPipelines();
            if (textureDiffusion) textureDiffusion->rebuildPipelines();
        } catch (...) {
            for (auto& [key, p] : rebuilt) vkDestroyPipeline(dev.device(), p, nullptr);
            if (rebuiltShadow) vkDestroyPipeline(dev.device(), rebuiltShadow, nullptr);
            if (rebuiltShadowMask) vkDestroyPipeline(dev.device(), rebuiltShadowMask, nullptr);
            shaderOverrides = std::move(previous);
            if (screenDiffusion) screenDiffusion->rebuildPipelines();  // the previous code, which built before
            if (textureDiffusion) textureDiffusion->rebuildPipelines();
            throw;
        }
    }
    for (auto& [key, p] : pipelines) vkDestroyPipeline(dev.device(), p, nullptr);
    if (shadowPipeline) vkDestroyPipeline(dev.device(), shadowPipeline, nullptr);
    if (shadowMaskPipeline) vkDestroyPipeline(dev.device(), shadowMaskPipeline, nullptr);
    pipelines = std::move(rebuilt);
    shadowPipeline = rebuiltShadow;
    shadowMaskPipeline = rebuiltShadowMask;
}

void Renderer::Impl::setPose(ScenePose p) {
    if (p.instances.size() != scene->restInstances.size())
        throw Error(
            fmt::format("pose: {} instances for a scene of {}", p.instances.size(), scene->restInstances.size()));
    for (size_t i = 0; i < p.instances.size(); ++i)
        if (!finite(p.instances[i].worldFromObject))
            throw Error(fmt::format("pose: instance {}: its transform is not finite", i));
    deformer->check(p);
    bounds = poseBounds->worldBounds(p);
    receivers = receiverPoseBounds->worldBounds(p);
    pose = std::move(p);
    ++poseVersion;
}

// Fills the slot's uniforms and light list; returns whether a shadow map is rendered.
bool Renderer::Impl::prepareFrame(Slot& slot, uint32_t slotIndex, const View& view, VkExtent2D extent,
                                  glm::mat4& shadowClipFromWorld) {
    // The pose: instance transforms, and the deformation's weights and joint matrices.
    if (slot.instancesPose != poseVersion) {  // static scenes fill them once per slot
        auto* instances = static_cast<gpu::GpuInstance*>(slot.instances.mapped());
        for (size_t i = 0; i < scene->restInstances.size(); ++i)
            instances[i] = toGpuInstance(pose.instances[i].worldFromObject);
        slot.instancesPose = poseVersion;
    }
    deformer->prepare(slotIndex, pose);
    const int shadowLight = shadowMapLight();
    // Directional lights first, the shadow light (if any) at index 0: forward.frag shades it on
    // its own and loops over the rest; then the point and spot lights the grid lists, in order.
    const uint32_t directional = frameLightRecords(frameLights, shadowLight, gpuLights, gridLights);
    const VkDeviceSize bytes = std::max<size_t>(gpuLights.size(), 1) * sizeof(gpu::GpuLight);
    if (bytes > slot.lights.size()) slot.lights = vk::Buffer(dev, bytes * 2, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
    slot.lights.upload(gpuLights.data(), gpuLights.size() * sizeof(gpu::GpuLight));
    slot.lightCount = static_cast<uint32_t>(gpuLights.size());

    gpu::FrameUniforms u{};
    for (uint32_t e = 0; e < view.eyeCount(); ++e) {
        const Eye& eye = view.eyes[e];
        u.eyes[e].clipFromWorld = eye.clipFromWorld();
        u.eyes[e].positionWs = glm::vec4(eye.positionWs, 1.0f);
        u.eyes[e].viewDepthFromWorld = -glm::row(eye.viewFromWorld, 2);
    }
    u.params = glm::vec4(settings.exposure, float(view.eyeCount()), 0.0f, 0.0f);
    u.viewport =
        glm::vec4(float(extent.width), float(extent.height), 1.0f / float(extent.width), 1.0f / float(extent.height));
    const uint32_t mapSize = shadowMap.desc().width;
    ShadowFit fit;  // without a shadow light: unit values, never sampled
    fit.texelSizeM = 2.0f / float(mapSize);
    fit.depthRangeM = 2.0f;
    if (shadowLight >= 0) {
        // The shadow light's record (gpuLights[0]): its unit direction and irradiance, which the
        // forward pass reads from here rather than from the lights' storage buffer.
        const gpu::GpuLight& record = gpuLights.front();
        const glm::vec3 dir(record.directionType);
        fit = fitDirectionalShadow(bounds, settings.fitShadowToSkin ? receivers : Bounds{}, view, dir, mapSize);
        shadowClipFromWorld = fit.clipFromWorld;
        u.shadowClipFromWorld = shadowClipFromWorld;
        u.shadowDirectionWs = glm::vec4(dir, 1.0f);
        u.shadowIrradiance = glm::vec4(glm::vec3(record.colorIntensity), 0.0f);
    }
    u.shadowParams =
        glm::vec4(fit.texelSizeM, std::max(settings.shadowSoftnessTexels, 0.25f), fit.depthRangeM, float(mapSize));
    // Skin's wide map: blocks of the shadow map so large that its filter's footprint (3 wide
    // texels, preskin/skin.glsl) covers the distance the widest skin profile scatters.
    const double reachMm = settings.skinShadowReachMm > 0.0f ? double(settings.skinShadowReachMm) : skinReachMm;
    if (shadowLight >= 0 && sceneHasSkin)
        wideFactor = uint32_t(std::clamp(std::ceil(reachMm / (3.0 * double(fit.texelSizeM) * 1000.0)), 1.0,
                                         std::max(1.0, double(mapSize) / 8.0)));
    const uint32_t wideSize = wideShadowSize();
    u.wideShadow = glm::vec4(float(mapSize) / float(wideSize * wideFactor), float(wideSize),
                             fit.texelSizeM * float(wideFactor), float(wideFactor));
    for (int i = 0; i < 9; ++i) u.shRadiance[i] = glm::vec4(extracted.residualSh.c[size_t(i)], 0.0f);
    u.lightCounts = glm::uvec4(slot.lightCount, directional, 0u, 0u);
    u.environment = glm::vec4(std::cos(environment.rotationY()), std::sin(environment.rotationY()),
                              environmentMaps->maxLevel(), 0.0f);
    if (settings.lightLoop == LightLoop::Clustered) {
        // The triangles drawn in this pose bound the lists (recomputed when the pose changes).
        const bool fitSurfaces = settings.clusters.fitListsToSurfaces;
        if (fitSurfaces && surfacesPose != poseVersion) {
            surfaces = poseSurfaces->surfaces(pose);
            surfacesPose = poseVersion;
        }
        if (fitSurfaces) {  // this frame's terms of the pose's triangles, set in place
            // Without MSAA a fragment is shaded inside its triangle; with it, at the centre of a
            // pixel the triangle covers in part.
            surfaces.outsidePx = settings.msaaSamples > 1 ? 1.0f : 0.0f;
            surfaces.version = settings.clusters.reuseSurfaces ? poseVersion + 1 : 0;
        }
        const ClusterSurfaces none;
        const ClusterBuilder::FrameGrid grid =
            clusters->prepare(slotIndex, settings.clusters, clusterCamera(view, extent.width, extent.height), bounds,
                              gridLights, directional, slot.lights, fitSurfaces ? surfaces : none);
        u.clusterFromWorld = grid.clusterFromWorld;
        u.clusterScale = grid.lookupScale;
        u.clusterDims = grid.dims;
        u.lightCounts.z = grid.indexCapacity;
    }
    slot.frameUniforms.upload(&u, sizeof(u));
    return shadowLight >= 0;
}

void Renderer::Impl::updateFrameSet(Slot& slot, uint32_t slotIndex) {
    const VkDescriptorBufferInfo frameInfo{slot.frameUniforms.handle(), 0, sizeof(gpu::FrameUniforms)};
    const VkDescriptorBufferInfo lightInfo{slot.lights.handle(), 0, VK_WHOLE_SIZE};
    const VkDescriptorBufferInfo instanceInfo{slot.instances.handle(), 0, VK_WHOLE_SIZE};
    const VkDescriptorBufferInfo rangesInfo{clusters->ranges(slotIndex).handle(), 0, VK_WHOLE_SIZE};
    const VkDescriptorBufferInfo indicesInfo{clusters->indices(slotIndex).handle(), 0, VK_WHOLE_SIZE};
    const VkDescriptorImageInfo shadowInfo{shadowSampler, shadowMap.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    const VkDescriptorImageInfo wideShadowInfo{shadowSampler, wideShadowMap.view(),
                                               VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    const std::array<VkDescriptorImageInfo, 4> lutInfos = luts->descriptors();
    std::vector<VkWriteDescriptorSet> writes;
    auto write = [&](uint32_t binding, VkDescriptorType type, const VkDescriptorBufferInfo* bufferInfo,
                     const VkDescriptorImageInfo* imageInfo) {
        VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        w.dstSet = slot.set;
        w.dstBinding = binding;
        w.descriptorCount = 1;
        w.descriptorType = type;
        w.pBufferInfo = bufferInfo;
        w.pImageInfo = imageInfo;
        writes.push_back(w);
    };
    auto buffer = [&](uint32_t binding, VkDescriptorType type, const VkDescriptorBufferInfo* info) {
        write(binding, type, info, nullptr);
    };
    auto image = [&](uint32_t binding, const VkDescriptorImageInfo* info) {
        write(binding, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, nullptr, info);
    };
    buffer(gpu::kBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, &frameInfo);
    buffer(gpu::kBindingLights, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &lightInfo);
    buffer(gpu::kBindingInstances, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &instanceInfo);
    buffer(gpu::kBindingClusterRanges, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &rangesInfo);
    buffer(gpu::kBindingClusterIndices, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &indicesInfo);
    image(gpu::kBindingShadowMap, &shadowInfo);
    image(gpu::kBindingWideShadowMap, &wideShadowInfo);
    image(gpu::kBindingDiffuseLut, &lutInfos[0]);
    image(gpu::kBindingPenumbraLut, &lutInfos[1]);
    image(gpu::kBindingShTransferLut, &lutInfos[2]);
    image(gpu::kBindingTransmittanceLut, &lutInfos[3]);
    const VkDescriptorImageInfo environmentInfos[] = {environmentMaps->imageInfo(), environmentMaps->prefilteredInfo(),
                                                      environmentMaps->dfgInfo()};
    image(gpu::kBindingEnvironmentImage, &environmentInfos[0]);
    image(gpu::kBindingPrefilteredEnvironment, &environmentInfos[1]);
    image(gpu::kBindingDfgTable, &environmentInfos[2]);
    // The texture-space baseline's blurred irradiance; any array texture stands in when unused.
    const VkDescriptorImageInfo diffusionInfo = textureDiffusion && textureDiffusionFrame()
        ? VkDescriptorImageInfo{textureDiffusion->sampler(), textureDiffusion->sumView(),
                                VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}
        : lutInfos[0];
    image(gpu::kBindingDiffusionTexture, &diffusionInfo);
    vkUpdateDescriptorSets(dev.device(), static_cast<uint32_t>(writes.size()), writes.data(), 0, nullptr);
}

// Binds the index buffer; vertex buffers are bound per draw (bindDrawVertices).
void Renderer::Impl::bindGeometry(VkCommandBuffer cmd, VkBuffer& boundVertices) {
    vkCmdBindIndexBuffer(cmd, scene->indices.handle(), 0, VK_INDEX_TYPE_UINT32);
    boundVertices = VK_NULL_HANDLE;
}

// Binds the vertices a draw reads (the scene's rest vertices, or this frame's deformed ones of
// its instance) and returns its vertex offset.
int32_t Renderer::Impl::bindDrawVertices(VkCommandBuffer cmd, uint32_t slotIndex, const DrawItem& d, VkBuffer& bound) {
    const bool deformed = deformer->deforms(d.instance);
    const VkBuffer vb = deformed ? deformer->output(slotIndex).handle() : scene->vertices.handle();
    if (vb != bound) {
        // Binding 1, the skin's normal basis, is laid out like the vertices.
        const VkBuffer buffers[2] = {
            vb, deformed ? deformer->normalBasisOutput(slotIndex).handle() : scene->normalBasis.handle()};
        const VkDeviceSize offsets[2] = {0, 0};
        vkCmdBindVertexBuffers(cmd, 0, 2, buffers, offsets);
        bound = vb;
    }
    return d.vertexOffset + (deformed ? deformer->vertexShift(d.instance) : 0);
}

// Throws preskin::Error unless the view and settings can be drawn on this device.
void Renderer::Impl::checkFrame(const View& view) const {
    if (view.eyes.empty() || view.eyeCount() > maxEyes())
        throw Error(fmt::format("view: {} eye(s); this device draws 1 to {} per view", view.eyeCount(), maxEyes()));
    for (uint32_t e = 0; e < view.eyeCount(); ++e) {
        const Eye& eye = view.eyes[e];
        if (!finite(eye.viewFromWorld) || !finite(eye.clipFromView) || !std::isfinite(eye.positionWs.x) ||
            !std::isfinite(eye.positionWs.y) || !std::isfinite(eye.positionWs.z))
            throw Error(fmt::format("view: eye {}: its matrices and position must be finite", e));
    }
    if (settings.eyeDrawing == EyeDrawing::InstancedLayers && !dev.shaderOutputLayer())
        throw Error("RenderSettings: instanced layered eyes need the device's shaderOutputLayer feature");
    if (textureDiffusionFrame()) checkTextureDiffusion();
    if (settings.diffusion != Diffusion::PreIntegrated && !dev.independentBlend())
        throw Error(
            fmt::format("RenderSettings: diffusion {}: needs the independentBlend feature, which {} does not "
                        "offer (or a host's device did not say it enabled)",
                        settings.diffusion == Diffusion::ScreenSpace ? "ScreenSpace" : "TextureSpace",
                        dev.properties().deviceName));
    const uint32_t n = settings.msaaSamples;
    if (n == 0 || (n & (n - 1)) != 0 || (dev.msaaSampleCounts() & n) == 0)
        throw Error(fmt::format("RenderSettings: msaaSamples {} is not offered by {} (offered: {})", n,
                                dev.properties().deviceName, fmt::join(msaaSampleCounts(), ", ")));
}

std::vector<uint32_t> Renderer::Impl::msaaSampleCounts() const { return context.msaaSampleCounts(); }

void Renderer::Impl::timestamp(VkCommandBuffer cmd, Slot& slot, uint32_t query) {
    if (slot.queries) vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, slot.queries, query);
}

void Renderer::Impl::record(VkCommandBuffer cmd, const RenderTarget& target, const View& view, uint32_t slotIndex) {
    const auto start = std::chrono::steady_clock::now();
    if (slotIndex >= kSlotCount) throw Error(fmt::format("Renderer::record: frame slot {} (0 or 1)", slotIndex));
    if (target.extent.width == 0 || target.extent.height == 0) throw Error("Renderer::record: target extent is empty");
    checkFrame(view);
    checkTarget(target);
    Slot& slot = slots[slotIndex];
    releaseRetired(slotIndex);
    createShadowMap(cmd, slotIndex);
    // The screen-space baseline: the forward pass draws into its targets, its passes into the target.
    ScreenDiffusion* split = splitDiffusion() ? &prepareScreenDiffusion(target, view.eyeCount(), slotIndex) : nullptr;
    RenderTarget forwardTarget = target;
    if (split) {
        forwardTarget.image = split->scene().handle();
        forwardTarget.view = split->scene().view();
        forwardTarget.format = ScreenDiffusion::kSceneFormat;
        forwardTarget.layoutBefore = VK_IMAGE_LAYOUT_UNDEFINED;
        forwardTarget.layoutAfter = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    }
    ensureAttachments(target.extent, view.eyeCount(), forwardTarget.format, target.depth.image == VK_NULL_HANDLE,
                      split == nullptr, slotIndex);
    glm::mat4 shadowClipFromWorld(1.0f);
    const bool shadow = prepareFrame(slot, slotIndex, view, target.extent, shadowClipFromWorld);
    const bool texture = textureDiffusionFrame();
    if (texture) prepareTextureDiffusion();
    createWideShadowMap(cmd, slotIndex);  // at the factor prepareFrame picked
    updateFrameSet(slot, slotIndex);
    if (slot.queries) vkCmdResetQueryPool(cmd, slot.queries, 0, kQueryCount);
    timestamp(cmd, slot, 0);
    deformer->recordDeformation(cmd, slotIndex);  // animated instances into this frame's vertices
    timestamp(cmd, slot, 1);
    deformer->recordCurvature(cmd, slotIndex);
    timestamp(cmd, slot, 2);
    if (shadow)
        recordShadowPass(cmd, slot, slotIndex);  // writes 6 between the map and the wide map's reduction
    else
        timestamp(cmd, slot, 6);
    timestamp(cmd, slot, 3);
    clusters->record(cmd, slotIndex);  // the compute build, when this frame uses it
    timestamp(cmd, slot, 4);
    if (texture) {
        recordTextureDiffusion(cmd, slot, slotIndex);
        timestamp(cmd, slot, 8);
    }
    if (split) {
        recordForwardPass(cmd, slot, slotIndex, forwardTarget, view, split->splitAttachments(),
                          isDisplayFormat(target.format));
        timestamp(cmd, slot, 5);
        split->record(cmd, slotIndex, target, view, eyeDrawing() == EyeDrawing::InstancedLayers,
                      [&] { timestamp(cmd, slot, 7); });
        timestamp(cmd, slot, 8);
    } else {
        recordForwardPass(cmd, slot, slotIndex, target, view);
        timestamp(cmd, slot, 5);
    }
    slot.split = split != nullptr;
    slot.texture = texture;
    slot.recorded = true;
    slot.shadowRecorded = shadow;
    slot.eyes = view.eyeCount();
    slot.recordMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

void Renderer::Impl::checkProfileLayers(size_t layerCount) const {
    if (layerCount == 0) return;
    const std::vector<Material>& materials = scene->sceneMaterials();
    for (size_t i = 0; i < materials.size(); ++i) {
        if (!materials[i].skin) continue;
        std::vector<int> profiles{materials[i].skin->profile};
        for (int p : materials[i].skin->blendProfiles) profiles.push_back(p);
        for (int p : profiles) {
            if (p >= -1 && size_t(p + 1) < layerCount) continue;
            throw Error(
                fmt::format("{}: materials[{}] ('{}'): profile {} has no LUT layer: the renderer holds {} "
                            "(the default set and {} profiles)",
                            sceneName, i, materials[i].name, p, layerCount, layerCount - 1));
        }
    }
}

void Renderer::Impl::dropSkinPipelines() {
    std::erase_if(pipelines, [&](const auto& entry) {
        if (entry.first.model != gpu::kModelSkin) return false;
        vkDestroyPipeline(dev.device(), entry.second, nullptr);
        return true;
    });
}

void Renderer::Impl::setLutLayers(const std::vector<const LutSet*>& layers) {
    checkProfileLayers(layers.size());
    auto replacement = std::make_unique<GpuLuts>(dev, layers);
    vkDeviceWaitIdle(dev.device());
    luts = std::move(replacement);
    scene->updateMaterials(luts->layers());
    updateSkinReach();
    dropSkinPipelines();
}

void Renderer::Impl::updateSkinReach() {
    diffusionKernelsStale = true;  // the profiles changed
    textureKernelsStale = true;
    // Two RMS widths of the widest profile of any skin material, in world mm: where red's
    // scattering into a cast shadow falls to a few percent (d'Eon's red: 3.3 mm, 5 % of lit).
    skinReachMm = 0.0;
    const std::vector<Material>& materials = scene->sceneMaterials();
    for (const Material& m : materials) {
        if (!m.skin) continue;
        std::vector<int> profiles{m.skin->profile};
        profiles.insert(profiles.end(), m.skin->blendProfiles.begin(), m.skin->blendProfiles.end());
        for (int p : profiles) {
            const size_t layer = size_t(p + 1);
            if (layer >= luts->layers().size() || !luts->layers()[layer].profile) continue;
            const double scale = std::max(double(m.skin->scatterScale), 1e-6);
            skinReachMm = std::max(skinReachMm, 2.0 * luts->layers()[layer].profile->maxWidthMm() / scale);
        }
    }
}

namespace {

std::vector<const LutSet*> layersOf(const ProfileLibrary& profiles) {
    std::vector<const LutSet*> layers;
    for (size_t i = 0; i < profiles.layerCount(); ++i) layers.push_back(&profiles.layer(i));
    return layers;
}

std::vector<const LutSet*> layersOf(const LutSet* luts) {
    return luts ? std::vector<const LutSet*>{luts} : std::vector<const LutSet*>{};
}

}  // namespace

Renderer::Renderer(Context& context, const Scene& scene, const Environment& environment, const LutSet* luts,
                   const RenderSettings& settings)
    : impl_(std::make_unique<Impl>(context, scene, environment, layersOf(luts), settings)) {}

Renderer::Renderer(Context& context, const Scene& scene, const Environment& environment, const ProfileLibrary& profiles,
                   const RenderSettings& settings)
    : impl_(std::make_unique<Impl>(context, scene, environment, layersOf(profiles), settings)) {}

Renderer::~Renderer() = default;

const RenderSettings& Renderer::settings() const { return impl_->settings; }

void Renderer::setSettings(const RenderSettings& settings) {
    checkRenderSettings(settings);
    const bool newLights = settings.environmentLights != impl_->settings.environmentLights ||
        settings.environmentLightSizes != impl_->settings.environmentLightSizes;
    impl_->settings = settings;
    if (newLights) impl_->updateEnvironmentLights(false);  // hosts set settings every frame
    impl_->resolveEyeDrawing();
}

void Renderer::setPose(const ScenePose& pose) { impl_->setPose(pose); }

const ScenePose& Renderer::pose() const { return impl_->pose; }

void Renderer::setLights(const std::vector<Light>& lights) {
    checkLights(lights);
    impl_->lights = lights;
    impl_->updateEnvironmentLights(false);
}
const std::vector<Light>& Renderer::lights() const { return impl_->lights; }
void Renderer::setEnvironment(const Environment& environment) {
    impl_->environment = environment.downsampled(kEnvironmentKeptWidth);
    impl_->updateEnvironmentLights(true);
}
const std::vector<Light>& Renderer::environmentLights() const { return impl_->extractedLights; }

std::vector<Light> withEnvironmentLights(const std::vector<Light>& lights, const EnvironmentLights& extracted,
                                         bool lightSizes) {
    std::vector<Light> out = lights;
    const bool sceneShadow = shadowLightIndex(lights) >= 0;
    for (size_t i = 0; i < extracted.lights.size(); ++i) {
        const EnvironmentLight& e = extracted.lights[i];
        Light l;
        l.name = fmt::format("environment light {}", i + 1);
        l.type = LightType::Directional;
        l.intensity = std::max({e.irradiance.r, e.irradiance.g, e.irradiance.b});
        l.color = l.intensity > 0.0f ? e.irradiance / l.intensity : glm::vec3(1.0f);
        l.directionWs = e.directionWs;
        l.angularRadius = lightSizes ? e.angularRadius : 0.0f;
        l.castsShadow = i == 0 && !sceneShadow;
        out.push_back(l);
    }
    return out;
}

void Renderer::setLuts(const LutSet* luts) { impl_->setLutLayers(layersOf(luts)); }

void Renderer::setProfiles(const ProfileLibrary& profiles) { impl_->setLutLayers(layersOf(profiles)); }

void Renderer::setProfileLayer(size_t layer, const LutSet& luts) {
    if (layer >= impl_->luts->layerCount())
        throw Error(fmt::format("Renderer::setProfileLayer: layer {} is out of range (the renderer holds {})", layer,
                                impl_->luts->layerCount()));
    vkDeviceWaitIdle(impl_->dev.device());
    if (!impl_->luts->replaceLayer(static_cast<uint32_t>(layer), luts))
        throw Error("Renderer::setProfileLayer: the LUT set is larger than the renderer's LUT arrays; use setProfiles");
    impl_->scene->updateMaterials(impl_->luts->layers());
    impl_->updateSkinReach();
    impl_->dropSkinPipelines();
}

void Renderer::setShaderOverrides(const std::map<std::string, std::vector<uint32_t>>& spirvByFile) {
    impl_->setShaderOverrides(spirvByFile);
}

void Renderer::record(VkCommandBuffer cmd, const RenderTarget& target, const View& view, uint32_t frameSlot) {
    impl_->record(cmd, target, view, frameSlot);
}

FrameStats Renderer::frameStats(uint32_t frameSlot) const { return impl_->stats(frameSlot); }

uint32_t Renderer::maxEyes() const { return impl_->maxEyes(); }

std::vector<uint32_t> Renderer::msaaSampleCounts() const { return impl_->msaaSampleCounts(); }

RenderedImage Renderer::render(const View& view, uint32_t width, uint32_t height, OutputEncoding encoding) {
    Impl& im = *impl_;
    const uint32_t maxDim = std::min<uint32_t>(im.dev.properties().limits.maxImageDimension2D, 16384);
    if (width == 0 || height == 0 || width > maxDim || height > maxDim)
        throw Error(fmt::format("image size: {}x{} is outside 1..{} pixels per side", width, height, maxDim));
    const VkFormat format =
        encoding == OutputEncoding::DisplaySrgb8 ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R32G32B32A32_SFLOAT;
    im.checkFrame(view);
    const uint32_t eyes = view.eyeCount();
    const VkDeviceSize pixelBytes = encoding == OutputEncoding::DisplaySrgb8 ? 4 : 16;
    if (!im.colorTarget || im.colorTarget.desc().width != width || im.colorTarget.desc().height != height ||
        im.colorTarget.desc().format != format || im.colorTarget.desc().layers != eyes) {
        vkDeviceWaitIdle(im.dev.device());
        im.colorTarget =
            vk::Image(im.dev,
                      {format, width, height, 1, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                       VK_IMAGE_ASPECT_COLOR_BIT, eyes});
        im.readback = vk::Buffer(im.dev, VkDeviceSize(width) * height * pixelBytes * eyes,
                                 VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    }
    RenderTarget target;
    target.image = im.colorTarget.handle();
    target.view = im.colorTarget.view();
    target.format = format;
    target.extent = {width, height};
    target.layoutBefore = VK_IMAGE_LAYOUT_UNDEFINED;
    target.layoutAfter = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;

    const auto start = std::chrono::steady_clock::now();
    im.dev.submitAndWait([&](VkCommandBuffer cmd) {
        im.record(cmd, target, view, 0);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, eyes};
        region.imageExtent = {width, height, 1};
        vkCmdCopyImageToBuffer(cmd, target.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, im.readback.handle(), 1,
                               &region);
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    });
    im.slots[0].wallMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();

    RenderedImage out;
    out.width = width;
    out.height = height;
    out.eyes = eyes;
    out.encoding = encoding;
    const size_t count = size_t(width) * height * 4 * eyes;
    if (encoding == OutputEncoding::DisplaySrgb8) {
        out.rgba8.resize(count);
        std::memcpy(out.rgba8.data(), im.readback.mapped(), count);
    } else {
        out.rgba32f.resize(count);
        std::memcpy(out.rgba32f.data(), im.readback.mapped(), count * sizeof(float));
    }
    return out;
}

}  // namespace preskin
