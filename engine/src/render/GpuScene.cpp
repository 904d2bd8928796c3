#include "render/GpuScene.h"

#include <preskin/NormalBasis.h>
#include <preskin/SkinParameters.h>

#include "io/MessageText.h"
#include "shared/deform.h"
#include "vk/Check.h"
#include "vk/Pipeline.h"

#include <fmt/core.h>

#include <glm/gtc/matrix_inverse.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace preskin {

static_assert(sizeof(Vertex) == 52, "Vertex is read by the GPU with the layout of forward.vert");
static_assert(sizeof(NormalBasis) == gpu::kNormalBasisFloats * 4 && kNormalBasisCount == int(gpu::kNormalBasisCount) &&
                  offsetof(NormalBasis, opposing) == gpu::kNormalBasisCount * 12 &&
                  offsetof(NormalBasis, opposingCentroid) == gpu::kNormalBasisCount * 24,
              "NormalBasis is read by the GPU as consecutive vec3: averaged, opposing, centroid");

namespace {

VkFilter toVk(Filter f) { return f == Filter::Nearest ? VK_FILTER_NEAREST : VK_FILTER_LINEAR; }
VkSamplerAddressMode toVk(Wrap w) {
    switch (w) {
    case Wrap::ClampToEdge: return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    case Wrap::MirroredRepeat: return VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
    default: return VK_SAMPLER_ADDRESS_MODE_REPEAT;
    }
}

gpu::GpuUvTransform toGpu(const TextureRef& ref) {
    const glm::mat3 m = ref.uvTransform();  // column-major: m[col][row]
    return {glm::vec4(m[0][0], m[1][0], m[2][0], 0.0f), glm::vec4(m[0][1], m[1][1], m[2][1], 0.0f)};
}

// Whether a skin material's specular map can ride in its base colour's alpha, saving a texture
// read per fragment: the material is opaque (its base colour's alpha unused), both maps are 8-bit
// images of one size read through one sampler (the shader reads the specular map at the base
// colour's uv either way), so the packed alpha is filtered as the map itself would be.
bool specularPacksIntoBaseAlpha(const Scene& scene, const Material& mat) {
    if (!mat.skin || mat.alphaMode != AlphaMode::Opaque) return false;
    const TextureRef& base = mat.baseColor;
    const SkinTextureRef& specular = mat.skin->specularTexture;
    const auto image = [&](int i) {
        return i >= 0 && size_t(i) < scene.images.size() ? &scene.images[size_t(i)] : nullptr;
    };
    const Image* b = image(base.image);
    const Image* s = image(specular.image);
    return b && s && base.sampler == specular.sampler && b->width == s->width && b->height == s->height &&
        s->rgba16.empty() && s->rgba8.size() == b->rgba8.size();
}

}  // namespace

gpu::GpuInstance toGpuInstance(const glm::mat4& worldFromObject) {
    gpu::GpuInstance g{};
    g.worldFromObject = worldFromObject;
    g.normalWorldFromObject = glm::mat4(glm::inverseTranspose(glm::mat3(worldFromObject)));
    // Object curvature -> world curvature: 1 / the length scale (cube root of |det|).
    const float scale = std::cbrt(std::abs(glm::determinant(glm::mat3(worldFromObject))));
    g.params = glm::vec4(scale > 0.0f ? 1.0f / scale : 1.0f, 0.0f, 0.0f, 0.0f);
    return g;
}

GpuScene::GpuScene(const vk::Device& device, const Scene& scene) : device_(device), sceneMaterials_(scene.materials) {
    const VkDevice dev = device.device();
    // Geometry: one buffer each. Indices are stored rebased to the shared vertex buffer (every
    // draw has vertexOffset 0), so that consecutive primitives of a mesh that share a material
    // are one contiguous index range and can be drawn with one call (see below). The scene's
    // vertex limit keeps every index far below 2^32.
    std::vector<Vertex> allVertices;
    std::vector<uint32_t> allIndices;
    struct PrimitiveRange {
        uint32_t firstIndex, indexCount;
        int32_t vertexOffset;
    };
    std::vector<std::vector<PrimitiveRange>> meshRanges(scene.meshes.size());
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        meshFirstVertex.push_back(static_cast<uint32_t>(allVertices.size()));
        for (const Primitive& p : scene.meshes[m].primitives) {
            const auto base = static_cast<uint32_t>(allVertices.size());
            meshRanges[m].push_back(
                {static_cast<uint32_t>(allIndices.size()), static_cast<uint32_t>(p.indices.size()), 0});
            allVertices.insert(allVertices.end(), p.vertices.begin(), p.vertices.end());
            for (const uint32_t index : p.indices) allIndices.push_back(base + index);
        }
    }
    // The skin's normal basis, per mesh with a skin primitive (all its primitives as one surface,
    // as for curvature), in the millimetres of its first instance.
    std::vector<NormalBasis> allBasis(allVertices.size(), NormalBasis{});
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = scene.meshes[m];
        const bool skin = std::any_of(mesh.primitives.begin(), mesh.primitives.end(), [&](const Primitive& p) {
            return p.material >= 0 && size_t(p.material) < scene.materials.size() &&
                scene.materials[size_t(p.material)].skin.has_value();
        });
        if (!skin) continue;
        double scale = 1.0;
        for (const MeshInstance& inst : scene.instances)
            if (inst.mesh == int(m)) {
                const double s = std::cbrt(std::abs(glm::determinant(glm::dmat3(inst.worldFromObject))));
                if (std::isfinite(s) && s > 0.0) scale = s;
                break;
            }
        std::vector<glm::vec3> positions, normals;
        std::vector<uint32_t> meshIndices;
        for (const Primitive& p : mesh.primitives) {
            const auto base = static_cast<uint32_t>(positions.size());
            for (const Vertex& v : p.vertices) {
                positions.push_back(v.positionOs);
                normals.push_back(v.normalOs);
            }
            for (uint32_t index : p.indices) meshIndices.push_back(base + index);
        }
        const std::vector<NormalBasis> basis = computeNormalBasis(positions, normals, meshIndices, 1000.0 * scale);
        std::copy(basis.begin(), basis.end(), allBasis.begin() + meshFirstVertex[m]);
    }
    normalBasis = vk::Buffer(
        device, std::max<size_t>(allBasis.size(), 1) * sizeof(NormalBasis),
        VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
        false);
    normalBasis.upload(allBasis.data(), allBasis.size() * sizeof(NormalBasis));

    // Also read by the deformation pass (GpuDeformer) as its rest pose.
    vertices = vk::Buffer(device, std::max<size_t>(allVertices.size(), 1) * sizeof(Vertex),
                          VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, false);
    vertices.upload(allVertices.data(), allVertices.size() * sizeof(Vertex));
    indices = vk::Buffer(device, std::max<size_t>(allIndices.size(), 1) * sizeof(uint32_t),
                         VK_BUFFER_USAGE_INDEX_BUFFER_BIT, false);
    indices.upload(allIndices.data(), allIndices.size() * sizeof(uint32_t));

    // Instances and draws; texel density per material.
    const uint32_t defaultMaterial = static_cast<uint32_t>(scene.materials.size());
    std::vector<gpu::GpuInstance> instanceData;
    std::vector<double> uvArea(scene.materials.size() + 1, 0.0);
    std::vector<double> worldArea(scene.materials.size() + 1, 0.0);
    bool lastBlended = false;
    for (const MeshInstance& inst : scene.instances) {
        // One GPU instance per scene instance, so that poses index both alike.
        const uint32_t instanceIndex = static_cast<uint32_t>(instanceData.size());
        instanceData.push_back(toGpuInstance(inst.worldFromObject));
        if (inst.mesh < 0 || size_t(inst.mesh) >= scene.meshes.size()) continue;
        const Mesh& mesh = scene.meshes[size_t(inst.mesh)];
        for (size_t p = 0; p < mesh.primitives.size(); ++p) {
            const Primitive& prim = mesh.primitives[p];
            const PrimitiveRange& r = meshRanges[size_t(inst.mesh)][p];
            if (r.indexCount == 0) continue;
            const uint32_t material = prim.material >= 0 && size_t(prim.material) < scene.materials.size()
                ? static_cast<uint32_t>(prim.material)
                : defaultMaterial;
            const glm::vec3 center =
                glm::vec3(inst.worldFromObject *
                          glm::vec4(prim.boundsOs.empty() ? glm::vec3(0.0f) : prim.boundsOs.center(), 1.0f));
            // Draw submission costs the same per call whatever its size (on lavapipe about 10 us
            // per draw and pass), so a run of primitives of one instance with one material
            // becomes one draw. Blended primitives stay apart: they are sorted back to front.
            const bool blended =
                material < scene.materials.size() && scene.materials[material].alphaMode == AlphaMode::Blend;
            DrawItem* last = draws.empty() ? nullptr : &draws.back();
            if (!blended && last && last->instance == instanceIndex && last->material == material &&
                last->firstIndex + last->indexCount == r.firstIndex && !lastBlended) {
                last->indexCount += r.indexCount;
            } else {
                draws.push_back({r.firstIndex, r.indexCount, r.vertexOffset, instanceIndex, material, center});
            }
            lastBlended = blended;
            accumulateTexelDensity(prim, inst.worldFromObject, uvArea[material], worldArea[material]);
        }
    }
    restInstances = std::move(instanceData);
    for (size_t i = 0; i < scene.materials.size(); ++i)
        if (scene.materials[i].skin && worldArea[i] > 0.0 && !hasUvLayout(uvArea[i]))
            skinWithoutUvLayout.push_back(
                fmt::format("materials[{}] ('{}')", i, io::messageText(scene.materials[i].name)));

    // Default textures.
    const uint8_t whitePixel[4] = {255, 255, 255, 255};
    const uint8_t flatPixel[4] = {128, 128, 255, 255};
    white_ = vk::Image(device,
                       {VK_FORMAT_R8G8B8A8_UNORM, 1, 1, 1, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                        VK_IMAGE_ASPECT_COLOR_BIT});
    white_.uploadAndGenerateMips(whitePixel, 4);
    flatNormal_ = vk::Image(device,
                            {VK_FORMAT_R8G8B8A8_UNORM, 1, 1, 1,
                             VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, VK_IMAGE_ASPECT_COLOR_BIT});
    flatNormal_.uploadAndGenerateMips(flatPixel, 4);

    // Samplers: the scene's, then the default (linear, mipmapped, repeat).
    VkPhysicalDeviceFeatures features;
    vkGetPhysicalDeviceFeatures(device.physicalDevice(), &features);
    // Anisotropic filtering on hardware only: lavapipe emulates it with many taps per sample,
    // which nearly doubled the forward pass of the head scene there.
    const bool anisotropy = features.samplerAnisotropy && device.properties().deviceType != VK_PHYSICAL_DEVICE_TYPE_CPU;
    std::vector<Sampler> samplerDescs = scene.samplers;
    samplerDescs.push_back(Sampler{});
    for (const Sampler& s : samplerDescs) {
        VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
        info.magFilter = toVk(s.magFilter);
        info.minFilter = toVk(s.minFilter);
        info.mipmapMode =
            s.mipFilter == Filter::Nearest ? VK_SAMPLER_MIPMAP_MODE_NEAREST : VK_SAMPLER_MIPMAP_MODE_LINEAR;
        info.addressModeU = toVk(s.wrapU);
        info.addressModeV = toVk(s.wrapV);
        info.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
        info.maxLod = s.mipmaps ? VK_LOD_CLAMP_NONE : 0.0f;
        if (anisotropy && s.mipmaps && s.minFilter == Filter::Linear) {
            info.anisotropyEnable = VK_TRUE;
            info.maxAnisotropy = std::min(8.0f, device.properties().limits.maxSamplerAnisotropy);
        }
        VkSampler sampler = VK_NULL_HANDLE;
        PRESKIN_VK(vkCreateSampler(dev, &info, nullptr, &sampler));
        samplers_.push_back(sampler);
        samplerAnisotropic_.push_back(info.anisotropyEnable == VK_TRUE);
    }

    // Material descriptor sets.
    // The uniforms are read by both stages (the vertex stage: a skin material's per-vertex terms).
    std::vector<vk::Binding> bindings = {{gpu::kBindingMaterial, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER,
                                          VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT}};
    // The profile-weight texture too (the vertex stage blends the normal basis weights by it).
    for (uint32_t b = 1; b <= gpu::kMaterialTextureCount; ++b)
        bindings.push_back({b, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                            b == gpu::kBindingProfileWeightTexture || b == gpu::kBindingCurvatureTexture
                                ? VkShaderStageFlags(VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT)
                                : VkShaderStageFlags(VK_SHADER_STAGE_FRAGMENT_BIT)});
    materialLayout_ = vk::createSetLayout(device, bindings);
    const uint32_t setCount = defaultMaterial + 1;
    const VkDescriptorPoolSize sizes[] = {
        {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, setCount},
        {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, setCount * gpu::kMaterialTextureCount}};
    pool_ = vk::createDescriptorPool(device, sizes, setCount);

    const VkDeviceSize align = device.properties().limits.minUniformBufferOffsetAlignment;
    uniformStride_ = (sizeof(gpu::MaterialUniforms) + align - 1) / align * align;
    materialUniforms_ = vk::Buffer(device, uniformStride_ * setCount, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true);

    for (uint32_t i = 0; i < setCount; ++i) {
        const Material fallback;
        const Material& mat = i < defaultMaterial ? sceneMaterials_[i] : fallback;
        GpuMaterial gm;
        gm.skin = mat.skin.has_value();
        if (mat.skin) gm.quality = mat.skin->quality;
        gm.alphaMode = mat.alphaMode;
        gm.doubleSided = mat.doubleSided;
        const bool specularInBaseAlpha = specularPacksIntoBaseAlpha(scene, mat);
        if (mat.skin)
            gm.skinInputs = (mat.skin->detailNormalTexture.valid() ? gpu::kSkinInputDetailNormals : 0u) |
                (uint32_t(static_cast<int>(mat.skin->curvatureSource)) << gpu::kSkinInputCurvatureShift) |
                (specularInBaseAlpha                     ? gpu::kSkinInputSpecularInBaseAlpha
                     : mat.skin->specularTexture.valid() ? gpu::kSkinInputSpecularMap
                                                         : 0u);
        // Without anisotropic filtering the unbiased normal is the biased samples' levels blended
        // at the unbiased level of detail: the shader takes it from them.
        if (mat.skin && !samplerAnisotropic_[samplerSlot(mat.normal.sampler)] &&
            !(mat.skin->detailNormalTexture.valid() &&
              samplerAnisotropic_[samplerSlot(mat.skin->detailNormalTexture.sampler)]))
            gm.skinInputs |= gpu::kSkinInputSpecularFromLevels;
        if (mat.skin && mat.skin->profileWeightTexture.valid())
            gm.profileMix = 1u + uint32_t(std::min(mat.skin->blendProfiles.size(), size_t(kMaxBlendedProfiles - 1)));
        if (mat.normal.valid() && size_t(mat.normal.image) < scene.images.size()) {
            const Image& img = scene.images[size_t(mat.normal.image)];
            // KHR_texture_transform's scale repeats the map: density grows with it.
            gm.texelsPerMm = texelsPerMm(uvArea[i], worldArea[i], img.width, img.height) *
                std::sqrt(std::abs(mat.normal.uvScale.x * mat.normal.uvScale.y));
        }
        gm.set = vk::allocateDescriptorSet(device, pool_, materialLayout_);

        struct Slot {
            uint32_t binding;
            int image;
            int sampler;
            bool srgb;
            const vk::Image* fallbackImage;
            int alphaFrom = -1;
        };
        const SkinMaterial skin = mat.skin.value_or(SkinMaterial{});
        const Slot slots[] = {
            {gpu::kBindingBaseColorTexture, mat.baseColor.image, mat.baseColor.sampler, true, &white_,
             specularInBaseAlpha ? skin.specularTexture.image : -1},
            {gpu::kBindingMetallicRoughnessTexture, mat.metallicRoughness.image, mat.metallicRoughness.sampler, false,
             &white_},
            {gpu::kBindingNormalTexture, mat.normal.image, mat.normal.sampler, false, &flatNormal_},
            {gpu::kBindingOcclusionTexture, mat.occlusion.image, mat.occlusion.sampler, false, &white_},
            {gpu::kBindingEmissiveTexture, mat.emissive.image, mat.emissive.sampler, true, &white_},
            {gpu::kBindingSpecularTexture, specularInBaseAlpha ? -1 : skin.specularTexture.image,
             skin.specularTexture.sampler, false, &white_},
            {gpu::kBindingDetailNormalTexture, skin.detailNormalTexture.image, skin.detailNormalTexture.sampler, false,
             &flatNormal_},
            {gpu::kBindingCurvatureTexture, skin.curvatureTexture.image, skin.curvatureTexture.sampler, false, &white_},
            {gpu::kBindingProfileWeightTexture, skin.profileWeightTexture.image, skin.profileWeightTexture.sampler,
             false, &white_},
        };
        std::array<VkDescriptorImageInfo, gpu::kMaterialTextureCount> imageInfos{};
        std::array<VkWriteDescriptorSet, gpu::kMaterialTextureCount + 1> writes{};
        const VkDescriptorBufferInfo bufferInfo{materialUniforms_.handle(), uniformStride_ * i,
                                                sizeof(gpu::MaterialUniforms)};
        writes[0] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        writes[0].dstSet = gm.set;
        writes[0].dstBinding = gpu::kBindingMaterial;
        writes[0].descriptorCount = 1;
        writes[0].descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
        writes[0].pBufferInfo = &bufferInfo;
        for (size_t s = 0; s < std::size(slots); ++s) {
            const Slot& slot = slots[s];
            const bool valid = slot.image >= 0 && size_t(slot.image) < scene.images.size();
            const vk::Image& image =
                valid ? texture(scene, slot.image, slot.srgb, slot.alphaFrom) : *slot.fallbackImage;
            imageInfos[s] = {sampler(slot.sampler), image.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
            if (slot.binding == gpu::kBindingNormalTexture || slot.binding == gpu::kBindingDetailNormalTexture)
                gm.normalMipLevels = std::max(gm.normalMipLevels, image.desc().mipLevels);
            writes[s + 1] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
            writes[s + 1].dstSet = gm.set;
            writes[s + 1].dstBinding = slot.binding;
            writes[s + 1].descriptorCount = 1;
            writes[s + 1].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
            writes[s + 1].pImageInfo = &imageInfos[s];
        }
        vkUpdateDescriptorSets(dev, static_cast<uint32_t>(writes.size()), writes.data(), 0, nullptr);
        materials.push_back(gm);
    }
    updateMaterials({});
}

GpuScene::~GpuScene() {
    const VkDevice dev = device_.device();
    for (VkSampler s : samplers_) vkDestroySampler(dev, s, nullptr);
    if (pool_) vkDestroyDescriptorPool(dev, pool_, nullptr);
    if (materialLayout_) vkDestroyDescriptorSetLayout(dev, materialLayout_, nullptr);
}

const vk::Image& GpuScene::texture(const Scene& scene, int image, bool srgb, int alphaFrom) {
    const auto key = std::make_tuple(image, srgb, alphaFrom);
    auto it = textures_.find(key);
    if (it != textures_.end()) return it->second;
    const Image& src = scene.images[size_t(image)];
    if (src.width == 0 || src.height == 0 || src.rgba8.size() != size_t(src.width) * src.height * 4)
        throw Error(fmt::format("{}: image data does not match its size {}x{}", src.name, src.width, src.height));
    const uint32_t maxDim = device_.properties().limits.maxImageDimension2D;
    if (src.width > maxDim || src.height > maxDim)
        throw Error(fmt::format("{}: {}x{} exceeds the device's largest texture ({})", src.name, src.width, src.height,
                                maxDim));
    if (!src.rgba16.empty() && src.rgba16.size() != src.rgba8.size())
        throw Error(
            fmt::format("{}: 16-bit image data does not match its size {}x{}", src.name, src.width, src.height));
    // Linear uses of 16-bit sources keep their precision (curvature and height maps step visibly at
    // 8 bits) where the device filters and blits the format (optional in Vulkan; common).
    const bool sixteen = !srgb && alphaFrom < 0 && !src.rgba16.empty() &&
        device_.supportsFormat(VK_FORMAT_R16G16B16A16_UNORM,
                               VK_FORMAT_FEATURE_2_SAMPLED_IMAGE_FILTER_LINEAR_BIT | VK_FORMAT_FEATURE_2_BLIT_SRC_BIT |
                                   VK_FORMAT_FEATURE_2_BLIT_DST_BIT);
    vk::ImageDesc desc;
    desc.format = srgb ? VK_FORMAT_R8G8B8A8_SRGB : sixteen ? VK_FORMAT_R16G16B16A16_UNORM : VK_FORMAT_R8G8B8A8_UNORM;
    desc.width = src.width;
    desc.height = src.height;
    desc.mipLevels = vk::mipLevelCount(src.width, src.height);
    desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    vk::Image gpuImage(device_, desc);
    if (sixteen) {
        gpuImage.uploadAndGenerateMips(src.rgba16.data(), src.rgba16.size() * sizeof(uint16_t));
    } else if (alphaFrom >= 0) {
        // The alpha source's red in the alpha (specularPacksIntoBaseAlpha matched the two sizes).
        const Image& alpha = scene.images[size_t(alphaFrom)];
        std::vector<uint8_t> packed = src.rgba8;
        for (size_t p = 3; p < packed.size(); p += 4) packed[p] = alpha.rgba8[p - 3];
        gpuImage.uploadAndGenerateMips(packed.data(), packed.size());
    } else {
        gpuImage.uploadAndGenerateMips(src.rgba8.data(), src.rgba8.size());
    }
    return textures_.emplace(key, std::move(gpuImage)).first->second;
}

VkSampler GpuScene::sampler(int index) const { return samplers_[samplerSlot(index)]; }

size_t GpuScene::samplerSlot(int index) const {
    return index >= 0 && size_t(index) + 1 < samplers_.size() ? size_t(index) : samplers_.size() - 1;
}

gpu::MaterialUniforms GpuScene::uniformsFor(const Material& mat, const GpuMaterial& gm,
                                            const std::vector<ProfileLayer>& layers) const {
    gpu::MaterialUniforms u{};
    u.baseColorFactor = mat.baseColorFactor;
    // A specular map packed into the base colour's alpha reads through an alpha factor of 1 (an
    // opaque material's alpha is unused otherwise).
    if ((gm.skinInputs & gpu::kSkinInputSpecularInBaseAlpha) != 0u) u.baseColorFactor.a = 1.0f;
    u.emissiveAlphaCutoff = glm::vec4(mat.emissiveFactor, mat.alphaCutoff);
    u.pbr = glm::vec4(mat.metallicFactor, mat.roughnessFactor, mat.normal.scale, mat.occlusion.scale);
    u.textureFlags = glm::vec4(0.0f, 1.0f, 0.0f, mat.normal.valid() ? 1.0f : 0.0f);
    // Absent textures are not sampled at all (a sample of the 1x1 stand-in costs as much as any).
    u.hasTextures = glm::vec4(mat.baseColor.valid() ? 1.0f : 0.0f, mat.metallicRoughness.valid() ? 1.0f : 0.0f,
                              mat.occlusion.valid() ? 1.0f : 0.0f, mat.emissive.valid() ? 1.0f : 0.0f);
    const TextureRef* refs[] = {&mat.baseColor, &mat.metallicRoughness, &mat.normal, &mat.occlusion, &mat.emissive};
    for (size_t i = 0; i < 5; ++i) u.uv[i] = toGpu(*refs[i]);
    if (mat.skin) {
        const SkinMaterial& s = *mat.skin;
        u.skinScatter = glm::vec4(s.scatterScale, s.curvatureTextureBias, s.curvatureTextureScalePerM, s.transmission);
        auto layerOf = [&](int index) {
            return index >= 0 && size_t(index) < layers.size() ? layers[size_t(index)] : ProfileLayer{};
        };
        u.skinTransmission = glm::vec4(s.transmissionColor, s.thicknessScale);
        u.skinSpecular = glm::vec4(s.specularIntensity, s.lobeRoughness0, s.lobeRoughness1, s.lobeMix);
        u.textureFlags.x = s.detailNormalScale;
        u.textureFlags.y = s.detailUvScale;
        // Layer p + 1 holds profile p (layer 0: the default set); unused entries repeat the first.
        const auto blended = std::min(s.blendProfiles.size(), size_t(kMaxBlendedProfiles - 1));
        const float base = float(s.profile + 1);
        u.skinProfileLayers = glm::vec4(base);
        for (size_t i = 0; i < blended; ++i) u.skinProfileLayers[int(i) + 1] = float(s.blendProfiles[i] + 1);
        u.skinProfileBlend = glm::vec4(s.profileWeightTexture.valid() ? float(blended) : 0.0f, 0.0f, 0.0f, 0.0f);
        for (int i = 0; i < 4; ++i) {
            const ProfileLayer& layer = layerOf(int(u.skinProfileLayers[i]));
            u.skinLuts[i] = layer.mapping;
            // Each profile's own normal prefiltering; the fragment blends them as it blends the lookups.
            u.skinNormalLodBias[i] = glm::vec4(
                s.normalLodBias ? *s.normalLodBias : normalLodBias(layer.widthMm, s.scatterScale, gm.texelsPerMm),
                0.0f);
        }
        for (int i = 0; i < 4; ++i)
            if (const auto& profile = layerOf(int(u.skinProfileLayers[i])).profile) {
                const std::array<glm::vec4, 3> w = normalBasisWeights(*profile, s.scatterScale);
                for (int c = 0; c < 3; ++c) u.skinNormalBasis[3 * i + c] = w[size_t(c)];
            }
    }
    return u;
}

void GpuScene::updateMaterials(const std::vector<ProfileLayer>& layers) {
    const Material fallback;
    for (size_t i = 0; i < materials.size(); ++i) {
        const Material& mat = i < sceneMaterials_.size() ? sceneMaterials_[i] : fallback;
        const gpu::MaterialUniforms u = uniformsFor(mat, materials[i], layers);
        // The levels the biased samples span, over every profile of the material's mix.
        glm::vec3 low = u.skinNormalLodBias[0], high = low;
        for (const glm::vec4& bias : u.skinNormalLodBias) {
            low = glm::min(low, glm::vec3(bias));
            high = glm::max(high, glm::vec3(bias));
        }
        const float lowest = std::min(low.x, std::min(low.y, low.z));
        const float highest = std::max(high.x, std::max(high.y, high.z));
        materials[i].normalLevels =
            uint32_t(normalLevelCount(glm::vec3(lowest, highest, highest), materials[i].normalMipLevels,
                                      (materials[i].skinInputs & gpu::kSkinInputSpecularFromLevels) != 0u));
        materials[i].lutMapping = u.skinLuts[0];
        materialUniforms_.upload(&u, sizeof(u), uniformStride_ * i);
    }
}

}  // namespace preskin
