#include "render/ScreenDiffusion.h"

#include "render/DisplayFormat.h"

#include <preskin/Error.h>

#include "shared/gpu_types.h"
#include "skin/SeparableKernel.h"
#include "vk/Check.h"

#include <algorithm>
#include <cmath>

namespace preskin {

namespace {

constexpr VkImageUsageFlags kTargetUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;

uint64_t formatBytes(VkFormat format) {
    switch (format) {
    case VK_FORMAT_R16G16B16A16_SFLOAT:
    case VK_FORMAT_R32G32_SFLOAT: return 8;
    default: return 4;
    }
}

uint64_t imageBytes(const vk::Image& image) {
    if (!image) return 0;
    const vk::ImageDesc& d = image.desc();
    return uint64_t(d.width) * d.height * d.layers * uint64_t(d.samples) * formatBytes(d.format);
}

}  // namespace

ScreenDiffusion::ScreenDiffusion(const vk::Device& device, std::function<std::span<const uint32_t>(const char*)> shader,
                                 uint32_t slots)
    : device_(device), shader_(std::move(shader)) {
    const VkShaderStageFlags fs = VK_SHADER_STAGE_FRAGMENT_BIT;
    const vk::Binding bindings[] = {
        {gpu::kBindingDiffusionInput, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, fs},
        {gpu::kBindingDiffusionSurface, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, fs},
        {gpu::kBindingDiffusionScene, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, fs},
        {gpu::kBindingDiffusionKernels, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, fs},
    };
    setLayout_ = vk::createSetLayout(device_, bindings);
    layout_ = vk::createPipelineLayout(device_, std::span(&setLayout_, 1), sizeof(gpu::DiffusionPush), fs);
    const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 6 * slots},
                                          {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2 * slots}};
    pool_ = vk::createDescriptorPool(device_, sizes, 2 * slots);
    sets_.resize(slots);
    kernels_.resize(slots);
    for (auto& s : sets_)
        for (VkDescriptorSet& set : s) set = vk::allocateDescriptorSet(device_, pool_, setLayout_);
    linear_ = vk::createClampSampler(device_, VK_FILTER_LINEAR);
    nearest_ = vk::createClampSampler(device_, VK_FILTER_NEAREST);
}

ScreenDiffusion::~ScreenDiffusion() {
    const VkDevice d = device_.device();
    for (auto& [key, p] : pipelines_) vkDestroyPipeline(d, p, nullptr);
    vkDestroySampler(d, linear_, nullptr);
    vkDestroySampler(d, nearest_, nullptr);
    vkDestroyDescriptorPool(d, pool_, nullptr);
    vkDestroyPipelineLayout(d, layout_, nullptr);
    vkDestroyDescriptorSetLayout(d, setLayout_, nullptr);
}

void ScreenDiffusion::setKernels(const std::vector<Material>& materials, const std::vector<ProfileLayer>& layers,
                                 uint32_t taps) {
    // Per material: a header (rgb: 1 / 2v per channel, v the profile's per-axis variance in world
    // m^2, for the depth-aware weights), then its taps (rgb weight, w offset in world m).
    const size_t stride = taps + 1;
    std::vector<glm::vec4> data(std::max<size_t>(materials.size(), 1) * stride, glm::vec4(0.0f));
    std::map<const DiffusionProfile*, std::vector<SeparableTap>> kernels;  // materials share profiles
    for (size_t m = 0; m < materials.size(); ++m) {
        if (!materials[m].skin) continue;
        const SkinMaterial& skin = *materials[m].skin;
        const size_t layer = size_t(skin.profile + 1);
        if (layer >= layers.size() || !layers[layer].profile) continue;
        const DiffusionProfile* profile = layers[layer].profile.get();
        auto it = kernels.find(profile);
        if (it == kernels.end()) it = kernels.emplace(profile, separableKernel(*profile, taps)).first;
        // Profile mm -> world m: a scatter scale s makes the profile s times narrower in the world.
        const double metresPerProfileMm = 1e-3 / std::max(double(skin.scatterScale), 1e-6);
        const glm::dvec3 varianceM2 = 0.5 * glm::pow(profile->widthMm() * metresPerProfileMm, glm::dvec3(2.0));
        data[m * stride] = glm::vec4(glm::vec3(0.5 / varianceM2), 0.0f);
        for (uint32_t i = 0; i < taps; ++i) {
            const SeparableTap& t = it->second[i];
            data[m * stride + 1 + i] = glm::vec4(glm::vec3(t.weight), float(t.offsetMm * metresPerProfileMm));
        }
    }
    kernelData_ = std::move(data);
    ++kernelVersion_;
    kernelMaterials_ = uint32_t(materials.size());
    taps_ = taps;
}

void ScreenDiffusion::ensureTargets(VkExtent2D extent, uint32_t eyes, uint32_t samples,
                                    const std::function<void(vk::Image&)>& retire) {
    const auto make = [&](vk::Image& image, VkFormat format, uint32_t count) {
        const vk::ImageDesc& d = image.desc();
        if (image && d.width == extent.width && d.height == extent.height && d.layers == eyes &&
            uint32_t(d.samples) == count)
            return;
        retire(image);
        vk::ImageDesc desc{format,        extent.width,
                           extent.height, 1,
                           kTargetUsage,  VK_IMAGE_ASPECT_COLOR_BIT,
                           eyes,          static_cast<VkSampleCountFlagBits>(count)};
        desc.arrayView = true;
        if (count > 1) desc.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT;
        image = vk::Image(device_, desc);
    };
    make(scene_, kSceneFormat, 1);
    make(diffuse_, kDiffuseFormat, 1);
    make(surface_, kSurfaceFormat, 1);
    make(intermediate_, kDiffuseFormat, 1);
    if (samples > 1) {
        make(msaaScene_, kSceneFormat, samples);
        make(msaaDiffuse_, kDiffuseFormat, samples);
        make(msaaSurface_, kSurfaceFormat, samples);
    } else {
        retire(msaaScene_);
        retire(msaaDiffuse_);
        retire(msaaSurface_);
    }
}

std::array<ScreenDiffusion::Attachment, 2> ScreenDiffusion::splitAttachments() const {
    return {Attachment{&diffuse_, msaaDiffuse_ ? &msaaDiffuse_ : nullptr, kDiffuseFormat},
            Attachment{&surface_, msaaSurface_ ? &msaaSurface_ : nullptr, kSurfaceFormat}};
}

uint32_t ScreenDiffusion::targetCount() const {
    uint32_t n = 0;
    for (const vk::Image* i :
         {&scene_, &diffuse_, &surface_, &intermediate_, &msaaScene_, &msaaDiffuse_, &msaaSurface_})
        n += *i ? 1u : 0u;
    return n;
}

uint64_t ScreenDiffusion::targetBytes() const {
    uint64_t bytes = 0;
    for (const vk::Image* i :
         {&scene_, &diffuse_, &surface_, &intermediate_, &msaaScene_, &msaaDiffuse_, &msaaSurface_})
        bytes += imageBytes(*i);
    return bytes;
}

VkPipeline ScreenDiffusion::createPipeline(uint32_t pass, VkFormat format, uint32_t eyes, bool layered,
                                           uint32_t taps) const {
    vk::GraphicsPipelineDesc desc;
    desc.vertexSpirv = shader_(layered ? "fullscreen_layers.vert" : "fullscreen.vert");
    desc.fragmentSpirv = shader_("screen_diffusion.frag");
    desc.specialization.values = {pass, taps, 0u};
    desc.specialization.values[gpu::kSpecDiffusionOutput] =
        pass == gpu::kDiffusionVertical && isDisplayFormat(format) ? gpu::kOutputTonemapped : gpu::kOutputLinear;
    desc.colorFormats = {format};
    desc.cullMode = VK_CULL_MODE_NONE;
    desc.depthTest = false;
    desc.depthWrite = false;
    desc.viewMask = layered ? 0u : (1u << eyes) - 1u;
    desc.layout = layout_;
    return vk::createGraphicsPipeline(device_, desc);
}

VkPipeline ScreenDiffusion::pipeline(uint32_t pass, VkFormat format, uint32_t eyes, bool layered) {
    const Key key{pass, format, eyes, layered, taps_};
    auto it = pipelines_.find(key);
    if (it != pipelines_.end()) return it->second;
    return pipelines_.emplace(key, createPipeline(pass, format, eyes, layered, taps_)).first->second;
}

void ScreenDiffusion::rebuildPipelines() {
    std::map<Key, VkPipeline> rebuilt;
    try {
        for (const auto& [key, p] : pipelines_)
            rebuilt.emplace(key, std::apply([&](auto... k) { return createPipeline(k...); }, key));
    } catch (...) {
        for (auto& [key, p] : rebuilt) vkDestroyPipeline(device_.device(), p, nullptr);
        throw;
    }
    for (auto& [key, p] : pipelines_) vkDestroyPipeline(device_.device(), p, nullptr);
    pipelines_ = std::move(rebuilt);
}

void ScreenDiffusion::record(VkCommandBuffer cmd, uint32_t slot, const RenderTarget& target, const View& view,
                             bool layered, const std::function<void()>& betweenPasses) {
    const uint32_t eyes = view.eyeCount();
    std::array<VkDescriptorSet, 2>& sets = sets_[slot];
    SlotKernels& kernels = kernels_[slot];  // the slot's previous frame has finished
    if (kernels.version != kernelVersion_) {
        const VkDeviceSize bytes = kernelData_.size() * sizeof(glm::vec4);
        if (!kernels.buffer || kernels.buffer.size() < bytes)
            kernels.buffer = vk::Buffer(device_, bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
        kernels.buffer.upload(kernelData_.data(), bytes);
        kernels.version = kernelVersion_;
    }
    for (uint32_t pass = 0; pass < 2; ++pass) {
        const VkDescriptorImageInfo images[] = {
            {linear_, (pass == 0 ? diffuse_ : intermediate_).view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
            {nearest_, surface_.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
            {nearest_, scene_.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}};
        const VkDescriptorBufferInfo buffer{kernels.buffer.handle(), 0, VK_WHOLE_SIZE};
        std::array<VkWriteDescriptorSet, 4> writes{};
        for (uint32_t b = 0; b < 4; ++b) {
            writes[b] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
            writes[b].dstSet = sets[pass];
            writes[b].dstBinding = b;
            writes[b].descriptorCount = 1;
            writes[b].descriptorType = b == gpu::kBindingDiffusionKernels ? VK_DESCRIPTOR_TYPE_STORAGE_BUFFER
                                                                          : VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
            if (b == gpu::kBindingDiffusionKernels)
                writes[b].pBufferInfo = &buffer;
            else
                writes[b].pImageInfo = &images[b];
        }
        vkUpdateDescriptorSets(device_.device(), uint32_t(writes.size()), writes.data(), 0, nullptr);
    }

    gpu::DiffusionPush push{};
    for (uint32_t e = 0; e < eyes; ++e) {
        const glm::mat4& p = view.eyes[e].clipFromView;
        push.eyeScale[e] = glm::vec4(std::abs(p[0][0]) * 0.5f * float(target.extent.width),
                                     std::abs(p[1][1]) * 0.5f * float(target.extent.height),
                                     view.eyes[e].orthographic() ? 0.0f : 1.0f, 0.0f);
    }
    push.params = glm::uvec4(kernelMaterials_, 0u, 0u, 0u);

    constexpr VkAccessFlags2 kColorWrite = VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT;
    const auto blur = [&](uint32_t pass, VkImageView output, VkFormat format) {
        VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        color.imageView = output;
        color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        color.loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;  // every pixel is written
        color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        vk::beginColorRendering(cmd, target.extent, std::span(&color, 1), layered ? 0u : (1u << eyes) - 1u,
                                layered ? eyes : 1u);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline(pass, format, eyes, layered));
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 0, 1, &sets[pass], 0, nullptr);
        vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(push), &push);
        vkCmdDraw(cmd, 3, layered ? eyes : 1u, 0, 0);
        vkCmdEndRendering(cmd);
    };
    vk::imageBarrier(cmd, intermediate_.handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                     VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                     VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, kColorWrite, eyes);
    blur(gpu::kDiffusionHorizontal, intermediate_.view(), kDiffuseFormat);
    vk::imageBarrier(cmd, intermediate_.handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                     kColorWrite, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, eyes);
    betweenPasses();
    vk::imageBarrier(cmd, target.image, VK_IMAGE_ASPECT_COLOR_BIT, target.layoutBefore,
                     VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                     VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT,
                     VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, kColorWrite, eyes);
    blur(gpu::kDiffusionVertical, target.view, target.format);
    vk::imageBarrier(cmd, target.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                     target.layoutAfter, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, kColorWrite,
                     VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT,
                     eyes);
}

}  // namespace preskin
