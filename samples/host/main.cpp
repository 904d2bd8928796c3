// preskin-host: a small host renderer that embeds preskin the way an engine does. It owns its
// Vulkan instance, device, offscreen target and command buffers, and draws a glTF scene (by
// default the head preskin installs) once into a PNG in one of two ways:
//  - its own passes (the default): a depth-only shadow pass for the scene's shadow light, then
//    its own forward shader (host.frag, which includes preskin/skin.glsl) with its own pipeline
//    and descriptor layout. From preskin it takes only what a host takes: the scene loader, the
//    LUTs (LutSet::loadDefault, lutMapping), the SH of the environment, the view framing, the
//    normal basis and the per-channel normal-map biases;
//  - preskin's renderer inside its frame (--renderer): Context::wrap on its own device and
//    Renderer::record into its own command buffer and colour image.
//
//   preskin-host [--scene FILE.gltf] [--out FILE.png] [--width W] [--height H] [--device NAME]
//                [--skin-quality low|medium|high] [--no-shadows] [--renderer]
//
// Limits of its own passes: one shadow map over the scene's bounding sphere (no wide map, so red
// scatters into cast shadows only as far as the map's filter reaches), the scene's first material
// for every primitive, no texture transforms, at most 8 lights; textures get a linear mip chain as
// preskin's renderer gives them.
#include <vulkan/vulkan.h>

#include <preskin/Context.h>
#include <preskin/Environment.h>
#include <preskin/Error.h>
#include <preskin/LightRecord.h>
#include <preskin/LutSet.h>
#include <preskin/NormalBasis.h>
#include <preskin/Renderer.h>  // writeImage
#include <preskin/Scene.h>
#include <preskin/SkinParameters.h>
#include <preskin/View.h>
#include <shared/light.h>

#include <glm/gtc/matrix_inverse.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "Gpu.h"        // the Vulkan set-up any host has
#include "host_frag.h"  // SPIR-V of host.frag and host.vert, compiled by CMakeLists.txt
#include "host_vert.h"

namespace {

using host::check;
using host::Gpu;
using host::mipCount;
using host::shaderModule;

struct Frame {  // host.frag's uniform block
    preskin::gpu::LutMapping lut;
    glm::vec4 sh[9];
    glm::vec4 cameraPositionWs;
    glm::vec4 skin;
    glm::vec4 lodBias;
    glm::vec4 lobes;
    glm::vec4 transmission;
    glm::mat4 shadowClipFromWorld;
    glm::vec4 shadowParams;
    glm::uvec4 lightCount;
    preskin::gpu::GpuLight lights[8];
};

struct Camera {  // host.vert's uniform block
    glm::mat4 clipFromWorld;
    glm::vec4 normalBasisWeights[3];  // preskin::normalBasisWeights() per channel
};

struct Draw {  // host.vert's push constants
    glm::mat4 worldFromObject;
    glm::vec4 normalFromObject[3];
};

// The shadow light's map: orthographic over the scene's bounding sphere, looking along the light
// (x, y in [-1, 1], depth 0 near .. 1 far), and preskin/shadow.glsl's parameters: texel size (m),
// filter sigma (texels), depth range (m), map size (texels).
struct ShadowFit {
    glm::mat4 clipFromWorld{1.0f};
    glm::vec4 params{0.0f};
};
ShadowFit fitShadow(const preskin::Bounds& bounds, const glm::vec3& direction, uint32_t mapSize, float sigmaTexels) {
    const glm::vec3 centre = 0.5f * (bounds.min + bounds.max);
    const float radius = std::max(0.5f * glm::length(bounds.max - bounds.min), 1e-4f);
    const glm::vec3 forward = glm::normalize(direction);
    const glm::vec3 right = glm::normalize(
        glm::cross(std::abs(forward.y) < 0.99f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(1.0f, 0.0f, 0.0f), forward));
    const glm::vec3 up = glm::cross(forward, right);
    ShadowFit fit;
    glm::mat4& m = fit.clipFromWorld;  // m[column][row]
    m = glm::mat4(0.0f);
    for (int i = 0; i < 3; ++i) {
        m[i][0] = right[i] / radius;
        m[i][1] = up[i] / radius;
        m[i][2] = forward[i] / (2.0f * radius);
    }
    m[3] = glm::vec4(-glm::dot(centre, right) / radius, -glm::dot(centre, up) / radius,
                     (radius - glm::dot(centre, forward)) / (2.0f * radius), 1.0f);
    fit.params = glm::vec4(2.0f * radius / float(mapSize), sigmaTexels, 2.0f * radius, float(mapSize));
    return fit;
}

struct Options {
    std::string scenePath = PRESKIN_DATA_DIR "/samples/assets/head/head.gltf";
    std::string out = "host.png";
    std::string deviceName;
    uint32_t width = 256, height = 256;
    preskin::SkinQuality quality = preskin::SkinQuality::High;
    bool shadows = true;
    bool renderer = false;
};

const char* kUsage =
    "usage: preskin-host [--scene FILE.gltf] [--out FILE.png] [--width W] [--height H] [--device NAME]\n"
    "                    [--skin-quality low|medium|high] [--no-shadows] [--renderer]\n"
    "Renders the scene (default: the head preskin installs) once and writes a PNG (default host.png,\n"
    "256x256): with the host's own shadow pass and skin shader, or with --renderer preskin's renderer\n"
    "recorded into the host's command buffer (Context::wrap, Renderer::record).\n"
    "--device: part of a device name (default: the first). --skin-quality: the skin techniques compiled\n"
    "in (default high: all). --no-shadows: no shadow map (no penumbra, transmission or opposing light).\n";

// Throws std::invalid_argument with the message for a bad command line; false after --help.
bool parseOptions(int argc, char** argv, Options& o) {
    for (int i = 1; i < argc; ++i) {
        const std::string flag = argv[i];
        if (flag == "--help" || flag == "-h") {
            std::fputs(kUsage, stdout);
            return false;
        }
        if (flag == "--no-shadows" || flag == "--renderer") {
            (flag == "--renderer" ? o.renderer : o.shadows) = flag == "--renderer";
            continue;
        }
        if (flag != "--scene" && flag != "--out" && flag != "--device" && flag != "--width" && flag != "--height" &&
            flag != "--skin-quality")
            throw std::invalid_argument(flag + ": unknown option (see --help)");
        if (i + 1 >= argc) throw std::invalid_argument(flag + ": value: missing");
        const std::string value = argv[++i];
        if (flag == "--scene") {
            o.scenePath = value;
        } else if (flag == "--out") {
            o.out = value;
        } else if (flag == "--device") {
            o.deviceName = value;
        } else if (flag == "--skin-quality") {
            if (value != "low" && value != "medium" && value != "high")
                throw std::invalid_argument(flag + ": value: '" + value + "' is not low, medium or high");
            o.quality = value == "low" ? preskin::SkinQuality::Low
                : value == "medium"    ? preskin::SkinQuality::Medium
                                       : preskin::SkinQuality::High;
        } else {
            char* end = nullptr;
            const unsigned long n = std::strtoul(value.c_str(), &end, 10);
            if (value.empty() || *end != '\0' || n < 1 || n > 16384)
                throw std::invalid_argument(flag + ": value: '" + value + "' is not a whole number in [1, 16384]");
            (flag == "--width" ? o.width : o.height) = uint32_t(n);
        }
    }
    return true;
}

// The renderer inside the host's frame: Context::wrap on the host's device, Renderer::record into
// the host's command buffer and colour image (left in TRANSFER_SRC for the host's readback, which
// `afterwards` records behind it). The renderer's shadow pass, wide shadow map, light grid and
// forward pass are all in that one command buffer; the host submits it.
void renderWithPreskin(Gpu& gpu, const Options& o, const preskin::Scene& scene, const preskin::Environment& env,
                       const preskin::LutSet& luts, const preskin::View& view, const Gpu::Image& color,
                       VkFormat colorFormat, const std::function<void(VkCommandBuffer)>& afterwards) {
    preskin::HostVulkan host;
    host.getInstanceProcAddr = vkGetInstanceProcAddr;
    host.instance = gpu.instance;
    host.physicalDevice = gpu.physical;
    host.device = gpu.device;
    host.queue = gpu.queue;
    host.queueFamilyIndex = gpu.family;
    const std::unique_ptr<preskin::Context> context = preskin::Context::wrap(host);
    preskin::RenderSettings settings;
    settings.skinQuality = o.quality;
    settings.shadows = o.shadows;
    preskin::Renderer renderer(*context, scene, env, &luts, settings);
    preskin::RenderTarget target;
    target.image = color.image;
    target.view = color.view;
    target.format = colorFormat;
    target.extent = {o.width, o.height};
    target.layoutBefore = VK_IMAGE_LAYOUT_UNDEFINED;
    target.layoutAfter = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    gpu.submit([&](VkCommandBuffer cmd) {
        renderer.record(cmd, target, view, 0);
        afterwards(cmd);
    });
}  // the renderer and its context go before the host's device

// The host's own passes into `color` (left in TRANSFER_SRC; `afterwards` records the readback
// behind them): the shadow map of the scene's shadow light, then the forward pass with host.frag.
void renderWithHostPasses(Gpu& gpu, const Options& o, const preskin::Scene& scene, const preskin::Environment& env,
                          const preskin::LutSet& luts, const preskin::Eye& eye, const Gpu::Image& color,
                          VkFormat colorFormat, const std::function<void(VkCommandBuffer)>& afterwards) {
    if (scene.materials.empty() || !scene.materials[0].baseColor.valid() || !scene.materials[0].normal.valid())
        throw std::runtime_error(o.scenePath +
                                 ": the host sample needs a first material with base colour and normal maps");
    const preskin::Material& material = scene.materials[0];
    const preskin::SkinMaterial skin = material.skin.value_or(preskin::SkinMaterial{});

    Frame frame{};
    frame.lut = preskin::lutMapping(luts);
    for (int i = 0; i < 9; ++i) frame.sh[i] = glm::vec4(env.radianceSh().c[size_t(i)], 0.0f);
    frame.cameraPositionWs = glm::vec4(eye.positionWs, 1.0f);
    frame.skin = glm::vec4(skin.scatterScale, std::clamp(material.roughnessFactor, 0.03f, 1.0f), skin.specularIntensity,
                           material.normal.scale);
    frame.lobes = glm::vec4(skin.lobeRoughness0, skin.lobeRoughness1, skin.lobeMix, 0.0f);
    frame.transmission = glm::vec4(skin.transmission * skin.transmissionColor, skin.thicknessScale);
    // The normal map's per-channel biases from its texel density on the mesh and the profile.
    double uvArea = 0.0, areaMm2 = 0.0;
    for (const preskin::MeshInstance& inst : scene.instances)
        for (const preskin::Primitive& p : scene.meshes[size_t(inst.mesh)].primitives)
            preskin::accumulateTexelDensity(p, inst.worldFromObject, uvArea, areaMm2);
    const preskin::Image& normalImage = scene.images[size_t(material.normal.image)];
    const glm::vec3 lodBias = skin.normalLodBias.value_or(
        preskin::normalLodBias(glm::vec3(luts.profile().widthMm()), skin.scatterScale,
                               preskin::texelsPerMm(uvArea, areaMm2, normalImage.width, normalImage.height)));
    // The whole mip levels the biased samples blend; the map has a full chain (texture() below).
    frame.lodBias =
        glm::vec4(lodBias, float(preskin::normalLevelCount(lodBias, mipCount(normalImage.width, normalImage.height))));
    // The first 8 lights; the shadow light (preskin's choice: the first directional light that
    // casts shadows) gets the shadow map when it is among them.
    const int shadowLight = o.shadows ? preskin::shadowLightIndex(scene.lights) : -1;
    const bool shadowed = shadowLight >= 0 && shadowLight < 8;
    for (const preskin::Light& l : scene.lights) {
        if (frame.lightCount.x == 8) break;
        frame.lights[frame.lightCount.x] = preskin::toGpuLight(l, shadowed && int(frame.lightCount.x) == shadowLight);
        ++frame.lightCount.x;
    }
    const uint32_t shadowMapSize = shadowed ? 2048u : 1u;  // without a shadow light: cleared, never read
    if (shadowed) {
        const ShadowFit fit = fitShadow(scene.worldBounds(), scene.lights[size_t(shadowLight)].directionWs,
                                        shadowMapSize, 1.5f);  // preskin's defaults: 2048 texels, sigma 1.5
        frame.shadowClipFromWorld = fit.clipFromWorld;
        frame.shadowParams = fit.params;
        frame.lightCount.y = uint32_t(shadowLight);
        frame.lightCount.z = 1u;
    }

    // The host's own Vulkan objects.
    const VkDevice dev = gpu.device;
    std::vector<preskin::Vertex> vertices;
    std::vector<preskin::NormalBasis> normalBasis;  // the second vertex stream: the skin's prefiltered normals
    std::vector<uint32_t> indices;
    struct DrawRange {
        uint32_t firstIndex, indexCount;
        Draw push;
    };
    std::vector<DrawRange> draws;
    for (const preskin::MeshInstance& inst : scene.instances) {
        const glm::mat3 normalFromObject = glm::inverseTranspose(glm::mat3(inst.worldFromObject));
        Draw push{inst.worldFromObject, {}};
        for (int c = 0; c < 3; ++c) push.normalFromObject[c] = glm::vec4(normalFromObject[c], 0.0f);
        push.normalFromObject[0].w = 1.0f / inst.curvatureScale();
        // The mesh's normal basis, all its primitives as one surface, in its world millimetres.
        const preskin::Mesh& mesh = scene.meshes[size_t(inst.mesh)];
        std::vector<glm::vec3> positions, normals;
        std::vector<uint32_t> meshIndices;
        for (const preskin::Primitive& p : mesh.primitives) {
            for (uint32_t index : p.indices) meshIndices.push_back(uint32_t(positions.size()) + index);
            for (const preskin::Vertex& v : p.vertices) {
                positions.push_back(v.positionOs);
                normals.push_back(v.normalOs);
            }
        }
        const std::vector<preskin::NormalBasis> basis =
            preskin::computeNormalBasis(positions, normals, meshIndices, 1000.0 / inst.curvatureScale());
        normalBasis.insert(normalBasis.end(), basis.begin(), basis.end());
        for (const preskin::Primitive& p : mesh.primitives) {
            draws.push_back({uint32_t(indices.size()), uint32_t(p.indices.size()), push});
            for (uint32_t index : p.indices) indices.push_back(uint32_t(vertices.size()) + index);
            vertices.insert(vertices.end(), p.vertices.begin(), p.vertices.end());
        }
    }
    const VkBuffer vertexBuffer =
        gpu.buffer(vertices.size() * sizeof(preskin::Vertex), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, vertices.data());
    const VkBuffer indexBuffer = gpu.buffer(indices.size() * 4, VK_BUFFER_USAGE_INDEX_BUFFER_BIT, indices.data());
    const VkBuffer frameBuffer = gpu.buffer(sizeof(Frame), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, &frame);
    const VkBuffer basisBuffer = gpu.buffer(normalBasis.size() * sizeof(preskin::NormalBasis),
                                            VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, normalBasis.data());
    Camera camera{eye.clipFromWorld(), {}};
    const std::array<glm::vec4, 3> basisWeights = preskin::normalBasisWeights(luts.profile(), skin.scatterScale);
    for (int c = 0; c < 3; ++c) camera.normalBasisWeights[c] = basisWeights[size_t(c)];
    const VkBuffer cameraBuffer = gpu.buffer(sizeof(Camera), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, &camera);
    Camera lightCamera = camera;  // the shadow pass draws with the same vertex shader from the light
    lightCamera.clipFromWorld = frame.shadowClipFromWorld;
    const VkBuffer lightCameraBuffer = gpu.buffer(sizeof(Camera), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, &lightCamera);
    const VkFormat depthFormat = VK_FORMAT_D32_SFLOAT;
    const Gpu::Image shadowMap =
        gpu.image(depthFormat, shadowMapSize, shadowMapSize, 1,
                  VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, VK_IMAGE_ASPECT_DEPTH_BIT);

    auto sceneTexture = [&](int index, VkFormat format) {
        const preskin::Image& img = scene.images[size_t(index)];
        return gpu.texture(format, img.width, img.height, img.rgba8.data(), img.rgba8.size(), true);
    };
    // Each skin table as its channel planes (one float channel, three times as wide).
    auto lutTexture = [&](const preskin::LutTable& table) {
        const std::vector<float> planes = table.planes();
        return gpu.texture(VK_FORMAT_R32_SFLOAT, uint32_t(table.width() * 3), uint32_t(table.height()), planes.data(),
                           planes.size() * sizeof(float), false, VK_IMAGE_VIEW_TYPE_2D_ARRAY);
    };
    const uint8_t white[4] = {255, 255, 255, 255};
    // Bindings 1..5 and 7..9 of host.frag (6 is the vertex stage's camera).
    const VkImageView views[] = {
        sceneTexture(material.baseColor.image, VK_FORMAT_R8G8B8A8_SRGB),
        sceneTexture(material.normal.image, VK_FORMAT_R8G8B8A8_UNORM),
        skin.specularTexture.valid() ? sceneTexture(skin.specularTexture.image, VK_FORMAT_R8G8B8A8_UNORM)
                                     : gpu.texture(VK_FORMAT_R8G8B8A8_UNORM, 1, 1, white, 4, false),
        lutTexture(luts.diffuse()),
        lutTexture(luts.shTransfer()),
        shadowMap.view,
        lutTexture(luts.penumbra()),
        lutTexture(luts.transmittance()),
    };
    // Material textures: linear, mipmapped, repeat; LUTs and the shadow map: unfiltered (the
    // shader gathers), clamped, no mips.
    VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
    si.magFilter = si.minFilter = VK_FILTER_LINEAR;
    si.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
    si.maxLod = VK_LOD_CLAMP_NONE;
    VkSampler materialSampler, lutSampler;
    check(vkCreateSampler(dev, &si, nullptr, &materialSampler), "vkCreateSampler");
    si.addressModeU = si.addressModeV = si.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    si.magFilter = si.minFilter = VK_FILTER_NEAREST;
    si.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
    si.maxLod = 0.0f;
    check(vkCreateSampler(dev, &si, nullptr, &lutSampler), "vkCreateSampler");

    // The host's descriptor layouts: the forward pass's (its frame block, eight textures and the
    // camera) and the shadow pass's (the light's camera alone: its vertex stage reads nothing else).
    constexpr uint32_t kBindings = 10;
    VkDescriptorSetLayoutBinding bindings[kBindings]{};
    for (uint32_t b = 0; b < kBindings; ++b)
        bindings[b] = {b, b == 0 ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER : VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
                       VK_SHADER_STAGE_FRAGMENT_BIT, nullptr};
    bindings[6] = {6, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_VERTEX_BIT, nullptr};
    VkDescriptorSetLayoutCreateInfo li{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    li.bindingCount = kBindings;
    li.pBindings = bindings;
    VkDescriptorSetLayout setLayout, shadowSetLayout;
    check(vkCreateDescriptorSetLayout(dev, &li, nullptr, &setLayout), "vkCreateDescriptorSetLayout");
    li.bindingCount = 1;
    li.pBindings = &bindings[6];
    check(vkCreateDescriptorSetLayout(dev, &li, nullptr, &shadowSetLayout), "vkCreateDescriptorSetLayout");
    const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 3},
                                          {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kBindings - 2}};
    VkDescriptorPoolCreateInfo dpi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    dpi.maxSets = 2;
    dpi.poolSizeCount = 2;
    dpi.pPoolSizes = sizes;
    VkDescriptorPool descriptorPool;
    check(vkCreateDescriptorPool(dev, &dpi, nullptr, &descriptorPool), "vkCreateDescriptorPool");
    const VkDescriptorSetLayout setLayouts[2] = {setLayout, shadowSetLayout};
    VkDescriptorSetAllocateInfo dai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    dai.descriptorPool = descriptorPool;
    dai.descriptorSetCount = 2;
    dai.pSetLayouts = setLayouts;
    VkDescriptorSet sets[2];  // forward, shadow
    check(vkAllocateDescriptorSets(dev, &dai, sets), "vkAllocateDescriptorSets");
    const VkDescriptorBufferInfo bufferInfos[3] = {
        {frameBuffer, 0, sizeof(Frame)}, {cameraBuffer, 0, sizeof(Camera)}, {lightCameraBuffer, 0, sizeof(Camera)}};
    VkDescriptorImageInfo imageInfos[kBindings];
    VkWriteDescriptorSet writes[kBindings + 1];
    for (uint32_t b = 0; b < kBindings; ++b) {
        writes[b] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        writes[b].dstSet = sets[0];
        writes[b].dstBinding = b;
        writes[b].descriptorCount = 1;
        writes[b].descriptorType = bindings[b].descriptorType;
        if (b == 0 || b == 6) {
            writes[b].pBufferInfo = &bufferInfos[b == 0 ? 0 : 1];
            continue;
        }
        const uint32_t view = b < 6 ? b - 1 : b - 2;
        imageInfos[b] = {b <= 3 ? materialSampler : lutSampler, views[view], VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        writes[b].pImageInfo = &imageInfos[b];
    }
    writes[kBindings] = writes[6];
    writes[kBindings].dstSet = sets[1];
    writes[kBindings].pBufferInfo = &bufferInfos[2];
    vkUpdateDescriptorSets(dev, kBindings + 1, writes, 0, nullptr);

    // The host's pipeline: its own shaders, reversed Z as preskin's views project.
    const VkPushConstantRange pushRange{VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(Draw)};
    VkPipelineLayoutCreateInfo pli{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    pli.setLayoutCount = 1;
    pli.pSetLayouts = &setLayout;
    pli.pushConstantRangeCount = 1;
    pli.pPushConstantRanges = &pushRange;
    VkPipelineLayout pipelineLayout, shadowPipelineLayout;
    check(vkCreatePipelineLayout(dev, &pli, nullptr, &pipelineLayout), "vkCreatePipelineLayout");
    pli.pSetLayouts = &shadowSetLayout;
    check(vkCreatePipelineLayout(dev, &pli, nullptr, &shadowPipelineLayout), "vkCreatePipelineLayout");
    const VkShaderModule vs = shaderModule(dev, spv_host_vert, sizeof(spv_host_vert));
    const VkShaderModule fs = shaderModule(dev, spv_host_frag, sizeof(spv_host_frag));
    VkPipelineShaderStageCreateInfo stages[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                                 {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
    stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stages[0].module = vs;
    stages[0].pName = "main";
    stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[1].module = fs;
    stages[1].pName = "main";
    // The skin techniques compiled in: host.frag's specialization constant 0.
    const uint32_t features = preskin::skinQualityFeatures(o.quality).mask();
    const VkSpecializationMapEntry featuresEntry{0, 0, sizeof(uint32_t)};
    const VkSpecializationInfo specialization{1, &featuresEntry, sizeof(uint32_t), &features};
    stages[1].pSpecializationInfo = &specialization;
    const VkVertexInputBindingDescription vertexBindings[] = {
        {0, sizeof(preskin::Vertex), VK_VERTEX_INPUT_RATE_VERTEX},
        {1, sizeof(preskin::NormalBasis), VK_VERTEX_INPUT_RATE_VERTEX}};
    std::vector<VkVertexInputAttributeDescription> attributes = {
        {preskin::gpu::kAttributePosition, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(preskin::Vertex, positionOs)},
        {preskin::gpu::kAttributeNormal, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(preskin::Vertex, normalOs)},
        {preskin::gpu::kAttributeTangent, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(preskin::Vertex, tangentOs)},
        {preskin::gpu::kAttributeUv0, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(preskin::Vertex, uv0)},
        {preskin::gpu::kAttributeCurvature, 0, VK_FORMAT_R32_SFLOAT, offsetof(preskin::Vertex, curvaturePerM)}};
    for (uint32_t b = 0; b < preskin::gpu::kNormalBasisCount; ++b)
        attributes.push_back({preskin::gpu::kAttributeNormalBasis + b, 1, VK_FORMAT_R32G32B32_SFLOAT,
                              uint32_t(offsetof(preskin::NormalBasis, averaged) + b * sizeof(glm::vec3))});
    for (uint32_t b = 0; b < preskin::gpu::kNormalBasisCount; ++b)
        attributes.push_back({preskin::gpu::kAttributeOpposing + b, 1, VK_FORMAT_R32G32B32_SFLOAT,
                              uint32_t(offsetof(preskin::NormalBasis, opposing) + b * sizeof(glm::vec3))});
    attributes.push_back({preskin::gpu::kAttributeOpposingCentroid, 1, VK_FORMAT_R32G32B32_SFLOAT,
                          offsetof(preskin::NormalBasis, opposingCentroid)});
    VkPipelineVertexInputStateCreateInfo vertexInput{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    vertexInput.vertexBindingDescriptionCount = 2;
    vertexInput.pVertexBindingDescriptions = vertexBindings;
    vertexInput.vertexAttributeDescriptionCount = uint32_t(attributes.size());
    vertexInput.pVertexAttributeDescriptions = attributes.data();
    VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    const VkViewport viewport{0.0f, 0.0f, float(o.width), float(o.height), 0.0f, 1.0f};
    const VkRect2D scissor{{0, 0}, {o.width, o.height}};
    VkPipelineViewportStateCreateInfo viewportState{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    viewportState.viewportCount = 1;
    viewportState.pViewports = &viewport;
    viewportState.scissorCount = 1;
    viewportState.pScissors = &scissor;
    VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    raster.cullMode = material.doubleSided ? VK_CULL_MODE_NONE : VK_CULL_MODE_BACK_BIT;
    raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    raster.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineDepthStencilStateCreateInfo depthState{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    depthState.depthTestEnable = depthState.depthWriteEnable = VK_TRUE;
    depthState.depthCompareOp = VK_COMPARE_OP_GREATER_OR_EQUAL;
    VkPipelineColorBlendAttachmentState blendAttachment{};
    blendAttachment.colorWriteMask = 0xf;
    VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    blend.attachmentCount = 1;
    blend.pAttachments = &blendAttachment;
    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    rendering.colorAttachmentCount = 1;
    rendering.pColorAttachmentFormats = &colorFormat;
    rendering.depthAttachmentFormat = depthFormat;
    VkGraphicsPipelineCreateInfo gpi{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    gpi.pNext = &rendering;
    gpi.stageCount = 2;
    gpi.pStages = stages;
    gpi.pVertexInputState = &vertexInput;
    gpi.pInputAssemblyState = &assembly;
    gpi.pViewportState = &viewportState;
    gpi.pRasterizationState = &raster;
    gpi.pMultisampleState = &multisample;
    gpi.pDepthStencilState = &depthState;
    gpi.pColorBlendState = &blend;
    gpi.layout = pipelineLayout;
    VkPipeline pipeline;
    check(vkCreateGraphicsPipelines(dev, VK_NULL_HANDLE, 1, &gpi, nullptr, &pipeline), "vkCreateGraphicsPipelines");

    // The shadow pass's pipeline: the same vertex stage from the light, depth only (0 near .. 1
    // far), both facings (thickness reads the nearest surface of either), and preskin's depth
    // bias, which preskinShadowOccluder adds back when it measures an occluder's distance.
    const VkViewport shadowViewport{0.0f, 0.0f, float(shadowMapSize), float(shadowMapSize), 0.0f, 1.0f};
    const VkRect2D shadowArea{{0, 0}, {shadowMapSize, shadowMapSize}};
    VkPipelineViewportStateCreateInfo shadowViewportState = viewportState;
    shadowViewportState.pViewports = &shadowViewport;
    shadowViewportState.pScissors = &shadowArea;
    VkPipelineRasterizationStateCreateInfo shadowRaster = raster;
    shadowRaster.cullMode = VK_CULL_MODE_NONE;
    shadowRaster.depthBiasEnable = VK_TRUE;
    shadowRaster.depthBiasConstantFactor = preskin::gpu::kShadowDepthBiasConstant;
    shadowRaster.depthBiasSlopeFactor = preskin::gpu::kShadowDepthBiasSlope;
    VkPipelineDepthStencilStateCreateInfo shadowDepthState = depthState;
    shadowDepthState.depthCompareOp = VK_COMPARE_OP_LESS_OR_EQUAL;
    VkPipelineColorBlendStateCreateInfo noColor{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    VkPipelineRenderingCreateInfo depthOnly{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    depthOnly.depthAttachmentFormat = depthFormat;
    VkGraphicsPipelineCreateInfo shadowInfo = gpi;
    shadowInfo.pNext = &depthOnly;
    shadowInfo.stageCount = 1;
    shadowInfo.pViewportState = &shadowViewportState;
    shadowInfo.pRasterizationState = &shadowRaster;
    shadowInfo.pDepthStencilState = &shadowDepthState;
    shadowInfo.pColorBlendState = &noColor;
    shadowInfo.layout = shadowPipelineLayout;
    VkPipeline shadowPipeline;
    check(vkCreateGraphicsPipelines(dev, VK_NULL_HANDLE, 1, &shadowInfo, nullptr, &shadowPipeline),
          "vkCreateGraphicsPipelines");

    // One frame: the shadow pass (cleared to far; drawn when there is a shadow light), then the
    // forward pass into the host's target, then the host's readback.
    const Gpu::Image depth = gpu.image(depthFormat, o.width, o.height, 1, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                                       VK_IMAGE_ASPECT_DEPTH_BIT);
    gpu.submit([&](VkCommandBuffer cmd) {
        const VkBuffer vertexBuffers[2] = {vertexBuffer, basisBuffer};
        const VkDeviceSize offsets[2] = {0, 0};
        auto drawScene = [&](VkPipeline p, VkPipelineLayout layout, VkDescriptorSet set) {
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p);
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &set, 0, nullptr);
            vkCmdBindVertexBuffers(cmd, 0, 2, vertexBuffers, offsets);
            vkCmdBindIndexBuffer(cmd, indexBuffer, 0, VK_INDEX_TYPE_UINT32);
            for (const DrawRange& d : draws) {
                vkCmdPushConstants(cmd, layout, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(Draw), &d.push);
                vkCmdDrawIndexed(cmd, d.indexCount, 1, d.firstIndex, 0, 0);
            }
        };
        Gpu::barrier(cmd, shadowMap.image, VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, VK_IMAGE_LAYOUT_UNDEFINED,
                     VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL);
        const VkRenderingAttachmentInfo shadowAttachment = Gpu::clearedAttachment(
            shadowMap.view, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VkClearValue{.depthStencil = {1.0f, 0}}, true);
        VkRenderingInfo shadowPass{VK_STRUCTURE_TYPE_RENDERING_INFO};
        shadowPass.renderArea = shadowArea;
        shadowPass.layerCount = 1;
        shadowPass.pDepthAttachment = &shadowAttachment;
        vkCmdBeginRendering(cmd, &shadowPass);
        if (shadowed) drawScene(shadowPipeline, shadowPipelineLayout, sets[1]);
        vkCmdEndRendering(cmd);
        Gpu::barrier(cmd, shadowMap.image, VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);

        Gpu::barrier(cmd, color.image, VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, VK_IMAGE_LAYOUT_UNDEFINED,
                     VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
        Gpu::barrier(cmd, depth.image, VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, VK_IMAGE_LAYOUT_UNDEFINED,
                     VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL);
        const VkRenderingAttachmentInfo colorAttachment =  // cleared to preskin render's background
            Gpu::clearedAttachment(color.view, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                                   VkClearValue{.color = {{0.045f, 0.045f, 0.05f, 1.0f}}}, true);
        const VkRenderingAttachmentInfo depthAttachment =  // reversed Z: cleared to far
            Gpu::clearedAttachment(depth.view, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                                   VkClearValue{.depthStencil = {0.0f, 0}}, false);
        VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
        ri.renderArea = scissor;
        ri.layerCount = 1;
        ri.colorAttachmentCount = 1;
        ri.pColorAttachments = &colorAttachment;
        ri.pDepthAttachment = &depthAttachment;
        vkCmdBeginRendering(cmd, &ri);
        drawScene(pipeline, pipelineLayout, sets[0]);
        vkCmdEndRendering(cmd);
        Gpu::barrier(cmd, color.image, VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                     VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
        afterwards(cmd);
    });

    vkDestroyPipeline(dev, shadowPipeline, nullptr);
    vkDestroyPipeline(dev, pipeline, nullptr);
    vkDestroyShaderModule(dev, vs, nullptr);
    vkDestroyShaderModule(dev, fs, nullptr);
    vkDestroyPipelineLayout(dev, pipelineLayout, nullptr);
    vkDestroyPipelineLayout(dev, shadowPipelineLayout, nullptr);
    vkDestroyDescriptorPool(dev, descriptorPool, nullptr);
    vkDestroyDescriptorSetLayout(dev, setLayout, nullptr);
    vkDestroyDescriptorSetLayout(dev, shadowSetLayout, nullptr);
    vkDestroySampler(dev, materialSampler, nullptr);
    vkDestroySampler(dev, lutSampler, nullptr);
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    try {
        if (!parseOptions(argc, argv, o)) return 0;
    } catch (const std::invalid_argument& e) {
        std::fprintf(stderr, "preskin-host: error: %s\n", e.what());
        return 1;
    }
    try {
        // What preskin gives a host: the scene, LUTs and their mapping, environment SH, the view.
        const preskin::Scene scene = preskin::Scene::load(o.scenePath);
        // The default set baked in-process (about 0.1 s on two cores): the core reads LUT folders of
        // raw tables (`preskin bake --raw`) by itself and EXR ones with preskin::imageio, which
        // this host does not link.
        const preskin::LutSet& luts = preskin::LutSet::loadDefault();
        const preskin::Environment env = scene.environmentPath
            ? preskin::Environment::load(*scene.environmentPath, scene.environmentIntensity, scene.environmentRotation)
            : preskin::Environment::constant(glm::vec3(0.25f));
        const preskin::View view = preskin::frameBoundsView(scene.worldBounds(), float(o.width) / float(o.height));

        // The host's device, its offscreen target and readback.
        Gpu gpu(o.deviceName);
        const VkFormat colorFormat = VK_FORMAT_R8G8B8A8_SRGB;
        const Gpu::Image color =
            gpu.image(colorFormat, o.width, o.height, 1,
                      VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, VK_IMAGE_ASPECT_COLOR_BIT);
        void* pixels = nullptr;
        const VkBuffer readback =
            gpu.buffer(VkDeviceSize(o.width) * o.height * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, nullptr, &pixels);
        auto copyOut = [&](VkCommandBuffer cmd) {
            VkBufferImageCopy region{};
            region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            region.imageExtent = {o.width, o.height, 1};
            vkCmdCopyImageToBuffer(cmd, color.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback, 1, &region);
        };
        if (o.renderer)
            renderWithPreskin(gpu, o, scene, env, luts, view, color, colorFormat, copyOut);
        else
            renderWithHostPasses(gpu, o, scene, env, luts, view.eyes[0], color, colorFormat, copyOut);

        preskin::RenderedImage image;
        image.width = o.width;
        image.height = o.height;
        image.rgba8.assign(static_cast<const uint8_t*>(pixels),
                           static_cast<const uint8_t*>(pixels) + size_t(o.width) * o.height * 4);
        preskin::writeImage(o.out, image);
        std::printf("preskin-host: wrote %s (%ux%u)\n", o.out.c_str(), o.width, o.height);
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "preskin-host: error: %s\n", e.what());
        return 1;
    }
}
