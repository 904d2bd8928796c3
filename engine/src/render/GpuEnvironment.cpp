// The environment on the GPU; see GpuEnvironment.h.
#include "render/GpuEnvironment.h"

#include "env/Dfg.h"
#include "env/Ltc.h"
#include "vk/Check.h"
#include "vk/Pipeline.h"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <span>
#include <string_view>

namespace preskin::shaders {
std::span<const uint32_t> spirv(std::string_view fileName);
}

namespace preskin {

namespace {

constexpr uint32_t kMaxImageWidth = 2048;  // the backdrop's image: box-filtered down to this width
constexpr uint32_t kMaxFaceSize = 256;     // the prefiltered cube's level 0
constexpr uint32_t kMinFaceSize = 8;       // its last level (roughness 1)

// The image box-filtered to at most maxWidth wide (boxFiltered), as RGBA half floats (radiance
// above the half range saturates).
std::vector<uint16_t> halfTexels(const EquirectImage& source, uint32_t maxWidth, uint32_t& width, uint32_t& height) {
    const EquirectImage image = boxFiltered(source, maxWidth);
    width = image.width;
    height = image.height;
    std::vector<uint16_t> out(size_t(width) * height * 4);
    for (size_t i = 0; i < size_t(width) * height; ++i) {
        for (size_t c = 0; c < 3; ++c) out[i * 4 + c] = glm::packHalf1x16(std::min(image.rgb[i * 3 + c], 65504.0f));
        out[i * 4 + 3] = glm::packHalf1x16(1.0f);
    }
    return out;
}

// A constant environment as a small image of its radiance.
EquirectImage constantImage(const Environment& environment) {
    EquirectImage image;
    image.width = 8;
    image.height = 4;
    const glm::vec3 l = environment.radiance(glm::vec3(0.0f, 1.0f, 0.0f));
    for (uint32_t i = 0; i < image.width * image.height; ++i) image.rgb.insert(image.rgb.end(), {l.r, l.g, l.b});
    return image;
}

vk::Image uploadImage(const vk::Device& device, const EquirectImage& source, uint32_t maxWidth) {
    uint32_t width = 0, height = 0;
    const std::vector<uint16_t> texels = halfTexels(source, maxWidth, width, height);
    vk::Image image(device,
                    {VK_FORMAT_R16G16B16A16_SFLOAT, width, height, vk::mipLevelCount(width, height),
                     VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT});
    image.uploadAndGenerateMips(texels.data(), texels.size() * sizeof(uint16_t));
    return image;
}

VkSampler createSampler(const vk::Device& device, VkSamplerAddressMode u) {
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = VK_FILTER_LINEAR;
    info.minFilter = VK_FILTER_LINEAR;
    info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
    info.addressModeU = u;
    info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    info.maxLod = VK_LOD_CLAMP_NONE;
    VkSampler sampler = VK_NULL_HANDLE;
    PRESKIN_VK(vkCreateSampler(device.device(), &info, nullptr, &sampler));
    return sampler;
}

}  // namespace

GpuEnvironment::GpuEnvironment(const vk::Device& device) : device_(device) {
    sampler_ = createSampler(device, VK_SAMPLER_ADDRESS_MODE_REPEAT);
    clampSampler_ = createSampler(device, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
    const vk::Binding bindings[] = {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_COMPUTE_BIT},
                                    {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_SHADER_STAGE_COMPUTE_BIT}};
    setLayout_ = vk::createSetLayout(device, bindings);
    layout_ =
        vk::createPipelineLayout(device, std::span(&setLayout_, 1), sizeof(glm::vec4), VK_SHADER_STAGE_COMPUTE_BIT);
    pipeline_ = vk::createComputePipeline(device, shaders::spirv("env_prefilter.comp"), layout_);

    // The GGX tables side by side (preskin/ibl.glsl): the split-sum DFG (A, B) on the left, the
    // linearly transformed cosine's M^-1 (env/Ltc.h) on the right, same grid.
    const std::vector<glm::vec2>& dfg = env::defaultDfgTable();
    const std::vector<env::LtcEntry>& ltc = env::defaultLtcTable();
    const uint32_t n = env::kDfgTableSize;
    std::vector<glm::vec4> table(size_t(2 * n) * n);
    for (uint32_t j = 0; j < n; ++j)
        for (uint32_t i = 0; i < n; ++i) {
            table[size_t(j) * 2 * n + i] = glm::vec4(dfg[size_t(j) * n + i], 0.0f, 0.0f);
            table[size_t(j) * 2 * n + n + i] = ltc[size_t(j) * n + i];
        }
    dfg_ = vk::Image(
        device,
        {VK_FORMAT_R32G32B32A32_SFLOAT, 2 * n, n, 1, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT});
    dfg_.uploadAndGenerateMips(table.data(), table.size() * sizeof(glm::vec4));
    set(Environment::constant(glm::vec3(0.0f)), EquirectImage{});
}

GpuEnvironment::~GpuEnvironment() {
    const VkDevice d = device_.device();
    if (pipeline_) vkDestroyPipeline(d, pipeline_, nullptr);
    if (layout_) vkDestroyPipelineLayout(d, layout_, nullptr);
    if (setLayout_) vkDestroyDescriptorSetLayout(d, setLayout_, nullptr);
    if (sampler_) vkDestroySampler(d, sampler_, nullptr);
    if (clampSampler_) vkDestroySampler(d, clampSampler_, nullptr);
}

void GpuEnvironment::set(const Environment& environment, const EquirectImage& specularImage) {
    const auto start = std::chrono::steady_clock::now();
    vkDeviceWaitIdle(device_.device());
    const bool hasImage = environment.image().width > 0;
    const EquirectImage constant = hasImage ? EquirectImage{} : constantImage(environment);
    image_ = uploadImage(device_, hasImage ? environment.image() : constant, kMaxImageWidth);
    prefilter(specularImage.width > 0 ? specularImage : hasImage ? environment.image() : constant);
    ++version_;
    setMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

void GpuEnvironment::prefilter(const EquirectImage& image) {
    // Level 0 about as sharp as the image (a face spans a quarter of its width), down to kMinFaceSize.
    uint32_t face = kMinFaceSize;
    while (face * 2 <= std::min(kMaxFaceSize, image.width / 4)) face *= 2;
    const uint32_t levels = uint32_t(std::log2(double(face) / kMinFaceSize)) + 1;
    const vk::Image source = uploadImage(device_, image, 2 * kMaxFaceSize * 2);
    prefiltered_ = vk::Image(device_,
                             {VK_FORMAT_R16G16B16A16_SFLOAT, face, face, levels,
                              VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                              VK_IMAGE_ASPECT_COLOR_BIT, 6, VK_SAMPLE_COUNT_1_BIT, false, true});
    const VkDevice d = device_.device();
    std::vector<VkImageView> views(levels, VK_NULL_HANDLE);
    const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, levels},
                                          {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, levels}};
    const VkDescriptorPool pool = vk::createDescriptorPool(device_, sizes, levels);
    try {
        std::vector<VkDescriptorSet> sets(levels);
        const VkDescriptorImageInfo sourceInfo{sampler_, source.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        for (uint32_t level = 0; level < levels; ++level) {
            VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
            viewInfo.image = prefiltered_.handle();
            viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D_ARRAY;
            viewInfo.format = VK_FORMAT_R16G16B16A16_SFLOAT;
            viewInfo.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, level, 1, 0, 6};
            PRESKIN_VK(vkCreateImageView(d, &viewInfo, nullptr, &views[level]));
            sets[level] = vk::allocateDescriptorSet(device_, pool, setLayout_);
            const VkDescriptorImageInfo levelInfo{VK_NULL_HANDLE, views[level], VK_IMAGE_LAYOUT_GENERAL};
            VkWriteDescriptorSet writes[2]{};
            for (uint32_t i = 0; i < 2; ++i) {
                writes[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
                writes[i].dstSet = sets[level];
                writes[i].dstBinding = i;
                writes[i].descriptorCount = 1;
            }
            writes[0].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
            writes[0].pImageInfo = &sourceInfo;
            writes[1].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
            writes[1].pImageInfo = &levelInfo;
            vkUpdateDescriptorSets(d, 2, writes, 0, nullptr);
        }
        device_.submitAndWait([&](VkCommandBuffer cmd) {
            vk::imageBarrier(cmd, prefiltered_.handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                             VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                             VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, 6);
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
            for (uint32_t level = 0; level < levels; ++level) {
                const uint32_t size = face >> level;
                const float roughness = levels > 1 ? float(level) / float(levels - 1) : 1.0f;
                // Samples per texel: the sharp levels read a small footprint, the rough ones need more.
                const float samples = roughness <= 0.0f ? 1.0f : level == 1 ? 32.0f : 64.0f;
                const glm::vec4 params(roughness, samples, float(source.desc().width), float(source.desc().mipLevels));
                vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, 1, &sets[level], 0, nullptr);
                vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(params), &params);
                vkCmdDispatch(cmd, (size + 7) / 8, (size + 7) / 8, 6);
            }
            vk::imageBarrier(cmd, prefiltered_.handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_GENERAL,
                             VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                             VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                             VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, 6);
        });
    } catch (...) {
        for (VkImageView v : views)
            if (v) vkDestroyImageView(d, v, nullptr);
        vkDestroyDescriptorPool(d, pool, nullptr);
        throw;
    }
    for (VkImageView v : views)
        if (v) vkDestroyImageView(d, v, nullptr);
    vkDestroyDescriptorPool(d, pool, nullptr);
}

std::vector<glm::vec4> GpuEnvironment::readPrefiltered() const {
    const uint32_t face = prefiltered_.desc().width, levels = prefiltered_.desc().mipLevels;
    size_t texels = 0;
    for (uint32_t level = 0; level < levels; ++level) texels += size_t(6) * (face >> level) * (face >> level);
    vk::Buffer readback(device_, texels * 4 * sizeof(uint16_t), VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    device_.submitAndWait([&](VkCommandBuffer cmd) {
        vk::imageBarrier(cmd, prefiltered_.handle(), VK_IMAGE_ASPECT_COLOR_BIT,
                         VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                         VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                         VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT, 6);
        VkDeviceSize offset = 0;
        for (uint32_t level = 0; level < levels; ++level) {
            VkBufferImageCopy region{};
            region.bufferOffset = offset;
            region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, 6};
            region.imageExtent = {face >> level, face >> level, 1};
            vkCmdCopyImageToBuffer(cmd, prefiltered_.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback.handle(),
                                   1, &region);
            offset += VkDeviceSize(6) * (face >> level) * (face >> level) * 4 * sizeof(uint16_t);
        }
        vk::imageBarrier(cmd, prefiltered_.handle(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                         VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                         VK_ACCESS_2_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                         VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, 6);
    });
    const auto* half = static_cast<const uint16_t*>(readback.mapped());
    std::vector<glm::vec4> out(texels);
    for (size_t i = 0; i < texels; ++i)
        out[i] = glm::vec4(glm::unpackHalf1x16(half[i * 4]), glm::unpackHalf1x16(half[i * 4 + 1]),
                           glm::unpackHalf1x16(half[i * 4 + 2]), glm::unpackHalf1x16(half[i * 4 + 3]));
    return out;
}

}  // namespace preskin
