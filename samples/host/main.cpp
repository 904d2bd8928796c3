// preskin-host: a small host renderer that embeds preskin the way an engine does. It owns its
// Vulkan instance, device, pipeline, descriptor layout and offscreen target, draws with its own
// forward shader (host.frag, which includes preskin/skin.glsl) and takes from preskin only what
// a host takes: the scene loader, the LUTs (LutSet::loadDefault, lutMapping), the SH of the environment,
// the view framing and the per-channel normal-map biases. It renders a glTF scene (by default
// the head preskin installs) once and writes a PNG.
//
//   preskin-host [--scene FILE.gltf] [--out FILE.png] [--width W] [--height H] [--device NAME]
//
// Limits: no shadow pass, the scene's first material for every primitive, no texture transforms,
// at most 8 lights; textures get a linear mip chain as preskin's renderer gives them.
#include <vulkan/vulkan.h>

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

#include "host_frag.h"  // SPIR-V of host.frag and host.vert, compiled by CMakeLists.txt
#include "host_vert.h"

namespace {

// Levels of a full mip chain of a width x height image.
uint32_t mipCount(uint32_t width, uint32_t height) {
    uint32_t mips = 1;
    while (std::max(width, height) >> mips) ++mips;
    return mips;
}

void check(VkResult r, const char* what) {
    if (r != VK_SUCCESS) throw std::runtime_error(std::string(what) + " failed (VkResult " + std::to_string(r) + ")");
}

struct Frame {  // host.frag's uniform block
    preskin::gpu::LutMapping lut;
    glm::vec4 sh[9];
    glm::vec4 cameraPositionWs;
    glm::vec4 skin;
    glm::vec4 lodBias;
    glm::vec4 lobes;
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

class Gpu {
public:
    explicit Gpu(const std::string& deviceName) {
        VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
        app.pApplicationName = "preskin-host";
        app.apiVersion = VK_API_VERSION_1_3;
        VkInstanceCreateInfo ii{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
        ii.pApplicationInfo = &app;
        check(vkCreateInstance(&ii, nullptr, &instance), "vkCreateInstance");
        uint32_t count = 0;
        vkEnumeratePhysicalDevices(instance, &count, nullptr);
        std::vector<VkPhysicalDevice> devices(count);
        vkEnumeratePhysicalDevices(instance, &count, devices.data());
        for (VkPhysicalDevice d : devices) {
            VkPhysicalDeviceProperties p;
            vkGetPhysicalDeviceProperties(d, &p);
            if (p.apiVersion >= VK_API_VERSION_1_3 && std::string(p.deviceName).find(deviceName) != std::string::npos) {
                physical = d;
                break;
            }
        }
        if (!physical) throw std::runtime_error("no Vulkan 1.3 device named like '" + deviceName + "'");
        vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, nullptr);
        std::vector<VkQueueFamilyProperties> families(count);
        vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, families.data());
        while (family < count && !(families[family].queueFlags & VK_QUEUE_GRAPHICS_BIT)) ++family;
        const float priority = 1.0f;
        VkDeviceQueueCreateInfo qi{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
        qi.queueFamilyIndex = family;
        qi.queueCount = 1;
        qi.pQueuePriorities = &priority;
        VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
        f13.dynamicRendering = VK_TRUE;
        f13.synchronization2 = VK_TRUE;
        VkDeviceCreateInfo di{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
        di.pNext = &f13;
        di.queueCreateInfoCount = 1;
        di.pQueueCreateInfos = &qi;
        check(vkCreateDevice(physical, &di, nullptr, &device), "vkCreateDevice");
        vkGetDeviceQueue(device, family, 0, &queue);
        VkCommandPoolCreateInfo pi{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pi.queueFamilyIndex = family;
        check(vkCreateCommandPool(device, &pi, nullptr, &pool), "vkCreateCommandPool");
    }
    ~Gpu() {
        vkDeviceWaitIdle(device);
        for (auto it = cleanup.rbegin(); it != cleanup.rend(); ++it) (*it)();
        vkDestroyCommandPool(device, pool, nullptr);
        vkDestroyDevice(device, nullptr);
        vkDestroyInstance(instance, nullptr);
    }

    VkDeviceMemory allocate(VkMemoryRequirements req, VkMemoryPropertyFlags flags) {
        VkPhysicalDeviceMemoryProperties mp;
        vkGetPhysicalDeviceMemoryProperties(physical, &mp);
        uint32_t type = 0;
        while (type < mp.memoryTypeCount &&
               (!(req.memoryTypeBits & (1u << type)) || (mp.memoryTypes[type].propertyFlags & flags) != flags))
            ++type;
        VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        ai.allocationSize = req.size;
        ai.memoryTypeIndex = type;
        VkDeviceMemory memory;
        check(vkAllocateMemory(device, &ai, nullptr, &memory), "vkAllocateMemory");
        cleanup.push_back([this, memory] { vkFreeMemory(device, memory, nullptr); });
        return memory;
    }

    // A host-visible buffer holding `bytes` (copied in when given); returns its mapping.
    VkBuffer buffer(VkDeviceSize size, VkBufferUsageFlags usage, const void* bytes, void** mapped = nullptr) {
        VkBufferCreateInfo bi{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
        bi.size = size;
        bi.usage = usage;
        VkBuffer buffer;
        check(vkCreateBuffer(device, &bi, nullptr, &buffer), "vkCreateBuffer");
        cleanup.push_back([this, buffer] { vkDestroyBuffer(device, buffer, nullptr); });
        VkMemoryRequirements req;
        vkGetBufferMemoryRequirements(device, buffer, &req);
        VkDeviceMemory memory =
            allocate(req, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
        vkBindBufferMemory(device, buffer, memory, 0);
        void* p = nullptr;
        vkMapMemory(device, memory, 0, size, 0, &p);
        if (bytes) std::memcpy(p, bytes, size);
        if (mapped) *mapped = p;
        return buffer;
    }

    struct Image {
        VkImage image;
        VkImageView view;
    };
    Image image(VkFormat format, uint32_t width, uint32_t height, uint32_t mips, VkImageUsageFlags usage,
                VkImageAspectFlags aspect, VkImageViewType viewType = VK_IMAGE_VIEW_TYPE_2D) {
        VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
        ci.imageType = VK_IMAGE_TYPE_2D;
        ci.format = format;
        ci.extent = {width, height, 1};
        ci.mipLevels = mips;
        ci.arrayLayers = 1;
        ci.samples = VK_SAMPLE_COUNT_1_BIT;
        ci.usage = usage;
        Image out;
        check(vkCreateImage(device, &ci, nullptr, &out.image), "vkCreateImage");
        VkMemoryRequirements req;
        vkGetImageMemoryRequirements(device, out.image, &req);
        vkBindImageMemory(device, out.image, allocate(req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT), 0);
        VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        vi.image = out.image;
        vi.viewType = viewType;
        vi.format = format;
        vi.subresourceRange = {aspect, 0, mips, 0, 1};
        check(vkCreateImageView(device, &vi, nullptr, &out.view), "vkCreateImageView");
        cleanup.push_back([this, out] {
            vkDestroyImageView(device, out.view, nullptr);
            vkDestroyImage(device, out.image, nullptr);
        });
        return out;
    }

    void submit(const std::function<void(VkCommandBuffer)>& record) {
        VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        ai.commandPool = pool;
        ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        ai.commandBufferCount = 1;
        VkCommandBuffer cmd;
        check(vkAllocateCommandBuffers(device, &ai, &cmd), "vkAllocateCommandBuffers");
        VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        vkBeginCommandBuffer(cmd, &bi);
        record(cmd);
        vkEndCommandBuffer(cmd);
        VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        si.commandBufferCount = 1;
        si.pCommandBuffers = &cmd;
        check(vkQueueSubmit(queue, 1, &si, VK_NULL_HANDLE), "vkQueueSubmit");
        check(vkQueueWaitIdle(queue), "vkQueueWaitIdle");
        vkFreeCommandBuffers(device, pool, 1, &cmd);
    }

    static void barrier(VkCommandBuffer cmd, VkImage image, VkImageAspectFlags aspect, uint32_t mip, uint32_t mips,
                        VkImageLayout from, VkImageLayout to) {
        VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
        b.srcStageMask = b.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
        b.srcAccessMask = b.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
        b.oldLayout = from;
        b.newLayout = to;
        b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.image = image;
        b.subresourceRange = {aspect, mip, mips, 0, 1};
        VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        dep.imageMemoryBarrierCount = 1;
        dep.pImageMemoryBarriers = &b;
        vkCmdPipelineBarrier2(cmd, &dep);
    }

    // A sampled texture from tightly packed rows, with a mip chain of linear blits when `mipmapped`.
    VkImageView texture(VkFormat format, uint32_t width, uint32_t height, const void* pixels, size_t bytes,
                        bool mipmapped, VkImageViewType viewType = VK_IMAGE_VIEW_TYPE_2D) {
        const uint32_t mips = mipmapped ? mipCount(width, height) : 1u;
        const Image img =
            image(format, width, height, mips,
                  VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                  VK_IMAGE_ASPECT_COLOR_BIT, viewType);
        const VkBuffer staging = buffer(bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, pixels);
        submit([&](VkCommandBuffer cmd) {
            barrier(cmd, img.image, VK_IMAGE_ASPECT_COLOR_BIT, 0, mips, VK_IMAGE_LAYOUT_UNDEFINED,
                    VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
            VkBufferImageCopy region{};
            region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            region.imageExtent = {width, height, 1};
            vkCmdCopyBufferToImage(cmd, staging, img.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
            for (uint32_t level = 1; level < mips; ++level) {
                barrier(cmd, img.image, VK_IMAGE_ASPECT_COLOR_BIT, level - 1, 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                        VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
                VkImageBlit blit{};
                blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level - 1, 0, 1};
                blit.srcOffsets[1] = {std::max(1, int32_t(width >> (level - 1))),
                                      std::max(1, int32_t(height >> (level - 1))), 1};
                blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, 1};
                blit.dstOffsets[1] = {std::max(1, int32_t(width >> level)), std::max(1, int32_t(height >> level)), 1};
                vkCmdBlitImage(cmd, img.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, img.image,
                               VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
                barrier(cmd, img.image, VK_IMAGE_ASPECT_COLOR_BIT, level - 1, 1, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                        VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
            }
            barrier(cmd, img.image, VK_IMAGE_ASPECT_COLOR_BIT, mips - 1, 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                    VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        });
        return img.view;
    }

    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t family = 0;
    VkCommandPool pool = VK_NULL_HANDLE;
    std::vector<std::function<void()>> cleanup;  // in creation order; destroyed in reverse below
};

VkShaderModule shaderModule(VkDevice device, const uint32_t* code, size_t bytes) {
    VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    ci.codeSize = bytes;
    ci.pCode = code;
    VkShaderModule module;
    check(vkCreateShaderModule(device, &ci, nullptr, &module), "vkCreateShaderModule");
    return module;
}

}  // namespace

int main(int argc, char** argv) {
    std::string scenePath = PRESKIN_DATA_DIR "/samples/assets/head/head.gltf";
    std::string out = "host.png";
    std::string deviceName;
    uint32_t width = 256, height = 256;
    const char* usage =
        "usage: preskin-host [--scene FILE.gltf] [--out FILE.png] [--width W] [--height H] [--device NAME]\n"
        "Renders the scene (default: the head preskin installs) once with the host's own skin shader and\n"
        "writes a PNG (default host.png, 256x256). --device: part of a device name (default: the first).\n";
    for (int i = 1; i < argc; i += 2) {
        const std::string flag = argv[i];
        if (flag == "--help" || flag == "-h") {
            std::fputs(usage, stdout);
            return 0;
        }
        if (flag != "--scene" && flag != "--out" && flag != "--device" && flag != "--width" && flag != "--height") {
            std::fprintf(stderr, "preskin-host: error: %s: unknown option (see --help)\n", flag.c_str());
            return 1;
        }
        if (i + 1 >= argc) {
            std::fprintf(stderr, "preskin-host: error: %s: value: missing\n", flag.c_str());
            return 1;
        }
        const std::string value = argv[i + 1];
        if (flag == "--scene")
            scenePath = value;
        else if (flag == "--out")
            out = value;
        else if (flag == "--device")
            deviceName = value;
        else {
            char* end = nullptr;
            const unsigned long n = std::strtoul(value.c_str(), &end, 10);
            if (value.empty() || *end != '\0' || n < 1 || n > 16384) {
                std::fprintf(stderr, "preskin-host: error: %s: value: '%s' is not a whole number in [1, 16384]\n",
                             flag.c_str(), value.c_str());
                return 1;
            }
            (flag == "--width" ? width : height) = uint32_t(n);
        }
    }
    try {
        // What preskin gives a host: the scene, LUTs and their mapping, environment SH, the view.
        const preskin::Scene scene = preskin::Scene::load(scenePath);
        // The default set baked in-process (about 0.1 s on two cores): the core reads LUT folders of
        // raw tables (`preskin bake --raw`) by itself and EXR ones with preskin::imageio, which
        // this host does not link.
        const preskin::LutSet& luts = preskin::LutSet::loadDefault();
        const preskin::Environment env = scene.environmentPath
            ? preskin::Environment::load(*scene.environmentPath, scene.environmentIntensity, scene.environmentRotation)
            : preskin::Environment::constant(glm::vec3(0.25f));
        const preskin::Eye eye = preskin::frameBoundsView(scene.worldBounds(), float(width) / float(height)).eyes[0];
        if (scene.materials.empty() || !scene.materials[0].baseColor.valid() || !scene.materials[0].normal.valid())
            throw std::runtime_error(scenePath +
                                     ": the host sample needs a first material with base colour and normal maps");
        const preskin::Material& material = scene.materials[0];
        const preskin::SkinMaterial skin = material.skin.value_or(preskin::SkinMaterial{});

        Frame frame{};
        frame.lut = preskin::lutMapping(luts);
        for (int i = 0; i < 9; ++i) frame.sh[i] = glm::vec4(env.radianceSh().c[size_t(i)], 0.0f);
        frame.cameraPositionWs = glm::vec4(eye.positionWs, 1.0f);
        frame.skin = glm::vec4(skin.scatterScale, std::clamp(material.roughnessFactor, 0.03f, 1.0f),
                               skin.specularIntensity, material.normal.scale);
        frame.lobes = glm::vec4(skin.lobeRoughness0, skin.lobeRoughness1, skin.lobeMix, 0.0f);
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
        frame.lodBias = glm::vec4(
            lodBias, float(preskin::normalLevelCount(lodBias, mipCount(normalImage.width, normalImage.height))));
        for (const preskin::Light& l : scene.lights) {
            if (frame.lightCount.x == 8) break;
            frame.lights[frame.lightCount.x++] = preskin::toGpuLight(l, false);  // no shadow pass here
        }

        // The host's own Vulkan objects.
        Gpu gpu(deviceName);
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

        auto sceneTexture = [&](int index, VkFormat format) {
            const preskin::Image& img = scene.images[size_t(index)];
            return gpu.texture(format, img.width, img.height, img.rgba8.data(), img.rgba8.size(), true);
        };
        // Each skin table as its channel planes (one float channel, three times as wide).
        auto lutTexture = [&](const preskin::LutTable& table) {
            const std::vector<float> planes = table.planes();
            return gpu.texture(VK_FORMAT_R32_SFLOAT, uint32_t(table.width() * 3), uint32_t(table.height()),
                               planes.data(), planes.size() * sizeof(float), false, VK_IMAGE_VIEW_TYPE_2D_ARRAY);
        };
        const uint8_t white[4] = {255, 255, 255, 255};
        const VkImageView views[] = {
            sceneTexture(material.baseColor.image, VK_FORMAT_R8G8B8A8_SRGB),
            sceneTexture(material.normal.image, VK_FORMAT_R8G8B8A8_UNORM),
            skin.specularTexture.valid() ? sceneTexture(skin.specularTexture.image, VK_FORMAT_R8G8B8A8_UNORM)
                                         : gpu.texture(VK_FORMAT_R8G8B8A8_UNORM, 1, 1, white, 4, false),
            lutTexture(luts.diffuse()),
            lutTexture(luts.shTransfer()),
        };
        // Material textures: linear, mipmapped, repeat; LUTs: unfiltered (the shader gathers), clamped, no mips.
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

        // The host's descriptor layout: its frame block, five textures and the camera.
        VkDescriptorSetLayoutBinding bindings[7]{};
        for (uint32_t b = 0; b < 6; ++b)
            bindings[b] = {b, b == 0 ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER : VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
                           VK_SHADER_STAGE_FRAGMENT_BIT, nullptr};
        bindings[6] = {6, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, VK_SHADER_STAGE_VERTEX_BIT, nullptr};
        VkDescriptorSetLayoutCreateInfo li{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
        li.bindingCount = 7;
        li.pBindings = bindings;
        VkDescriptorSetLayout setLayout;
        check(vkCreateDescriptorSetLayout(dev, &li, nullptr, &setLayout), "vkCreateDescriptorSetLayout");
        const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 2},
                                              {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 5}};
        VkDescriptorPoolCreateInfo dpi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
        dpi.maxSets = 1;
        dpi.poolSizeCount = 2;
        dpi.pPoolSizes = sizes;
        VkDescriptorPool descriptorPool;
        check(vkCreateDescriptorPool(dev, &dpi, nullptr, &descriptorPool), "vkCreateDescriptorPool");
        VkDescriptorSetAllocateInfo dai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
        dai.descriptorPool = descriptorPool;
        dai.descriptorSetCount = 1;
        dai.pSetLayouts = &setLayout;
        VkDescriptorSet set;
        check(vkAllocateDescriptorSets(dev, &dai, &set), "vkAllocateDescriptorSets");
        const VkDescriptorBufferInfo bufferInfos[2] = {{frameBuffer, 0, sizeof(Frame)},
                                                       {cameraBuffer, 0, sizeof(Camera)}};
        VkDescriptorImageInfo imageInfos[5];
        VkWriteDescriptorSet writes[7];
        for (uint32_t b = 0; b < 7; ++b) {
            writes[b] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
            writes[b].dstSet = set;
            writes[b].dstBinding = b;
            writes[b].descriptorCount = 1;
            writes[b].descriptorType = bindings[b].descriptorType;
            if (b == 0 || b == 6) {
                writes[b].pBufferInfo = &bufferInfos[b == 0 ? 0 : 1];
                continue;
            }
            imageInfos[b - 1] = {b <= 3 ? materialSampler : lutSampler, views[b - 1],
                                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
            writes[b].pImageInfo = &imageInfos[b - 1];
        }
        vkUpdateDescriptorSets(dev, 7, writes, 0, nullptr);

        // The host's pipeline: its own shaders, reversed Z as preskin's views project.
        const VkPushConstantRange pushRange{VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(Draw)};
        VkPipelineLayoutCreateInfo pli{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
        pli.setLayoutCount = 1;
        pli.pSetLayouts = &setLayout;
        pli.pushConstantRangeCount = 1;
        pli.pPushConstantRanges = &pushRange;
        VkPipelineLayout pipelineLayout;
        check(vkCreatePipelineLayout(dev, &pli, nullptr, &pipelineLayout), "vkCreatePipelineLayout");
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
                                  uint32_t(b * sizeof(glm::vec3))});
        VkPipelineVertexInputStateCreateInfo vertexInput{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
        vertexInput.vertexBindingDescriptionCount = 2;
        vertexInput.pVertexBindingDescriptions = vertexBindings;
        vertexInput.vertexAttributeDescriptionCount = uint32_t(attributes.size());
        vertexInput.pVertexAttributeDescriptions = attributes.data();
        VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
        assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
        const VkViewport viewport{0.0f, 0.0f, float(width), float(height), 0.0f, 1.0f};
        const VkRect2D scissor{{0, 0}, {width, height}};
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
        const VkFormat colorFormat = VK_FORMAT_R8G8B8A8_SRGB, depthFormat = VK_FORMAT_D32_SFLOAT;
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

        // The offscreen target, one frame, read back.
        const Gpu::Image color =
            gpu.image(colorFormat, width, height, 1,
                      VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, VK_IMAGE_ASPECT_COLOR_BIT);
        const Gpu::Image depth = gpu.image(depthFormat, width, height, 1, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                                           VK_IMAGE_ASPECT_DEPTH_BIT);
        void* pixels = nullptr;
        const VkBuffer readback =
            gpu.buffer(VkDeviceSize(width) * height * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT, nullptr, &pixels);
        gpu.submit([&](VkCommandBuffer cmd) {
            Gpu::barrier(cmd, color.image, VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, VK_IMAGE_LAYOUT_UNDEFINED,
                         VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
            Gpu::barrier(cmd, depth.image, VK_IMAGE_ASPECT_DEPTH_BIT, 0, 1, VK_IMAGE_LAYOUT_UNDEFINED,
                         VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL);
            VkRenderingAttachmentInfo colorAttachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
            colorAttachment.imageView = color.view;
            colorAttachment.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
            colorAttachment.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
            colorAttachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
            colorAttachment.clearValue.color = {{0.045f, 0.045f, 0.05f, 1.0f}};  // preskin render's background
            VkRenderingAttachmentInfo depthAttachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
            depthAttachment.imageView = depth.view;
            depthAttachment.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
            depthAttachment.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
            depthAttachment.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
            depthAttachment.clearValue.depthStencil = {0.0f, 0};  // reversed Z: far
            VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
            ri.renderArea = scissor;
            ri.layerCount = 1;
            ri.colorAttachmentCount = 1;
            ri.pColorAttachments = &colorAttachment;
            ri.pDepthAttachment = &depthAttachment;
            vkCmdBeginRendering(cmd, &ri);
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelineLayout, 0, 1, &set, 0, nullptr);
            const VkDeviceSize offset = 0;
            const VkBuffer vertexBuffers[2] = {vertexBuffer, basisBuffer};
            const VkDeviceSize offsets[2] = {offset, offset};
            vkCmdBindVertexBuffers(cmd, 0, 2, vertexBuffers, offsets);
            vkCmdBindIndexBuffer(cmd, indexBuffer, 0, VK_INDEX_TYPE_UINT32);
            for (const DrawRange& d : draws) {
                vkCmdPushConstants(cmd, pipelineLayout, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(Draw), &d.push);
                vkCmdDrawIndexed(cmd, d.indexCount, 1, d.firstIndex, 0, 0);
            }
            vkCmdEndRendering(cmd);
            Gpu::barrier(cmd, color.image, VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                         VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
            VkBufferImageCopy region{};
            region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            region.imageExtent = {width, height, 1};
            vkCmdCopyImageToBuffer(cmd, color.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback, 1, &region);
        });
        preskin::RenderedImage image;
        image.width = width;
        image.height = height;
        image.rgba8.assign(static_cast<const uint8_t*>(pixels),
                           static_cast<const uint8_t*>(pixels) + size_t(width) * height * 4);
        preskin::writeImage(out, image);

        vkDestroyPipeline(dev, pipeline, nullptr);
        vkDestroyShaderModule(dev, vs, nullptr);
        vkDestroyShaderModule(dev, fs, nullptr);
        vkDestroyPipelineLayout(dev, pipelineLayout, nullptr);
        vkDestroyDescriptorPool(dev, descriptorPool, nullptr);
        vkDestroyDescriptorSetLayout(dev, setLayout, nullptr);
        vkDestroySampler(dev, materialSampler, nullptr);
        vkDestroySampler(dev, lutSampler, nullptr);
        std::printf("preskin-host: wrote %s (%ux%u)\n", out.c_str(), width, height);
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "preskin-host: error: %s\n", e.what());
        return 1;
    }
}
