#include "render/GpuLuts.h"

#include <preskin/Error.h>
#include <preskin/LutSet.h>

#include "vk/Check.h"

#include <fmt/core.h>

#include <algorithm>

namespace preskin {

namespace {

std::array<const LutTable*, 4> tablesOf(const LutSet& luts) {
    return {&luts.diffuse(), &luts.penumbra(), &luts.shTransfer(), &luts.transmittance()};
}

std::array<glm::ivec2*, 4> extentsOf(LutExtents& e) {
    return {&e.diffuse, &e.penumbra, &e.shTransfer, &e.transmittance};
}

// RGBA half texels of `table` in an extent.x x extent.y texture: the table at (0, 0), its last
// column and row repeated into the padding.
std::vector<uint16_t> paddedTexels(const LutTable& table, glm::ivec2 extent) {
    const std::vector<uint16_t> texels = table.rgba16f();
    if (extent == glm::ivec2(table.width(), table.height())) return texels;
    std::vector<uint16_t> out(size_t(extent.x) * size_t(extent.y) * 4);
    for (int y = 0; y < extent.y; ++y)
        for (int x = 0; x < extent.x; ++x) {
            const size_t from = (size_t(std::min(y, table.height() - 1)) * size_t(table.width()) +
                                 size_t(std::min(x, table.width() - 1))) *
                4;
            std::copy_n(texels.begin() + std::ptrdiff_t(from), 4,
                        out.begin() + std::ptrdiff_t((size_t(y) * size_t(extent.x) + size_t(x)) * 4));
        }
    return out;
}

}  // namespace

GpuLuts::GpuLuts(const vk::Device& device, const std::vector<const LutSet*>& layers) : device_(device) {
    // The shaders gather and filter by hand: no filtering (R32_SFLOAT need not be filterable).
    VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    info.magFilter = VK_FILTER_NEAREST;
    info.minFilter = VK_FILTER_NEAREST;
    info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    PRESKIN_VK(vkCreateSampler(device.device(), &info, nullptr, &sampler_));
    const auto layerCount = static_cast<uint32_t>(layers.size());
    if (layers.empty()) {
        const float one[3] = {1.0f, 1.0f, 1.0f};
        for (vk::Image& image : images_) {
            image =
                vk::Image(device,
                          {VK_FORMAT_R32_SFLOAT, 3, 1, 1, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                           VK_IMAGE_ASPECT_COLOR_BIT, 1, VK_SAMPLE_COUNT_1_BIT, true});
            image.uploadLayer(one, sizeof(one), 0, VK_IMAGE_LAYOUT_UNDEFINED);
        }
        return;
    }
    if (layerCount > device.properties().limits.maxImageArrayLayers)
        throw Error(fmt::format("Vulkan: {} diffusion profiles exceed the device's {} texture array layers", layerCount,
                                device.properties().limits.maxImageArrayLayers));
    for (const LutSet* luts : layers) {
        const auto tables = tablesOf(*luts);
        const auto extents = extentsOf(extents_);
        for (size_t t = 0; t < 4; ++t)
            *extents[t] = glm::max(*extents[t], glm::ivec2(tables[t]->width(), tables[t]->height()));
    }
    const auto extents = extentsOf(extents_);
    const uint32_t maxWidth = device.properties().limits.maxImageDimension2D;
    for (size_t t = 0; t < 4; ++t) {
        // Each table as its channel planes (lutPlanes), three times as wide.
        const uint32_t width = 3u * uint32_t(extents[t]->x);
        if (width > maxWidth)
            throw Error(
                fmt::format("Vulkan: a skin table {} texels wide needs a {}-texel image (its channel planes), "
                            "over the device's {}",
                            extents[t]->x, width, maxWidth));
        images_[t] = vk::Image(device,
                               {VK_FORMAT_R32_SFLOAT, width, uint32_t(extents[t]->y), 1,
                                VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, VK_IMAGE_ASPECT_COLOR_BIT,
                                layerCount, VK_SAMPLE_COUNT_1_BIT, true});
    }
    layers_.resize(layerCount);
    for (uint32_t layer = 0; layer < layerCount; ++layer) uploadLayer(layer, *layers[layer], VK_IMAGE_LAYOUT_UNDEFINED);
}

GpuLuts::~GpuLuts() {
    if (sampler_) vkDestroySampler(device_.device(), sampler_, nullptr);
}

void GpuLuts::uploadLayer(uint32_t layer, const LutSet& luts, VkImageLayout oldLayout) {
    const auto tables = tablesOf(luts);
    const auto extents = extentsOf(extents_);
    for (size_t t = 0; t < 4; ++t) {
        const std::vector<float> planes =
            lutPlanes(paddedTexels(*tables[t], *extents[t]), extents[t]->x, extents[t]->y);
        images_[t].uploadLayer(planes.data(), planes.size() * sizeof(float), layer, oldLayout);
    }
    layers_[layer].mapping = lutMapping(luts, extents_);
    layers_[layer].widthMm = glm::vec3(luts.profile().widthMm());
    layers_[layer].profile = std::make_shared<const DiffusionProfile>(luts.profile());
}

bool GpuLuts::replaceLayer(uint32_t layer, const LutSet& luts) {
    if (layer >= layerCount()) return false;
    const auto tables = tablesOf(luts);
    const auto extents = extentsOf(extents_);
    for (size_t t = 0; t < 4; ++t) {
        if (tables[t]->width() > extents[t]->x || tables[t]->height() > extents[t]->y) return false;
    }
    uploadLayer(layer, luts, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    return true;
}

std::array<VkDescriptorImageInfo, 4> GpuLuts::descriptors() const {
    std::array<VkDescriptorImageInfo, 4> out{};
    for (size_t i = 0; i < 4; ++i) out[i] = {sampler_, images_[i].view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    return out;
}

}  // namespace preskin
