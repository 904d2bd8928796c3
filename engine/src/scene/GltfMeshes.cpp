// glTF meshes to preskin meshes (see GltfMeshes.h).
#include "scene/GltfMeshes.h"

#include "scene/GltfAccessors.h"
#include "scene/GltfMorphTargets.h"
#include "scene/GltfSkins.h"
#include "scene/TangentFrames.h"

#include <preskin/Curvature.h>
#include <preskin/Limits.h>

#include <glm/gtc/type_ptr.hpp>

#include <map>
#include <set>
#include <string>
#include <tuple>

namespace preskin::gltf {

using scene::generateTangents;
using scene::makeFlatNormals;
using scene::orthonormalizeTangents;

namespace {

std::vector<uint32_t> toTriangleList(const LoadContext& ctx, const std::vector<uint32_t>& indices, int mode,
                                     bool indexed, const std::string& where) {
    std::vector<uint32_t> list;
    const size_t n = indices.size();
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        if (n % 3 != 0) {  // the glTF validator's warning; the trailing indices make no triangle
            ctx.warn(where,
                     std::string(indexed ? "index" : "vertex") + " count " + std::to_string(n) +
                         " is not a multiple of 3 for a triangle list; the last " + std::to_string(n % 3) + " ignored");
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

// Whether the primitive's material bends its normal by a tangent-space map (the normal map, or
// skin's detail normal map): only then does a vertex without a UV direction matter.
bool readsTangents(const tinygltf::Model& model, int material) {
    if (material < 0 || material >= static_cast<int>(model.materials.size())) return false;
    const tinygltf::Material& m = model.materials[size_t(material)];
    if (m.normalTexture.index >= 0) return true;
    const auto skin = m.extensions.find("PRESKIN_materials_skin");
    return skin != m.extensions.end() && skin->second.IsObject() && skin->second.Has("detailNormalTexture");
}

size_t repairNormals(Primitive& primitive) {
    std::vector<size_t> broken;
    for (size_t i = 0; i < primitive.vertices.size(); ++i) {
        glm::vec3& n = primitive.vertices[i].normalOs;
        const float len = glm::length(n);
        if (len > 1e-12f)
            n /= len;
        else
            broken.push_back(i);
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

}  // namespace

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
        using PrimitiveKey =
            std::tuple<std::map<std::string, int>, int, int, int, std::vector<std::map<std::string, int>>>;
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
                ctx.fail(where + ".material",
                         std::to_string(prim.material) + " is out of range: the file has " +
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
                    ctx.fail(at,
                             "accessors[" + std::to_string(index) + "] has " + std::to_string(count) +
                                 " elements, POSITION has " + std::to_string(vertexCount));
                }
            }
            const size_t indexCount = prim.indices >= 0
                ? accessorCount(ctx, prim.indices, where + ".indices", AccessorUse::Indices)
                : vertexCount;
            const size_t listCount = mode == TINYGLTF_MODE_TRIANGLES ? indexCount
                : indexCount < 3                                     ? 0
                                                                     : (indexCount - 2) * 3;
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
                    ctx.fail(at,
                             "accessors[" + std::to_string(index) + "] has " + std::to_string(a.count) +
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
            out.indices =
                toTriangleList(ctx, indices, mode, prim.indices >= 0, prim.indices >= 0 ? where + ".indices" : where);
            totalIndices += out.indices.size();
            if (out.indices.empty()) {
                ctx.warn(where, "no triangles; primitive skipped");
                continue;
            }

            if (!normals) {
                makeFlatNormals(out);
            } else if (const size_t fixed = repairNormals(out); fixed > 0) {
                ctx.warn(where + ".attributes.NORMAL",
                         std::to_string(fixed) + " zero-length normals replaced by the mean face normal");
            }
            if (tangents) {
                if (const size_t fixed = orthonormalizeTangents(out); fixed > 0) {
                    ctx.warn(where + ".attributes.TANGENT",
                             std::to_string(fixed) + " degenerate tangents replaced by a perpendicular to the normal");
                }
            } else {
                const size_t fallbacks = generateTangents(out);
                if (fallbacks > 0 && uvs && readsTangents(model, prim.material)) {
                    ctx.warn(where + ".attributes.TEXCOORD_0",
                             std::to_string(fallbacks) +
                                 " vertices have no usable UV direction; their tangent is arbitrary");
                }
            }
            for (const Vertex& v : out.vertices) out.boundsOs.extend(v.positionOs);
            mesh.primitives.push_back(std::move(out));
        }
        if (repeated > 0)
            ctx.warn(indexed("meshes", m) + ".primitives",
                     std::to_string(repeated) +
                         " primitives repeat an earlier one (same accessors, material and mode); drawn once");
        convertMorphWeights(ctx, m, mesh);
        updateMeshCurvature(mesh);
        ctx.scene->meshes.push_back(std::move(mesh));
    }
}

}  // namespace preskin::gltf
