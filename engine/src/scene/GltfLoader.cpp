// glTF 2.0 loading: file and container checks, tinygltf with confined file access and an
// OpenImageIO image callback, then meshes, nodes, lights and cameras (see GltfLoader.h).
#include "scene/GltfLoader.h"
#include "io/FolderConfinement.h"
#include "io/InputFile.h"
#include "io/JsonDocument.h"
#include "scene/GltfAccessors.h"
#include "scene/GltfAnimations.h"
#include "scene/GltfContext.h"
#include "scene/GltfFiles.h"
#include "scene/GltfMaterials.h"
#include "scene/GltfMorphTargets.h"
#include "scene/GltfNodes.h"
#include "scene/GltfPrepass.h"
#include "scene/GltfSkins.h"
#include "scene/ImageDecoder.h"
#include "scene/TangentFrames.h"

#include <preskin/Curvature.h>
#include <preskin/Error.h>
#include <preskin/Limits.h>

#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>
#include <tuple>

namespace preskin::gltf {

namespace fs = std::filesystem;
using scene::generateTangents;
using scene::makeFlatNormals;
using scene::orthonormalizeTangents;

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
    std::vector<std::string> unsupported;  // per image index: format description when unsupported
    std::optional<std::string> error;      // "images[i] (...): why"
    uint64_t totalPixels = 0;
};

bool loadImage(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
               const unsigned char* bytes, int size, void* user) {
    auto& state = *static_cast<ImageState*>(user);
    std::string where = "images[" + std::to_string(index) + "]";
    if (!image->uri.empty()) where += " ('" + image->uri + "')";
    try {
        if (index < 0 || size < 0) throw std::runtime_error("invalid image data");
        if (state.unsupported.size() <= static_cast<size_t>(index)) state.unsupported.resize(static_cast<size_t>(index) + 1);
        const std::span<const uint8_t> data(bytes, static_cast<size_t>(size));
        const ImageFormat format = sniffImageFormat(data);
        if (format == ImageFormat::Unsupported) {
            state.unsupported[static_cast<size_t>(index)] = describeImageFormat(data) + " data";
            image->width = image->height = 0;
            image->image.clear();
            return true;
        }
        DecodedImage decoded = decodeImageRgba8(data, format, limits::kMaxSceneImagePixels - state.totalPixels);
        state.totalPixels += uint64_t(decoded.width) * decoded.height;
        image->width = static_cast<int>(decoded.width);
        image->height = static_cast<int>(decoded.height);
        image->component = 4;
        image->bits = 8;
        image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
        image->image = std::move(decoded.rgba8);
        return true;
    } catch (const std::exception& e) {
        state.error = where + ": " + e.what();
        if (err) *err += *state.error;
        return false;
    }
}

// ---- meshes -------------------------------------------------------------------------------

std::vector<uint32_t> toTriangleList(const LoadContext& ctx, const std::vector<uint32_t>& indices, int mode,
                                     bool indexed, const std::string& where) {
    std::vector<uint32_t> list;
    const size_t n = indices.size();
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        if (n % 3 != 0) {  // the glTF validator's warning; the trailing indices make no triangle
            ctx.warn(where, std::string(indexed ? "index" : "vertex") + " count " + std::to_string(n) +
                                " is not a multiple of 3 for a triangle list; the last " + std::to_string(n % 3) +
                                " ignored");
            return std::vector<uint32_t>(indices.begin(), indices.end() - std::ptrdiff_t(n % 3));
        }
        return indices;
    }
    if (n < 3) return list;
    list.reserve((n - 2) * 3);
    for (size_t i = 0; i + 2 < n; ++i) {
        if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {  // p_i = {v_i, v_{i+(1+i%2)}, v_{i+(2-i%2)}}
            list.insert(list.end(), {indices[i], indices[i + 1 + i % 2], indices[i + 2 - i % 2]});
        } else {  // fan: p_i = {v_{i+1}, v_{i+2}, v_0}
            list.insert(list.end(), {indices[i + 1], indices[i + 2], indices[0]});
        }
    }
    return list;
}

size_t repairNormals(Primitive& primitive) {
    std::vector<size_t> broken;
    for (size_t i = 0; i < primitive.vertices.size(); ++i) {
        glm::vec3& n = primitive.vertices[i].normalOs;
        const float len = glm::length(n);
        if (len > 1e-12f) n /= len;
        else broken.push_back(i);
    }
    if (broken.empty()) return 0;
    std::vector<glm::vec3> faceSum(primitive.vertices.size(), glm::vec3(0.0f));
    for (size_t t = 0; t + 2 < primitive.indices.size(); t += 3) {
        const uint32_t a = primitive.indices[t], b = primitive.indices[t + 1], c = primitive.indices[t + 2];
        const glm::vec3 areaNormal = glm::cross(primitive.vertices[b].positionOs - primitive.vertices[a].positionOs,
                                                primitive.vertices[c].positionOs - primitive.vertices[a].positionOs);
        faceSum[a] += areaNormal;
        faceSum[b] += areaNormal;
        faceSum[c] += areaNormal;
    }
    for (size_t i : broken) {
        const float len = glm::length(faceSum[i]);
        primitive.vertices[i].normalOs = len > 0.0f ? faceSum[i] / len : glm::vec3(0.0f, 0.0f, 1.0f);
    }
    return broken.size();
}

void convertMeshes(const LoadContext& ctx) {
    const tinygltf::Model& model = *ctx.model;
    uint64_t totalVertices = 0;
    uint64_t totalIndices = 0;
    for (size_t m = 0; m < model.meshes.size(); ++m) {
        const tinygltf::Mesh& in = model.meshes[m];
        Mesh mesh;
        mesh.name = in.name.empty() ? indexed("meshes", m) : in.name;
        // A primitive that repeats an earlier one of the mesh (same accessors, material and mode)
        // draws the same triangles again: drawn once (a file of 100,000 copies would otherwise
        // multiply the frame's work).
        using PrimitiveKey = std::tuple<std::map<std::string, int>, int, int, int, std::vector<std::map<std::string, int>>>;
        std::set<PrimitiveKey> seen;
        size_t repeated = 0;
        for (size_t p = 0; p < in.primitives.size(); ++p) {
            const tinygltf::Primitive& prim = in.primitives[p];
            const std::string where = indexed("meshes", m) + indexed(".primitives", p);
            if (!seen.emplace(prim.attributes, prim.indices, prim.material, prim.mode, prim.targets).second) {
                ++repeated;
                continue;
            }
            if (std::find(ctx.skippedPrimitives.begin(), ctx.skippedPrimitives.end(), std::pair{m, p}) !=
                ctx.skippedPrimitives.end())
                continue;  // warned by the prepass
            const int mode = prim.mode == -1 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
            if (mode >= TINYGLTF_MODE_POINTS && mode <= TINYGLTF_MODE_LINE_STRIP) {
                ctx.warn(where + ".mode", std::to_string(mode) + " (points or lines) is not drawn; primitive skipped");
                continue;
            }
            if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
                mode != TINYGLTF_MODE_TRIANGLE_FAN) {
                ctx.fail(where + ".mode", std::to_string(mode) + " is not a glTF primitive mode");
            }
            if (prim.material < -1 || prim.material >= static_cast<int>(model.materials.size())) {
                ctx.fail(where + ".material", std::to_string(prim.material) + " is out of range: the file has " +
                                                  std::to_string(model.materials.size()) + " materials");
            }
            auto attribute = [&](const char* name) {
                auto it = prim.attributes.find(name);
                return it == prim.attributes.end() ? -1 : it->second;
            };
            const int positionIndex = attribute("POSITION");
            if (positionIndex < 0) ctx.fail(where + ".attributes", "no POSITION");
            // Counts first: every total is checked before the memory it needs is allocated.
            const size_t vertexCount = accessorCount(ctx, positionIndex, where + ".attributes.POSITION");
            totalVertices += vertexCount;
            if (totalVertices > limits::kMaxSceneVertices) {
                ctx.fail(where + ".attributes.POSITION",
                         indexed("accessors", static_cast<size_t>(positionIndex)) + " brings the scene to " +
                             std::to_string(totalVertices) + " vertices, over the limit of " +
                             std::to_string(limits::kMaxSceneVertices));
            }
            for (const char* name : {"NORMAL", "TEXCOORD_0", "TANGENT"}) {
                const int index = attribute(name);
                if (index < 0) continue;
                const std::string at = where + ".attributes." + name;
                if (const size_t count = accessorCount(ctx, index, at); count != vertexCount) {
                    ctx.fail(at, "accessors[" + std::to_string(index) + "] has " + std::to_string(count) +
                                     " elements, POSITION has " + std::to_string(vertexCount));
                }
            }
            const size_t indexCount = prim.indices >= 0 ? accessorCount(ctx, prim.indices, where + ".indices", AccessorUse::Indices) : vertexCount;
            const size_t listCount = mode == TINYGLTF_MODE_TRIANGLES ? indexCount : indexCount < 3 ? 0 : (indexCount - 2) * 3;
            if (totalIndices + listCount > limits::kMaxSceneIndices) {
                ctx.fail(prim.indices >= 0 ? where + ".indices" : where,
                         std::to_string(listCount) + " triangle-list indices bring the scene over the limit of " +
                             std::to_string(limits::kMaxSceneIndices));
            }
            const FloatAccessor positions = readFloatAccessor(ctx, positionIndex, {3}, where + ".attributes.POSITION");

            Primitive out;
            out.material = prim.material;
            out.vertices.resize(vertexCount);
            for (size_t i = 0; i < vertexCount; ++i) {
                out.vertices[i].positionOs = glm::make_vec3(&positions.values[i * 3]);
            }
            auto readMatching = [&](const char* name, int components) -> std::optional<FloatAccessor> {
                const int index = attribute(name);
                if (index < 0) return std::nullopt;
                const std::string at = where + ".attributes." + name;
                FloatAccessor a = readFloatAccessor(ctx, index, {components}, at);
                if (a.count != vertexCount) {
                    ctx.fail(at, "accessors[" + std::to_string(index) + "] has " + std::to_string(a.count) +
                                     " elements, POSITION has " + std::to_string(vertexCount));
                }
                return a;
            };
            const auto normals = readMatching("NORMAL", 3);
            const auto uvs = readMatching("TEXCOORD_0", 2);
            const auto tangents = readMatching("TANGENT", 4);
            for (size_t i = 0; i < vertexCount; ++i) {
                Vertex& v = out.vertices[i];
                if (normals) v.normalOs = glm::make_vec3(&normals->values[i * 3]);
                if (uvs) v.uv0 = glm::make_vec2(&uvs->values[i * 2]);
                if (tangents) v.tangentOs = glm::make_vec4(&tangents->values[i * 4]);
            }
            readMorphTargets(ctx, prim, where, vertexCount, out);
            readJointInfluences(ctx, m, prim, where, vertexCount, out);

            std::vector<uint32_t> indices;
            if (prim.indices >= 0) {

                indices = readIndexAccessor(ctx, prim.indices, vertexCount, where + ".indices");
            } else {
                indices.resize(vertexCount);
                for (size_t i = 0; i < vertexCount; ++i) indices[i] = static_cast<uint32_t>(i);
            }
            out.indices = toTriangleList(ctx, indices, mode, prim.indices >= 0, prim.indices >= 0 ? where + ".indices" : where);
            totalIndices += out.indices.size();
            if (out.indices.empty()) {
                ctx.warn(where, "no triangles; primitive skipped");
                continue;
            }

            if (!normals) {
                makeFlatNormals(out);
            } else if (const size_t fixed = repairNormals(out); fixed > 0) {
                ctx.warn(where + ".attributes.NORMAL", std::to_string(fixed) +
                                                           " zero-length normals replaced by the mean face normal");
            }
            if (tangents) {
                if (const size_t fixed = orthonormalizeTangents(out); fixed > 0) {
                    ctx.warn(where + ".attributes.TANGENT",
                             std::to_string(fixed) + " degenerate tangents replaced by a perpendicular to the normal");
                }
            } else {
                const size_t fallbacks = generateTangents(out);
                if (fallbacks > 0 && uvs) {
                    ctx.warn(where + ".attributes.TEXCOORD_0", std::to_string(fallbacks) +
                                                                  " vertices have no usable UV direction; their tangent is arbitrary");
                }
            }
            for (const Vertex& v : out.vertices) out.boundsOs.extend(v.positionOs);
            mesh.primitives.push_back(std::move(out));
        }
        if (repeated > 0)
            ctx.warn(indexed("meshes", m) + ".primitives", std::to_string(repeated) +
                                                               " primitives repeat an earlier one (same accessors, material and mode); drawn once");
        convertMorphWeights(ctx, m, mesh);
        updateMeshCurvature(mesh);
        ctx.scene->meshes.push_back(std::move(mesh));
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

// A light the file defines but that cannot light anything (an unknown type, a node scaled to
// nothing): the validator allows it, so it is skipped with a warning.
std::optional<Light> convertLight(const LoadContext& ctx, int lightIndex, const glm::mat4& world, const std::string& nodeName,
                                  const std::string& nodeWhere, bool& explicitShadowFlag) {
    const tinygltf::Model& model = *ctx.model;
    if (lightIndex < 0 || static_cast<size_t>(lightIndex) >= model.lights.size()) {
        ctx.fail(nodeWhere + ".extensions.KHR_lights_punctual.light",
                 std::to_string(lightIndex) + " is out of range: the file has " + std::to_string(model.lights.size()) + " lights");
    }
    const tinygltf::Light& in = model.lights[static_cast<size_t>(lightIndex)];
    const std::string where = "extensions.KHR_lights_punctual.lights[" + std::to_string(lightIndex) + "]";
    Light out;
    out.name = in.name.empty() ? nodeName : in.name;
    if (in.type == "directional") out.type = LightType::Directional;
    else if (in.type == "point") out.type = LightType::Point;
    else if (in.type == "spot") out.type = LightType::Spot;
    else {
        ctx.warn(where + ".type", "'" + in.type + "' is not a KHR_lights_punctual type (directional, point or spot); light skipped");
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
            ctx.fail(where + ".spot", "cone angles inner " + number(inner) + ", outer " + number(outer) +
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
    explicitShadowFlag = false;
    if (auto casts = boolField(ctx, in.extras, "castsShadow", where + ".extras")) {
        out.castsShadow = *casts;
        explicitShadowFlag = true;
    }
    return out;
}

// A camera the validator allows but that cannot show anything (a node scaled to nothing, a field
// of view too small for single precision) is skipped with a warning.
std::optional<Camera> convertCamera(const LoadContext& ctx, int cameraIndex, const glm::mat4& world, const std::string& nodeName,
                                    const std::string& nodeWhere) {
    const tinygltf::Model& model = *ctx.model;
    if (cameraIndex < 0 || static_cast<size_t>(cameraIndex) >= model.cameras.size()) {
        ctx.fail(nodeWhere + ".camera", std::to_string(cameraIndex) + " is out of range: the file has " +
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
        if (!std::isfinite(p.aspectRatio) || p.aspectRatio < 0.0) ctx.fail(where + ".perspective.aspectRatio", "must be > 0");
        out.yfov = static_cast<float>(p.yfov);
        if (!(out.yfov >= kMinCameraYfov)) {
            ctx.warn(where + ".perspective.yfov", number(p.yfov) + " rad is too small a field of view to render; camera skipped");
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
        if (!std::isfinite(o.xmag) || o.xmag == 0.0) ctx.fail(where + ".orthographic.xmag", "must be finite and non-zero");
        if (!std::isfinite(o.ymag) || o.ymag == 0.0) ctx.fail(where + ".orthographic.ymag", "must be finite and non-zero");
        if (!(o.znear >= 0.0) || !std::isfinite(o.znear)) ctx.fail(where + ".orthographic.znear", "must be >= 0");
        if (!(o.zfar > o.znear) || !std::isfinite(o.zfar)) ctx.fail(where + ".orthographic.zfar", "must be greater than znear");
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
    // The node graph must be a forest (glTF 2.0, "Nodes and Hierarchy"): one parent per node and
    // no cycles, whether or not the file has scenes.
    std::vector<int> parent(nodeCount, -1);
    for (size_t i = 0; i < nodeCount; ++i) {
        const auto& children = model.nodes[i].children;
        for (size_t k = 0; k < children.size(); ++k) {
            if (children[k] < 0 || static_cast<size_t>(children[k]) >= nodeCount) {
                ctx.fail(indexed("nodes", i) + indexed(".children", k),
                         std::to_string(children[k]) + " is out of range: the file has " + std::to_string(nodeCount) + " nodes");
            }
            int& p = parent[static_cast<size_t>(children[k])];
            if (p >= 0) {
                ctx.fail(indexed("nodes", i) + indexed(".children", k),
                         "nodes[" + std::to_string(children[k]) + "] is already a child of nodes[" + std::to_string(p) +
                             "] (a node has at most one parent)");
            }
            p = static_cast<int>(i);
        }
    }
    {
        // Follow each node's parents up to a root; meeting the current path again is a cycle.
        std::vector<uint8_t> state(nodeCount, 0);  // 0 unseen, 1 on the current path, 2 leads to a root
        std::vector<size_t> path;
        for (size_t start = 0; start < nodeCount; ++start) {
            size_t n = start;
            while (state[n] == 0) {
                state[n] = 1;
                path.push_back(n);
                if (parent[n] < 0) break;
                n = static_cast<size_t>(parent[n]);
            }
            if (state[n] == 1 && parent[n] >= 0) ctx.fail(indexed("nodes", n), "is part of a cycle of children");
            for (size_t visited : path) state[visited] = 2;
            path.clear();
        }
    }

    std::vector<int> roots;
    if (model.defaultScene >= 0 || !model.scenes.empty()) {
        const int sceneIndex = model.defaultScene >= 0 ? model.defaultScene : 0;
        if (static_cast<size_t>(sceneIndex) >= model.scenes.size()) {
            ctx.fail("scene", std::to_string(sceneIndex) + " is out of range: the file has " +
                                  std::to_string(model.scenes.size()) + " scenes");
        }
        const auto& nodes = model.scenes[static_cast<size_t>(sceneIndex)].nodes;
        for (size_t k = 0; k < nodes.size(); ++k) {
            if (nodes[k] < 0 || static_cast<size_t>(nodes[k]) >= nodeCount) {
                ctx.fail(indexed("scenes", static_cast<size_t>(sceneIndex)) + indexed(".nodes", k),
                         std::to_string(nodes[k]) + " is out of range: the file has " + std::to_string(nodeCount) + " nodes");
            }
            if (const int p = parent[static_cast<size_t>(nodes[k])]; p >= 0) {
                ctx.fail(indexed("scenes", static_cast<size_t>(sceneIndex)) + indexed(".nodes", k),
                         "nodes[" + std::to_string(nodes[k]) + "] is not a root node: it is a child of nodes[" +
                             std::to_string(p) + "]");
            }
            roots.push_back(nodes[k]);
        }
    } else {
        for (size_t i = 0; i < nodeCount; ++i)
            if (parent[i] < 0) roots.push_back(static_cast<int>(i));
    }

    Scene& scene = *ctx.scene;
    std::vector<uint64_t> meshTriangles(scene.meshes.size(), 0);
    for (size_t m = 0; m < scene.meshes.size(); ++m)
        for (const Primitive& p : scene.meshes[m].primitives) meshTriangles[m] += p.indices.size() / 3;
    uint64_t draws = 0;
    uint64_t drawnTriangles = 0;
    std::vector<uint8_t> visited(nodeCount, 0);
    std::vector<uint8_t> explicitShadow;
    struct Pending {
        int node;
        glm::mat4 parentWorld;
    };
    std::vector<Pending> stack;
    for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, glm::mat4(1.0f)});
    while (!stack.empty()) {
        const Pending item = stack.back();
        stack.pop_back();
        const auto index = static_cast<size_t>(item.node);
        const std::string where = indexed("nodes", index);
        if (visited[index]) {
            ctx.fail(where, "reached twice: the node graph has a cycle, a node with two parents, or a node listed twice");
        }
        visited[index] = 1;
        const tinygltf::Node& node = model.nodes[index];
        const std::string nodeName = node.name.empty() ? where : node.name;
        const glm::mat4 world = item.parentWorld * localMatrix(ctx, node, where);
        if (!withinInputRange(world)) {
            ctx.fail(where, "its world transform (the product of its parents' transforms) has an element that is not "
                            "finite or exceeds the limit of " + number(limits::kMaxInputMagnitude) + " in magnitude");
        }

        if (node.mesh >= 0) {
            if (static_cast<size_t>(node.mesh) >= model.meshes.size()) {
                ctx.fail(where + ".mesh", std::to_string(node.mesh) + " is out of range: the file has " +
                                              std::to_string(model.meshes.size()) + " meshes");
            }
            const auto mesh = static_cast<size_t>(node.mesh);
            draws += scene.meshes[mesh].primitives.size();
            drawnTriangles += meshTriangles[mesh];
            if (draws > limits::kMaxSceneDraws) {
                ctx.fail(where + ".mesh", "the scene draws more than the limit of " +
                                              std::to_string(limits::kMaxSceneDraws) + " primitives (instances included)");
            }
            if (drawnTriangles > limits::kMaxDrawnTriangles) {
                ctx.fail(where + ".mesh", "the scene draws more than the limit of " +
                                              std::to_string(limits::kMaxDrawnTriangles) + " triangles (instances included)");
            }
            scene.instances.push_back(MeshInstance{node.mesh, world, nodeName});
            scene.instances.back().node = item.node;
            scene.instances.back().skin = node.skin;
        } else if (node.mesh < -1) {
            ctx.fail(where + ".mesh", std::to_string(node.mesh) + " is out of range");
        }
        const bool cameraSkipped = std::find(ctx.skippedCameras.begin(), ctx.skippedCameras.end(),
                                             static_cast<size_t>(std::max(node.camera, 0))) != ctx.skippedCameras.end();
        if ((node.camera >= 0 && !cameraSkipped) || node.camera < -1) {
            if (auto camera = convertCamera(ctx, node.camera, world, nodeName, where)) scene.cameras.push_back(std::move(*camera));
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
        for (auto child = node.children.rbegin(); child != node.children.rend(); ++child) {
            stack.push_back({*child, world});
        }
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
    return loadSceneBytes(io::readInputFile(path, path.string(),
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
        fail(file, "GLB chunk 0 length", std::to_string(jsonText.size()) + " bytes of JSON exceeds the limit of " +
                                             std::to_string(limits::kMaxGltfJsonBytes));
    }
    // The bounded parse comes first: tinygltf parses the same text again, and walks it
    // recursively, only once depth and size are known to be within the limits.
    if (jsonText.size() >= 3 && jsonText[0] == 0xEF && jsonText[1] == 0xBB && jsonText[2] == 0xBF)
        bomWarning = file + ": JSON: starts with a UTF-8 byte-order mark, which glTF does not allow; read anyway";
    nlohmann::json doc = io::parseJson(jsonText, file);
    const PrepassResult prepass = checkDocument(doc, file, folder, isGlb ? &glb : nullptr, options.allowLinksOutsideFolder);
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
    loader.SetFsCallbacks(tinygltf::FsCallbacks{&fileExists, &expandFilePath, &readWholeFile, &writeWholeFile, &fsState});
    ImageState imageState;
    loader.SetImageLoader(&loadImage, &imageState);
    tinygltf::Model model;
    std::string err, warn;
    const bool ok =
        isGlb ? loader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), static_cast<unsigned>(bytes.size()),
                                            folder.string())
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
            ctx.warn(where, ctx.unsupportedImageFormat[i] + " is not decoded (PNG and JPEG are supported)");
        } else if (in.image.empty() || in.width <= 0 || in.height <= 0 || in.component != 4) {
            ctx.fail(where, "no pixel data could be read");
        } else {
            out.width = static_cast<uint32_t>(in.width);
            out.height = static_cast<uint32_t>(in.height);
            out.rgba8 = std::move(in.image);
        }
        scene.images.push_back(std::move(out));
    }
    convertSamplers(ctx);
    convertMaterials(ctx);
    convertMeshes(ctx);
    convertNodes(ctx);
    convertNodeHierarchy(ctx);
    convertSkins(ctx);
    convertAnimations(ctx);
    if (scene.instances.empty())
        ctx.warn("scenes", "nothing to draw: no node of the scene holds a mesh (the image shows the background only)");
    return scene;
}

}  // namespace preskin::gltf
