// The skin LUTs on the GPU: four R32_SFLOAT 2D array textures (diffuse, penumbra, SH transfer,
// transmittance), one layer per diffusion profile (layer 0 the default set, <preskin/ProfileLibrary.h>),
// each table stored as its channel planes side by side (lutPlanes), gathered and filtered by hand
// in the shaders (preskin/lut.glsl) with an unfiltered CLAMP_TO_EDGE sampler; each layer's
// LutMapping goes to the uniforms of the materials that use it (GpuScene::updateMaterials). Array textures need no descriptor indexing, so this runs on lavapipe. Each texture
// is as large as the largest layer's table; smaller tables are padded with their edge texels and
// their mapping addresses only their own texels. Without LUT sets, 1x1 stand-ins keep the
// descriptors valid and skin materials render with the standard model.
#pragma once

#include <preskin/LutSet.h>

#include "render/GpuScene.h"
#include "shared/gpu_types.h"
#include "vk/Resources.h"

#include <array>
#include <vector>

namespace preskin {

class GpuLuts {
public:
    GpuLuts(const vk::Device& device, const std::vector<const LutSet*>& layers);
    ~GpuLuts();
    GpuLuts(const GpuLuts&) = delete;
    GpuLuts& operator=(const GpuLuts&) = delete;

    bool valid() const { return !layers_.empty(); }
    uint32_t layerCount() const { return static_cast<uint32_t>(layers_.size()); }
    // Per layer: the profile's scattering widths (normal-map LOD biases) and its tables' LutMapping
    // in the (possibly larger) array textures.
    const std::vector<ProfileLayer>& layers() const { return layers_; }
    // Replaces one layer's tables and mapping when they fit the textures (returns false, and
    // changes nothing, when a table is larger). The GPU must not be using the textures.
    bool replaceLayer(uint32_t layer, const LutSet& luts);
    // diffuse, penumbra, SH transfer, transmittance
    std::array<VkDescriptorImageInfo, 4> descriptors() const;

private:
    void uploadLayer(uint32_t layer, const LutSet& luts, VkImageLayout oldLayout);

    const vk::Device& device_;
    std::vector<ProfileLayer> layers_;
    LutExtents extents_;
    std::array<vk::Image, 4> images_;
    VkSampler sampler_ = VK_NULL_HANDLE;
};

}  // namespace preskin
