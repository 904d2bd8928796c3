#include "render/TextureDiffusion.h"

#include "shared/gpu_types.h"
#include "skin/GaussianFit.h"
#include "vk/Check.h"

#include <algorithm>
#include <cmath>

namespace preskin {

namespace {

constexpr VkColorComponentFlags kAll =
    VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;

}  // namespace

TextureDiffusion::TextureDiffusion(const vk::Device& device,
                                   std::function<std::span<const uint32_t>(const char*)> shader, uint32_t slots)
    : device_(device), shader_(std::move(shader)) {
    const VkShaderStageFlags fs = VK_SHADER_STAGE_FRAGMENT_BIT;
    const vk::Binding bindings[] = {{gpu::kBindingBlurInput, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, fs},
                                    {gpu::kBindingBlurStretch, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, fs}};
    setLayout_ = vk::createSetLayout(device_, bindings);
    layout_ = vk::createPipelineLayout(device_, std::span(&setLayout_, 1), sizeof(gpu::BlurPush), fs);
    const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 6 * slots}};
    pool_ = vk::createDescriptorPool(device_, sizes, 3 * slots);
    sets_.resize(slots);
    for (auto& s : sets_)
        for (VkDescriptorSet& set : s) set = vk::allocateDescriptorSet(device_, pool_, setLayout_);
    linear_ = vk::createClampSampler(device_, VK_FILTER_LINEAR);
    nearest_ = vk::createClampSampler(device_, VK_FILTER_NEAREST);
    pipelines_ = {createPipeline(false), createPipeline(true)};
}

TextureDiffusion::~TextureDiffusion() {
    const VkDevice d = device_.device();
    destroyViews();
    for (VkPipeline p : pipelines_)
        if (p) vkDestroyPipeline(d, p, nullptr);
    vkDestroySampler(d, linear_, nullptr);
    vkDestroySampler(d, nearest_, nullptr);
    vkDestroyDescriptorPool(d, pool_, nullptr);
    vkDestroyPipelineLayout(d, layout_, nullptr);
    vkDestroyDescriptorSetLayout(d, setLayout_, nullptr);
}

void TextureDiffusion::destroyViews() {
    for (auto& views : layerViews_) {
        for (VkImageView v : views) vkDestroyImageView(device_.device(), v, nullptr);
        views.clear();
    }
}

void TextureDiffusion::setKernels(const std::vector<Material>& materials, const std::vector<ProfileLayer>& layers) {
    gaussians_.assign(materials.size(), {});
    for (size_t m = 0; m < materials.size(); ++m) {
        if (!materials[m].skin) continue;
        const SkinMaterial& skin = *materials[m].skin;
        const size_t layer = size_t(skin.profile + 1);
        if (layer >= layers.size() || !layers[layer].profile) continue;
        // Profile mm -> world m: a scatter scale s makes the profile s times narrower in the world.
        const double metresPerProfileMm = 1e-3 / std::max(double(skin.scatterScale), 1e-6);
        for (const GaussianTerm& t : normalizedGaussians(*layers[layer].profile))
            gaussians_[m].push_back({t.varianceMm2 * metresPerProfileMm * metresPerProfileMm, glm::vec3(t.weight)});
    }
}

void TextureDiffusion::ensureTargets(uint32_t size, uint32_t layers) {
    layers = std::max(layers, 1u);
    if (size == size_ && layers == layers_) return;
    vkDeviceWaitIdle(device_.device());
    destroyViews();
    size_ = size;
    layers_ = layers;
    const VkImageUsageFlags usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    std::array<vk::Image*, 5> images{&irradiance_, &stretch_, &level_, &intermediate_, &sum_};
    for (size_t i = 0; i < images.size(); ++i) {
        vk::ImageDesc desc{
            i == 1 ? kStretchFormat : kIrradianceFormat, size, size, 1, usage, VK_IMAGE_ASPECT_COLOR_BIT, layers};
        desc.arrayView = true;
        *images[i] = vk::Image(device_, desc);
        for (uint32_t l = 0; l < layers; ++l) {
            VkImageViewCreateInfo v{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
            v.image = images[i]->handle();
            v.viewType = VK_IMAGE_VIEW_TYPE_2D;
            v.format = desc.format;
            v.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, l, 1};
            VkImageView view = VK_NULL_HANDLE;
            PRESKIN_VK(vkCreateImageView(device_.device(), &v, nullptr, &view));
            layerViews_[i].push_back(view);
        }
    }
}

std::array<VkImageView, 2> TextureDiffusion::irradianceViews(uint32_t layer) const {
    return {layerViews_[0][layer], layerViews_[1][layer]};
}

uint64_t TextureDiffusion::targetBytes() const { return uint64_t(size_) * size_ * layers_ * kBytesPerTexel; }

uint32_t TextureDiffusion::passesPerFrame(const std::vector<std::pair<uint32_t, uint32_t>>& layerMaterials) const {
    uint32_t passes = 0;
    for (const auto& [layer, material] : layerMaterials) passes += 1 + 2 * uint32_t(gaussians_[material].size());
    return passes;
}

VkPipeline TextureDiffusion::createPipeline(bool vertical) const {
    vk::GraphicsPipelineDesc desc;
    desc.vertexSpirv = shader_("fullscreen_single.vert");
    desc.fragmentSpirv = shader_("texture_blur.frag");
    desc.specialization.values = {vertical ? 1u : 0u};
    desc.colorFormats = {kIrradianceFormat, kIrradianceFormat};
    desc.colorWriteMasks = {kAll, vertical ? kAll : 0u};
    desc.cullMode = VK_CULL_MODE_NONE;
    desc.depthTest = false;
    desc.depthWrite = false;
    desc.layout = layout_;
    desc.additiveBlendAttachment = 1;
    return vk::createGraphicsPipeline(device_, desc);
}

void TextureDiffusion::rebuildPipelines() {
    std::array<VkPipeline, 2> rebuilt{createPipeline(false), VK_NULL_HANDLE};
    try {
        rebuilt[1] = createPipeline(true);
    } catch (...) {
        vkDestroyPipeline(device_.device(), rebuilt[0], nullptr);
        throw;
    }
    for (VkPipeline p : pipelines_) vkDestroyPipeline(device_.device(), p, nullptr);
    pipelines_ = rebuilt;
}

void TextureDiffusion::beginIrradiance(VkCommandBuffer cmd) {
    for (const vk::Image* image : {&irradiance_, &stretch_})
        vk::imageBarrier(cmd, image->handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                         VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                         VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                         VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                         VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, layers_);
}

void TextureDiffusion::recordBlur(VkCommandBuffer cmd, uint32_t slot,
                                  const std::vector<std::pair<uint32_t, uint32_t>>& layerMaterials) {
    constexpr VkPipelineStageFlags2 kOutput = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
    constexpr VkPipelineStageFlags2 kFragment = VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
    constexpr VkAccessFlags2 kWrite = VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT;
    constexpr VkAccessFlags2 kRead = VK_ACCESS_2_SHADER_SAMPLED_READ_BIT;
    const auto toRead = [&](const vk::Image& image) {
        vk::imageBarrier(cmd, image.handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                         VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, kOutput, kWrite, kFragment, kRead, layers_);
    };
    const auto toWrite = [&](const vk::Image& image, VkImageLayout from) {
        vk::imageBarrier(cmd, image.handle(), VK_IMAGE_ASPECT_COLOR_BIT, from, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                         kFragment | kOutput, from == VK_IMAGE_LAYOUT_UNDEFINED ? VK_ACCESS_2_NONE : kRead, kOutput,
                         kWrite | VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT, layers_);
    };
    toRead(irradiance_);
    toRead(stretch_);
    toWrite(level_, VK_IMAGE_LAYOUT_UNDEFINED);
    toWrite(intermediate_, VK_IMAGE_LAYOUT_UNDEFINED);
    toWrite(sum_, VK_IMAGE_LAYOUT_UNDEFINED);
    // The sets: the irradiance, the ping-pong level and the intermediate as inputs.
    std::array<VkDescriptorSet, 3>& sets = sets_[slot];
    const std::array<const vk::Image*, 3> inputs{&irradiance_, &level_, &intermediate_};
    for (size_t i = 0; i < 3; ++i) {
        const VkDescriptorImageInfo images[] = {{linear_, inputs[i]->view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
                                                {nearest_, stretch_.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}};
        std::array<VkWriteDescriptorSet, 2> writes{};
        for (uint32_t b = 0; b < 2; ++b) {
            writes[b] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
            writes[b].dstSet = sets[i];
            writes[b].dstBinding = b;
            writes[b].descriptorCount = 1;
            writes[b].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
            writes[b].pImageInfo = &images[b];
        }
        vkUpdateDescriptorSets(device_.device(), 2, writes.data(), 0, nullptr);
    }
    // One pass into `output` (a layer view) with the sum as the second attachment.
    const auto pass = [&](bool vertical, VkImageView output, uint32_t layer, VkDescriptorSet set,
                          const gpu::BlurPush& p, bool clearSum) {
        std::array<VkRenderingAttachmentInfo, 2> colors{};
        for (auto& c : colors) {
            c = {VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
            c.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
            c.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        }
        colors[0].imageView = output;
        colors[0].loadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;  // every texel is written
        colors[1].imageView = layerViews_[4][layer];
        colors[1].loadOp = clearSum ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
        vk::beginColorRendering(cmd, {size_, size_}, colors);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelines_[vertical ? 1 : 0]);
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 0, 1, &set, 0, nullptr);
        vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(p), &p);
        vkCmdDraw(cmd, 3, 1, 0, 0);
        vkCmdEndRendering(cmd);
    };
    bool levelReadable = false;  // the level was last written and read (else still an attachment)
    for (const auto& [layer, material] : layerMaterials) {
        const std::vector<Gaussian>& chain = gaussians_[material];
        double previous = 0.0;
        // Level k is blurred from level k - 1: the irradiance first, then the ping-pong level.
        for (size_t k = 0; k < chain.size(); ++k) {
            gpu::BlurPush p{};
            const float sigma = float(std::sqrt(std::max(chain[k].varianceM2 - previous, 0.0)));
            previous = chain[k].varianceM2;
            p.direction = glm::vec4(1.0f, 0.0f, sigma, float(layer));
            p.weight = glm::vec4(chain[k].weight, k == 0 ? 1.0f : 0.0f);
            pass(false, layerViews_[3][layer], layer, k == 0 ? sets[0] : sets[1], p, false);
            toRead(intermediate_);
            if (levelReadable) {  // the level becomes the output again
                vk::imageBarrier(cmd, level_.handle(), VK_IMAGE_ASPECT_COLOR_BIT,
                                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                                 kFragment, kRead, kOutput, kWrite, layers_);
            }
            p.direction = glm::vec4(0.0f, 1.0f, sigma, float(layer));
            pass(true, layerViews_[2][layer], layer, sets[2], p, k == 0);
            toRead(level_);
            levelReadable = true;
            toWrite(intermediate_, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        }
    }
    vk::imageBarrier(cmd, sum_.handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, kOutput, kWrite, kFragment, kRead, layers_);
}

}  // namespace preskin
