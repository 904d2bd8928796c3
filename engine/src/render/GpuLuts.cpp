#include "render/GpuLuts.h"

#include <preskin/LutSet.h>

#include "vk/Check.h"

#include <fmt/core.h>

namespace preskin {

namespace {

vk::Image uploadTable(const vk::Device& device, const LutTable& table) {
    if (!device.supportsFormat(VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_FEATURE_2_SAMPLED_IMAGE_FILTER_LINEAR_BIT))
        throw Error("Vulkan: the device cannot filter R16G16B16A16_SFLOAT textures linearly");
    vk::Image image(device, {VK_FORMAT_R16G16B16A16_SFLOAT, uint32_t(table.width()), uint32_t(table.height()), 1,
                             VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, VK_IMAGE_ASPECT_COLOR_BIT});
    const std::vector<uint16_t> texels = table.rgba16f();
    image.uploadAndGenerateMips(texels.data(), texels.size() * sizeof(uint16_t));
    return image;
}

}  // namespace

GpuLuts::GpuLuts(const vk::Device& device, const LutSet* luts) : device_(device) {
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = VK_FILTER_LINEAR;
    info.minFilter = VK_FILTER_LINEAR;
    info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    PRESKIN_VK(vkCreateSampler(device.device(), &info, nullptr, &sampler_));
    if (luts) {
        images_[0] = uploadTable(device, luts->diffuse());
        images_[1] = uploadTable(device, luts->penumbra());
        images_[2] = uploadTable(device, luts->shTransfer());
        images_[3] = uploadTable(device, luts->transmittance());
        mapping_ = lutMapping(*luts);
        widths_.widthMm = glm::vec3(luts->profile().widthMm());
        valid_ = true;
        return;
    }
    const uint8_t white[4] = {255, 255, 255, 255};
    for (vk::Image& image : images_) {
        image = vk::Image(device, {VK_FORMAT_R8G8B8A8_UNORM, 1, 1, 1,
                                   VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                                   VK_IMAGE_ASPECT_COLOR_BIT});
        image.uploadAndGenerateMips(white, sizeof(white));
    }
}

GpuLuts::~GpuLuts() {
    if (sampler_) vkDestroySampler(device_.device(), sampler_, nullptr);
}

std::array<VkDescriptorImageInfo, 4> GpuLuts::descriptors() const {
    std::array<VkDescriptorImageInfo, 4> out{};
    for (size_t i = 0; i < 4; ++i) out[i] = {sampler_, images_[i].view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    return out;
}

}  // namespace preskin
