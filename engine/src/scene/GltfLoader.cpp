// glTF 2.0 loading: file and container checks, tinygltf with confined file access and an
// image callback decoding through the registered codecs, then meshes, nodes, lights and cameras (see GltfLoader.h).
#include "scene/GltfLoader.h"
#include "anim/NodeHierarchy.h"
#include "image/ImageCodecs.h"
#include "image/ImageFormat.h"
#include "io/FolderConfinement.h"
#include "io/InputFile.h"
#include "io/JsonDocument.h"
#include "io/MessageText.h"
#include "scene/GltfAnimations.h"
#include "scene/GltfContext.h"
#include "scene/GltfFiles.h"
#include "scene/GltfMaterials.h"
#include "scene/GltfMeshes.h"
#include "scene/GltfNodes.h"
#include "scene/GltfPrepass.h"
#include "scene/GltfSkins.h"

#include <preskin/Error.h>
#include <preskin/LightRecord.h>
#include <preskin/Limits.h>

#include <fmt/core.h>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>
#include <optional>
#include <sstream>

namespace preskin::gltf {

namespace fs = std::filesystem;

namespace {

// The smallest perspective field of view a camera may have (radians): below it the projection
// is not representable in single precision.
constexpr float kMinCameraYfov = 1e-6f;

// ---- tinygltf callbacks -------------------------------------------------------------------

struct FsState {
    fs::path folder;
    bool allowOutsideLinks = false;
};

// The file tinygltf asks for, when it lies inside the scene's folder (links resolved under the
// same policy as the prepass) and is a regular file.
std::optional<fs::path> insideAndRegular(const std::string& path, const FsState& state) {
    const fs::path p = fs::path(path).lexically_normal();
    if (!p.is_absolute() || !isInsideFolder(p, state.folder)) return std::nullopt;
    fs::path resolved = p;
    if (!state.allowOutsideLinks) {
        const io::ConfinedPath confined = io::resolveInsideFolder(state.folder, p.lexically_relative(state.folder));
        if (!confined.inside) return std::nullopt;
        resolved = confined.path;
    }
    std::error_code ec;
    if (!fs::is_regular_file(resolved, ec)) return std::nullopt;
    return resolved;
}

bool fileExists(const std::string& path, void* user) {
    return insideAndRegular(path, *static_cast<const FsState*>(user)).has_value();
}

std::string expandFilePath(const std::string& path, void*) { return path; }  // no ~ or $VAR expansion

bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
    const auto& state = *static_cast<const FsState*>(user);
    const std::optional<fs::path> resolved = insideAndRegular(path, state);
    const std::string label = fs::path(path).lexically_relative(state.folder).string();
    if (!resolved) {
        if (err) *err += "'" + label + "' is not a file inside the scene's folder";
        return false;
    }
    try {
        *out = io::readInputFile(*resolved, label, limits::kMaxSceneFileBytes);
        return true;
    } catch (const std::exception& e) {
        if (err) *err += e.what();
        return false;
    }
}

bool writeWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err += "writing is disabled";
    return false;
}

struct ImageState {
    const SceneLoadOptions* options = nullptr;
    std::vector<std::string> unsupported;       // per image index: format description when unsupported
    std::vector<std::vector<uint16_t>> rgba16;  // per image index: texels of sources deeper than 8 bits
    std::optional<std::string> error;           // "images[i] (...): why"
    uint64_t totalPixels = 0;
};

// Decodes one image: the host's decoder first (SceneLoadOptions::decodeImage), then the
// registered codecs (<preskin/ImageCodec.h>). A format no codec reads is left undecoded with a
// warning, unless the image component would read it: then the scene needs that component.
bool loadImage(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
               const unsigned char* bytes, int size, void* user) {
    auto& state = *static_cast<ImageState*>(user);
    std::string where = "images[" + std::to_string(index) + "]";
    if (!image->uri.empty()) where += " ('" + image->uri + "')";
    try {
        if (index < 0 || size < 0) throw std::runtime_error("invalid image data");
        if (state.unsupported.size() <= static_cast<size_t>(index)) {
            state.unsupported.resize(static_cast<size_t>(index) + 1);
            state.rgba16.resize(static_cast<size_t>(index) + 1);
        }
        const std::span<const uint8_t> data(bytes, static_cast<size_t>(size));
        const DecodeLimits limits{limits::kMaxSceneImagePixels - state.totalPixels, limits::kMaxImageSide};
        std::optional<PixelImage> decoded;
        if (state.options->decodeImage) {
            decoded = state.options->decodeImage(data, image->uri, image->mimeType);
            if (decoded && (!decoded->consistent() || decoded->width == 0 || decoded->height == 0))
                throw std::runtime_error(
                    fmt::format("the host's decoder returned {}x{} texels of {} channels that do "
                                "not match its data",
                                decoded->width, decoded->height, decoded->channels));
            if (decoded) image::checkImageSize(decoded->width, decoded->height, {limits.maxPixels, limits.maxSide});
        }
        if (!decoded && !canDecodeImage(data)) {
            const image::ImageFormat format = image::sniffImageFormat(data);
            if (image::decodedByImageComponent(format))
                decodeImage(data, limits, where);  // throws, naming the component
            state.unsupported[static_cast<size_t>(index)] = describeImageFormat(data) + " data";
            image->width = image->height = 0;
            image->image.clear();
            return true;
        }
        if (!decoded) decoded = decodeImage(data, limits, where);
        state.totalPixels += uint64_t(decoded->width) * decoded->height;
        std::vector<uint8_t> rgba8;
        image::toRgba(*decoded, rgba8, state.rgba16[static_cast<size_t>(index)]);
        image->width = static_cast<int>(decoded->width);
        image->height = static_cast<int>(decoded->height);
        image->component = 4;
        image->bits = 8;
        image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
        image->image = std::move(rgba8);
        return true;
    } catch (const Error& e) {  // decodeImage's, which names the image
        state.error = e.what();
        if (err) *err += *state.error;
        return false;
    } catch (const std::exception& e) {
        state.error = where + ": " + e.what();
        if (err) *err += *state.error;
        return false;
    }
}

// ---- nodes --------------------------------------------------------------------------------

bool withinInputRange(const glm::mat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!io::acceptedNumber(m[c][r])) return false;
    return true;
}

glm::mat4 localMatrix(const LoadContext& ctx, const tinygltf::Node& node, const std::string& where) {
    if (auto m = fixedArray(ctx, node.matrix, 16, where + ".matrix")) {
        if (!node.translation.empty() || !node.rotation.empty() || !node.scale.empty()) {
            ctx.fail(where, "has both matrix and translation/rotation/scale");
        }
        glm::mat4 out(1.0f);
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) out[c][r] = static_cast<float>((*m)[static_cast<size_t>(c * 4 + r)]);
        return out;
    }
    glm::mat4 t(1.0f), r(1.0f), s(1.0f);
    if (auto v = fixedArray(ctx, node.translation, 3, where + ".translation")) {
        t[3] = glm::vec4(static_cast<float>((*v)[0]), static_cast<float>((*v)[1]), static_cast<float>((*v)[2]), 1.0f);
    }
    if (auto q = fixedArray(ctx, node.rotation, 4, where + ".rotation")) {
        glm::dquat quat((*q)[3], (*q)[0], (*q)[1], (*q)[2]);  // glTF stores x, y, z, w
        const double len = glm::length(quat);
        if (!(len > 1e-6)) ctx.fail(where + ".rotation", "zero-length quaternion");
        r = glm::mat4(glm::mat4_cast(quat / len));
    }
    if (auto v = fixedArray(ctx, node.scale, 3, where + ".scale")) {
        s = glm::mat4(1.0f);
        for (int k = 0; k < 3; ++k) s[k][k] = static_cast<float>((*v)[static_cast<size_t>(k)]);
    }
    return t * r * s;
}

// PRESKIN_lights_area on a point light (docs/gltf-extensions.md): the light's shape and size in
// metres (the node's scale does not apply, as to KHR_lights_punctual's range); a tube lies along
// the node's +X, a rectangle's width along +X and height along +Y, and a rectangle or disc emits
// along the node's -Z.
void applyAreaShape(const LoadContext& ctx, const tinygltf::Value& area, const std::string& where, Light& out) {
    if (!area.IsObject()) ctx.fail(where, "not an object");
    if (out.type == LightType::Spot) ctx.fail(where, "applies to lights of type point or directional only");
    const auto shape = stringField(ctx, area, "shape", where);
    if (!shape) ctx.fail(where + ".shape", "missing (sphere, tube, rectangle or disc)");
    if (out.type == LightType::Directional) {  // a sphere at infinity: the sun's disc
        if (*shape != "sphere") ctx.fail(where + ".shape", "a directional light's shape is sphere (its angularRadius)");
        const auto v = numberField(ctx, area, "angularRadius", where);
        if (!v) ctx.fail(where + ".angularRadius", "missing (a directional sphere light needs it)");
        if (!(*v > 0.0) || *v > std::numbers::pi / 4)
            ctx.fail(where + ".angularRadius", number(*v) + " is outside (0, pi/4] radians");
        out.angularRadius = static_cast<float>(*v);
        for (const char* key : {"radius", "length", "width", "height"})
            if (area.Has(key)) ctx.warn(where + "." + key, "not a size of a directional light; ignored");
        return;
    }
    if (area.Has("angularRadius")) ctx.warn(where + ".angularRadius", "a size of directional lights only; ignored");
    const auto size = [&](const char* key) {
        const auto v = numberField(ctx, area, key, where);
        if (!v) ctx.fail(where + "." + key, std::string("missing (a ") + *shape + " light needs it)");
        if (!(*v > 0.0) || *v > 1e6) ctx.fail(where + "." + key, number(*v) + " is outside (0, 1e6] metres");
        return static_cast<float>(std::max(*v, limits::kMinAreaLightSizeM));
    };
    if (*shape == "sphere") {
        out.type = LightType::Sphere;
        out.radius = size("radius");
    } else if (*shape == "tube") {
        out.type = LightType::Tube;
        out.radius = size("radius");
        out.length = size("length");
    } else if (*shape == "rectangle") {
        out.type = LightType::Rectangle;
        out.width = size("width");
        out.height = size("height");
    } else if (*shape == "disc") {
        out.type = LightType::Disc;
        out.radius = size("radius");
    } else {
        ctx.fail(where + ".shape", "'" + io::messageText(*shape) + "' is not sphere, tube, rectangle or disc");
    }
    const bool round = out.type != LightType::Rectangle;
    const std::pair<const char*, bool> fields[] = {
        {"radius", round}, {"length", out.type == LightType::Tube}, {"width", !round}, {"height", !round}};
    for (const auto& [key, used] : fields)
        if (!used && area.Has(key)) ctx.warn(where + "." + key, "not a size of a " + *shape + " light; ignored");
}

// A light the file defines but that cannot light anything (an unknown type, a node scaled to
// nothing): the validator allows it, so it is skipped with a warning.
std::optional<Light> convertLight(const LoadContext& ctx, int lightIndex, const glm::mat4& world,
                                  const std::string& nodeName, const std::string& nodeWhere, bool& explicitShadowFlag) {
    const tinygltf::Model& model = *ctx.model;
    if (lightIndex < 0 || static_cast<size_t>(lightIndex) >= model.lights.size()) {
        ctx.fail(nodeWhere + ".extensions.KHR_lights_punctual.light",
                 std::to_string(lightIndex) + " is out of range: the file has " + std::to_string(model.lights.size()) +
                     " lights");
    }
    const tinygltf::Light& in = model.lights[static_cast<size_t>(lightIndex)];
    const std::string where = "extensions.KHR_lights_punctual.lights[" + std::to_string(lightIndex) + "]";
    Light out;
    out.name = in.name.empty() ? nodeName : in.name;
    if (in.type == "directional")
        out.type = LightType::Directional;
    else if (in.type == "point")
        out.type = LightType::Point;
    else if (in.type == "spot")
        out.type = LightType::Spot;
    else {
        ctx.warn(where + ".type",
                 "'" + in.type + "' is not a KHR_lights_punctual type (directional, point or spot); light skipped");
        return std::nullopt;
    }
    if (auto c = fixedArray(ctx, in.color, 3, where + ".color")) {
        out.color = glm::vec3(static_cast<float>((*c)[0]), static_cast<float>((*c)[1]), static_cast<float>((*c)[2]));
        if (glm::any(glm::lessThan(out.color, glm::vec3(0.0f)))) ctx.fail(where + ".color", "negative component");
    }
    if (checkedNumber(ctx, in.intensity, where + ".intensity") < 0.0) ctx.fail(where + ".intensity", "must be >= 0");
    out.intensity = static_cast<float>(in.intensity);
    if (checkedNumber(ctx, in.range, where + ".range") < 0.0) ctx.fail(where + ".range", "must be > 0");
    out.range = static_cast<float>(in.range);
    if (out.type == LightType::Spot) {
        const double inner = in.spot.innerConeAngle, outer = in.spot.outerConeAngle;
        if (!(inner >= 0.0 && inner < outer && outer <= std::numbers::pi / 2 + 1e-6)) {
            ctx.fail(where + ".spot",
                     "cone angles inner " + number(inner) + ", outer " + number(outer) +
                         " (need 0 <= inner < outer <= pi/2)");
        }
        out.innerConeAngle = static_cast<float>(inner);
        out.outerConeAngle = static_cast<float>(outer);
    }
    out.positionWs = glm::vec3(world[3]);
    const glm::vec3 direction = glm::mat3(world) * glm::vec3(0.0f, 0.0f, -1.0f);
    if (!(glm::length(direction) > 1e-12f) && out.type != LightType::Point) {
        ctx.warn(nodeWhere, "the node's transform collapses the light's direction (scale 0); light skipped");
        return std::nullopt;
    }
    out.directionWs = glm::length(direction) > 1e-12f ? glm::normalize(direction) : glm::vec3(0.0f, 0.0f, -1.0f);
    if (auto it = in.extensions.find("PRESKIN_lights_area"); it != in.extensions.end()) {
        applyAreaShape(ctx, it->second, where + ".extensions.PRESKIN_lights_area", out);
        const glm::vec3 axis = glm::mat3(world) * glm::vec3(1.0f, 0.0f, 0.0f);
        if (isAreaLight(out.type) && !(glm::length(axis) > 1e-12f)) {
            ctx.warn(nodeWhere, "the node's transform collapses the area light's axis (scale 0); light skipped");
            return std::nullopt;
        }
        if (isAreaLight(out.type)) out.axisWs = glm::normalize(axis);
    }
    explicitShadowFlag = false;
    if (auto casts = boolField(ctx, in.extras, "castsShadow", where + ".extras")) {
        out.castsShadow = *casts;
        explicitShadowFlag = true;
    }
    return out;
}

// A camera the validator allows but that cannot show anything (a node scaled to nothing, a field
// of view too small for single precision) is skipped with a warning.
std::optional<Camera> convertCamera(const LoadContext& ctx, int cameraIndex, const glm::mat4& world,
                                    const std::string& nodeName, const std::string& nodeWhere) {
    const tinygltf::Model& model = *ctx.model;
    if (cameraIndex < 0 || static_cast<size_t>(cameraIndex) >= model.cameras.size()) {
        ctx.fail(nodeWhere + ".camera",
                 std::to_string(cameraIndex) + " is out of range: the file has " +
                     std::to_string(model.cameras.size()) + " cameras");
    }
    const tinygltf::Camera& in = model.cameras[static_cast<size_t>(cameraIndex)];
    const std::string where = indexed("cameras", static_cast<size_t>(cameraIndex));
    Camera out;
    out.name = in.name.empty() ? nodeName : in.name;
    out.source = ctx.file + ": " + where;
    if (in.type == "perspective") {
        const auto& p = in.perspective;
        for (const auto& [value, name] : {std::pair{p.yfov, "yfov"}, std::pair{p.znear, "znear"},
                                          std::pair{p.zfar, "zfar"}, std::pair{p.aspectRatio, "aspectRatio"}}) {
            checkedNumber(ctx, value, where + ".perspective." + name);
        }
        if (!(p.yfov > 0.0 && p.yfov < std::numbers::pi)) ctx.fail(where + ".perspective.yfov", "must be in (0, pi)");
        if (!(p.znear > 0.0) || !std::isfinite(p.znear)) ctx.fail(where + ".perspective.znear", "must be > 0");
        if (!std::isfinite(p.zfar) || (p.zfar != 0.0 && !(p.zfar > p.znear))) {
            ctx.fail(where + ".perspective.zfar", "must be greater than znear (or absent for infinite)");
        }
        if (!std::isfinite(p.aspectRatio) || p.aspectRatio < 0.0)
            ctx.fail(where + ".perspective.aspectRatio", "must be > 0");
        out.yfov = static_cast<float>(p.yfov);
        if (!(out.yfov >= kMinCameraYfov)) {
            ctx.warn(where + ".perspective.yfov",
                     number(p.yfov) + " rad is too small a field of view to render; camera skipped");
            return std::nullopt;
        }
        out.znear = static_cast<float>(p.znear);
        out.zfar = static_cast<float>(p.zfar);
        out.aspectRatio = static_cast<float>(p.aspectRatio);
    } else if (in.type == "orthographic") {
        const auto& o = in.orthographic;
        for (const auto& [value, name] : {std::pair{o.xmag, "xmag"}, std::pair{o.ymag, "ymag"},
                                          std::pair{o.znear, "znear"}, std::pair{o.zfar, "zfar"}}) {
            checkedNumber(ctx, value, where + ".orthographic." + name);
        }
        if (!std::isfinite(o.xmag) || o.xmag == 0.0)
            ctx.fail(where + ".orthographic.xmag", "must be finite and non-zero");
        if (!std::isfinite(o.ymag) || o.ymag == 0.0)
            ctx.fail(where + ".orthographic.ymag", "must be finite and non-zero");
        if (!(o.znear >= 0.0) || !std::isfinite(o.znear)) ctx.fail(where + ".orthographic.znear", "must be >= 0");
        if (!(o.zfar > o.znear) || !std::isfinite(o.zfar))
            ctx.fail(where + ".orthographic.zfar", "must be greater than znear");
        out.orthographic = true;
        out.xmag = static_cast<float>(o.xmag);
        out.ymag = static_cast<float>(o.ymag);
        out.znear = static_cast<float>(o.znear);
        out.zfar = static_cast<float>(o.zfar);
    } else {
        ctx.fail(where + ".type", "'" + in.type + "' (expected perspective or orthographic)");
    }
    // Rigid part of the node transform: Gram-Schmidt on the view axes, scale dropped.
    const glm::vec3 z = glm::vec3(world[2]), x0 = glm::vec3(world[0]);
    const glm::vec3 zn = glm::length(z) > 1e-12f ? glm::normalize(z) : glm::vec3(0.0f);
    const glm::vec3 xo = x0 - zn * glm::dot(zn, x0);
    if (!(glm::length(z) > 1e-12f) || !(glm::length(xo) > 1e-12f)) {
        ctx.warn(nodeWhere, "the node's transform collapses the camera's axes (scale 0); camera skipped");
        return std::nullopt;
    }
    const glm::vec3 xn = glm::normalize(xo);
    const glm::vec3 yn = glm::cross(zn, xn);
    out.worldFromView = glm::mat4(glm::vec4(xn, 0.0f), glm::vec4(yn, 0.0f), glm::vec4(zn, 0.0f), world[3]);
    return out;
}

void convertNodes(const LoadContext& ctx) {
    const tinygltf::Model& model = *ctx.model;
    const size_t nodeCount = model.nodes.size();
    const std::vector<Node>& nodes = ctx.scene->nodes;  // a forest (convertNodeHierarchy)

    // The roots drawn: the default scene's (scene 0 without one), or every root without scenes.
    std::vector<int> roots;
    if (model.defaultScene >= 0 || !model.scenes.empty()) {
        const int sceneIndex = model.defaultScene >= 0 ? model.defaultScene : 0;
        if (static_cast<size_t>(sceneIndex) >= model.scenes.size()) {
            ctx.fail("scene",
                     std::to_string(sceneIndex) + " is out of range: the file has " +
                         std::to_string(model.scenes.size()) + " scenes");
        }
        const auto& sceneNodes = model.scenes[static_cast<size_t>(sceneIndex)].nodes;
        std::vector<uint8_t> listed(nodeCount, 0);
        for (size_t k = 0; k < sceneNodes.size(); ++k) {
            const std::string at = indexed("scenes", static_cast<size_t>(sceneIndex)) + indexed(".nodes", k);
            if (sceneNodes[k] < 0 || static_cast<size_t>(sceneNodes[k]) >= nodeCount) {
                ctx.fail(at,
                         std::to_string(sceneNodes[k]) + " is out of range: the file has " + std::to_string(nodeCount) +
                             " nodes");
            }
            const auto n = static_cast<size_t>(sceneNodes[k]);
            if (const int p = nodes[n].parent; p >= 0) {
                ctx.fail(at,
                         "nodes[" + std::to_string(n) + "] is not a root node: it is a child of nodes[" +
                             std::to_string(p) + "]");
            }
            if (listed[n]) ctx.fail(indexed("nodes", n), "reached twice: the scene lists it twice");
            listed[n] = 1;
            roots.push_back(sceneNodes[k]);
        }
    } else {
        for (size_t i = 0; i < nodeCount; ++i)
            if (nodes[i].parent < 0) roots.push_back(static_cast<int>(i));
    }

    // The rest pose's world transforms, by the walk posing uses.
    std::vector<glm::mat4> local(nodeCount);
    for (size_t i = 0; i < nodeCount; ++i) local[i] = localMatrix(ctx, model.nodes[i], indexed("nodes", i));
    const std::vector<glm::mat4> worldFromNode = anim::worldTransforms(nodes, local);

    Scene& scene = *ctx.scene;
    std::vector<uint64_t> meshTriangles(scene.meshes.size(), 0);
    for (size_t m = 0; m < scene.meshes.size(); ++m)
        for (const Primitive& p : scene.meshes[m].primitives) meshTriangles[m] += p.indices.size() / 3;
    uint64_t draws = 0;
    uint64_t drawnTriangles = 0;
    std::vector<uint8_t> explicitShadow;
    // Depth first from the roots, each node before its children, in the file's order.
    std::vector<int> stack(roots.rbegin(), roots.rend());
    while (!stack.empty()) {
        const auto index = static_cast<size_t>(stack.back());
        stack.pop_back();
        const std::string where = indexed("nodes", index);
        const tinygltf::Node& node = model.nodes[index];
        const std::string nodeName = node.name.empty() ? where : node.name;
        const glm::mat4& world = worldFromNode[index];
        if (!withinInputRange(world)) {
            ctx.fail(where,
                     "its world transform (the product of its parents' transforms) has an element that is not "
                     "finite or exceeds the limit of " +
                         number(limits::kMaxInputMagnitude) + " in magnitude");
        }

        if (node.mesh >= 0) {  // in range (convertNodeHierarchy)
            const auto mesh = static_cast<size_t>(node.mesh);
            draws += scene.meshes[mesh].primitives.size();
            drawnTriangles += meshTriangles[mesh];
            if (draws > limits::kMaxSceneDraws) {
                ctx.fail(where + ".mesh",
                         "the scene draws more than the limit of " + std::to_string(limits::kMaxSceneDraws) +
                             " primitives (instances included)");
            }
            if (drawnTriangles > limits::kMaxDrawnTriangles) {
                ctx.fail(where + ".mesh",
                         "the scene draws more than the limit of " + std::to_string(limits::kMaxDrawnTriangles) +
                             " triangles (instances included)");
            }
            scene.instances.push_back(MeshInstance{node.mesh, world, nodeName});
            scene.instances.back().node = static_cast<int>(index);
            scene.instances.back().skin = node.skin;
        }
        const bool cameraSkipped = std::find(ctx.skippedCameras.begin(), ctx.skippedCameras.end(),
                                             static_cast<size_t>(std::max(node.camera, 0))) != ctx.skippedCameras.end();
        if ((node.camera >= 0 && !cameraSkipped) || node.camera < -1) {
            if (auto camera = convertCamera(ctx, node.camera, world, nodeName, where))
                scene.cameras.push_back(std::move(*camera));
        }
        if (auto it = node.extensions.find("KHR_lights_punctual"); it != node.extensions.end()) {
            const std::string at = where + ".extensions.KHR_lights_punctual";
            const auto light = integerField(ctx, it->second, "light", at);
            if (!light) ctx.fail(at + ".light", "missing");
            bool isExplicit = false;
            if (auto converted = convertLight(ctx, *light, world, nodeName, where, isExplicit)) {
                scene.lights.push_back(std::move(*converted));
                explicitShadow.push_back(isExplicit ? 1 : 0);
            }
        }
        stack.insert(stack.end(), node.children.rbegin(), node.children.rend());
    }

    // Without any explicit castsShadow, the first directional light casts shadows.
    if (std::find(explicitShadow.begin(), explicitShadow.end(), 1) == explicitShadow.end()) {
        for (Light& light : scene.lights) {
            if (light.type == LightType::Directional) {
                light.castsShadow = true;
                break;
            }
        }
    }
}

std::string lowercase(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

std::string extensionOf(const fs::path& path) {
    const std::string extension = lowercase(path.extension().string());
    std::error_code ec;
    if (fs::is_directory(path, ec)) fail(path.string(), "file", "is a folder, not a glTF scene (.gltf or .glb)");
    if (extension != ".gltf" && extension != ".glb") {
        fail(path.string(), "", "unsupported file type '" + io::messageText(extension) + "' (expected .gltf or .glb)");
    }
    return extension;
}

// A .glb with `json` as its JSON chunk and the BIN chunk of `glb` (glTF 2.0, "Binary glTF Layout").
std::vector<uint8_t> rebuildGlb(std::string json, const GlbChunks& glb) {
    while (json.size() % 4 != 0) json += ' ';
    const size_t binChunk = glb.hasBin ? 8 + glb.bin.size() : 0;
    const size_t total = 12 + 8 + json.size() + binChunk;
    std::string out;
    out.reserve(total);
    auto put = [&](const void* data, size_t size) { out.append(static_cast<const char*>(data), size); };
    auto u32 = [&](uint32_t v) {
        for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xffu));
    };
    u32(0x46546C67u);  // "glTF"
    u32(2);
    u32(static_cast<uint32_t>(total));
    u32(static_cast<uint32_t>(json.size()));
    u32(0x4E4F534Au);  // "JSON"
    put(json.data(), json.size());
    if (glb.hasBin) {
        u32(static_cast<uint32_t>(glb.bin.size()));
        u32(0x004E4942u);  // "BIN\0"
        if (!glb.bin.empty()) put(glb.bin.data(), glb.bin.size());
    }
    return std::vector<uint8_t>(out.begin(), out.end());
}

}  // namespace

Scene loadScene(const fs::path& path, const SceneLoadOptions& options) {
    const std::string extension = extensionOf(path);
    return loadSceneBytes(
        io::readInputFile(path, path.string(),
                          extension == ".glb" ? limits::kMaxSceneFileBytes : limits::kMaxGltfJsonBytes),
        path, options);
}

Scene loadSceneBytes(std::vector<uint8_t> bytes, const fs::path& path, const SceneLoadOptions& options) {
    const std::string file = path.string();
    const std::string extension = extensionOf(path);
    std::error_code ec;
    const fs::path absolute = fs::absolute(path, ec);
    if (ec) fail(file, "", "cannot resolve the path: " + ec.message());
    const fs::path folder = absolute.lexically_normal().parent_path();

    const bool isGlb = extension == ".glb";
    std::string bomWarning;
    GlbChunks glb;
    std::span<const uint8_t> jsonText(bytes);
    if (isGlb) {
        glb = splitGlb(bytes, file);
        jsonText = glb.json;
    } else {
        if (bytes.empty()) fail(file, "", "empty file");
        if (bytes.size() >= 4 && std::equal(bytes.begin(), bytes.begin() + 4, "glTF")) {
            fail(file, "", "binary glTF content in a .gltf file (name it .glb)");
        }
    }
    if (jsonText.size() > limits::kMaxGltfJsonBytes) {
        fail(file, "GLB chunk 0 length",
             std::to_string(jsonText.size()) + " bytes of JSON exceeds the limit of " +
                 std::to_string(limits::kMaxGltfJsonBytes));
    }
    // The bounded parse comes first: tinygltf parses the same text again, and walks it
    // recursively, only once depth and size are known to be within the limits.
    if (jsonText.size() >= 3 && jsonText[0] == 0xEF && jsonText[1] == 0xBB && jsonText[2] == 0xBF)
        bomWarning = file + ": JSON: starts with a UTF-8 byte-order mark, which glTF does not allow; read anyway";
    nlohmann::json doc = io::parseJson(jsonText, file);
    const PrepassResult prepass =
        checkDocument(doc, file, folder, isGlb ? &glb : nullptr, options.allowLinksOutsideFolder);
    if (!prepass.skippedCameras.empty() || !prepass.skippedPrimitives.empty()) {
        // tinygltf refuses a camera type it does not know: stand a valid one in its place (the
        // loader leaves it out) and hand tinygltf the edited document.
        for (size_t i : prepass.skippedCameras)
            doc["cameras"][i] = {{"type", "perspective"}, {"perspective", {{"yfov", 1.0}, {"znear", 1.0}}}};
        for (const auto& [m, p] : prepass.skippedPrimitives) doc["meshes"][m]["primitives"][p].erase("indices");
        bytes = isGlb ? rebuildGlb(doc.dump(), glb) : [&] {
            const std::string text = doc.dump();
            return std::vector<uint8_t>(text.begin(), text.end());
        }();
    }

    tinygltf::TinyGLTF loader;
    FsState fsState{folder, options.allowLinksOutsideFolder};
    loader.SetFsCallbacks(
        tinygltf::FsCallbacks{&fileExists, &expandFilePath, &readWholeFile, &writeWholeFile, &fsState});
    ImageState imageState;
    imageState.options = &options;
    loader.SetImageLoader(&loadImage, &imageState);
    tinygltf::Model model;
    std::string err, warn;
    const bool ok = isGlb ? loader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(),
                                                        static_cast<unsigned>(bytes.size()), folder.string())
                          : loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(bytes.data()),
                                                       static_cast<unsigned>(bytes.size()), folder.string());
    if (imageState.error) fail(file, "", *imageState.error);
    if (!ok) fail(file, "", "glTF parse error: " + (err.empty() ? std::string("unknown") : err));
    bytes = {};

    Scene scene;
    scene.sourcePath = path;
    if (!bomWarning.empty()) scene.warnings.push_back(bomWarning);
    scene.warnings.insert(scene.warnings.end(), prepass.warnings.begin(), prepass.warnings.end());
    {
        std::istringstream lines(warn);
        for (std::string line; std::getline(lines, line);) {
            if (!line.empty()) scene.warnings.push_back(file + ": " + line);
        }
    }
    scene.environmentPath = prepass.environmentPath;
    scene.environmentData = prepass.environmentData;
    if (scene.environmentPath || !scene.environmentData.empty()) {
        // A format only the image component reads fails here, naming the scene, not at its load.
        const std::vector<uint8_t> head = scene.environmentPath
            ? io::readInputFileStart(*scene.environmentPath, file, limits::kMaxImageFileBytes, 64)
            : std::vector<uint8_t>(scene.environmentData.begin(),
                                   scene.environmentData.begin() + std::min<size_t>(64, scene.environmentData.size()));
        const image::ImageFormat format = image::sniffImageFormat(head);
        const std::string shown = scene.environmentPath
            ? "'" + io::messageText(scene.environmentPath->filename().string()) + "'"
            : "its data URI";
        if (image::decodedByImageComponent(format) && !canDecodeImage(head))
            fail(file, "extensions.PRESKIN_environment.uri",
                 fmt::format("{} is {}: no decoder for it in this program (the image component preskin::imageio "
                             "reads it: link preskin::imageio and call preskin::imageio::registerCodecs())",
                             shown, image::formatName(format)));
    }
    scene.environmentIntensity = prepass.environmentIntensity;
    scene.environmentRotation = prepass.environmentRotation;
    scene.profiles = prepass.profiles;

    LoadContext ctx;
    ctx.file = file;
    ctx.folder = folder;
    ctx.allowOutsideLinks = options.allowLinksOutsideFolder;
    ctx.model = &model;
    ctx.scene = &scene;
    ctx.skippedCameras = prepass.skippedCameras;
    ctx.skippedPrimitives = prepass.skippedPrimitives;
    ctx.unsupportedImageFormat = std::move(imageState.unsupported);
    ctx.unsupportedImageFormat.resize(model.images.size());

    for (size_t i = 0; i < model.images.size(); ++i) {
        tinygltf::Image& in = model.images[i];
        const std::string where = indexed("images", i);
        Image out;
        out.name = !in.uri.empty() ? in.uri : !in.name.empty() ? in.name : where;
        if (!ctx.unsupportedImageFormat[i].empty()) {
            ctx.warn(
                where,
                ctx.unsupportedImageFormat[i] +
                    " is not decoded (no decoder for it in this program: PNG and JPEG are built in; a host plugs others in, <preskin/ImageCodec.h>)");
        } else if (in.image.empty() || in.width <= 0 || in.height <= 0 || in.component != 4) {
            ctx.fail(where, "no pixel data could be read");
        } else {
            out.width = static_cast<uint32_t>(in.width);
            out.height = static_cast<uint32_t>(in.height);
            out.rgba8 = std::move(in.image);
            if (i < imageState.rgba16.size() && imageState.rgba16[i].size() == out.rgba8.size())
                out.rgba16 = std::move(imageState.rgba16[i]);
        }
        scene.images.push_back(std::move(out));
    }
    convertSamplers(ctx);
    convertMaterials(ctx);
    convertMeshes(ctx);
    convertNodeHierarchy(ctx);
    convertNodes(ctx);
    convertSkins(ctx);
    convertAnimations(ctx);
    if (scene.instances.empty())
        ctx.warn("scenes", "nothing to draw: no node of the scene holds a mesh (the image shows the background only)");
    return scene;
}

}  // namespace preskin::gltf
