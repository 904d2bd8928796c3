// preskin::Scene: loading (delegated to the glTF loader), world bounds, turning materials into
// skin, and the KHR_texture_transform matrix of a texture reference.
#include <preskin/Error.h>
#include <preskin/Scene.h>

#include "scene/GltfLoader.h"
#include "scene/GltfMaterials.h"

#include <cmath>

namespace preskin {

glm::mat3 TextureRef::uvTransform() const {
    // KHR_texture_transform: T(offset) * R(rotation) * S(scale) with
    //   R = | cos  sin 0 |
    //       |-sin  cos 0 |
    //       |  0    0  1 |   (rows), so uv' = (sx u cos + sy v sin + ox, -sx u sin + sy v cos + oy).
    const float c = std::cos(uvRotation), s = std::sin(uvRotation);
    glm::mat3 m(1.0f);  // glm: m[column][row]
    m[0] = glm::vec3(uvScale.x * c, -uvScale.x * s, 0.0f);
    m[1] = glm::vec3(uvScale.y * s, uvScale.y * c, 0.0f);
    m[2] = glm::vec3(uvOffset.x, uvOffset.y, 1.0f);
    return m;
}

Scene Scene::load(const std::filesystem::path& path, const SceneLoadOptions& options) {
    return gltf::loadScene(path, options);
}

Bounds Scene::worldBounds() const {
    Bounds bounds;
    for (const MeshInstance& instance : instances) {
        if (instance.mesh < 0 || static_cast<size_t>(instance.mesh) >= meshes.size()) continue;
        for (const Primitive& primitive : meshes[static_cast<size_t>(instance.mesh)].primitives) {
            const Bounds& b = primitive.boundsOs;
            if (b.empty()) continue;
            for (int corner = 0; corner < 8; ++corner) {
                const glm::vec3 p((corner & 1) ? b.max.x : b.min.x, (corner & 2) ? b.max.y : b.min.y,
                                  (corner & 4) ? b.max.z : b.min.z);
                bounds.extend(glm::vec3(instance.worldFromObject * glm::vec4(p, 1.0f)));
            }
        }
    }
    return bounds;
}

int Scene::addDefaultMaterial() {
    int index = -1;
    for (Mesh& mesh : meshes)
        for (Primitive& primitive : mesh.primitives) {
            if (primitive.material >= 0 && size_t(primitive.material) < materials.size()) continue;
            if (index < 0) {
                index = static_cast<int>(materials.size());
                Material material;  // Material's defaults are glTF's default material
                material.name = kDefaultMaterialName;
                materials.push_back(std::move(material));
            }
            primitive.material = index;
        }
    return index;
}

void Scene::makeSkin(const std::string& materialName, const SkinMaterial& defaults) {
    if (materialName == "all") addDefaultMaterial();
    bool found = false;
    for (size_t i = 0; i < materials.size(); ++i) {
        Material& material = materials[i];
        if (materialName != "all" && material.name != materialName) continue;
        found = true;
        if (material.skin) continue;
        material.skin = gltf::seededSkin(material, defaults);
        gltf::applyKhronosScatter(*this, i);
    }
    if (!found && materialName != "all") {
        std::string names;
        for (const Material& material : materials) names += (names.empty() ? "" : ", ") + material.name;
        throw Error(sourcePath.string() + ": no material named '" + materialName +
                    "' (materials: " + (names.empty() ? "none" : names) + ")");
    }
}

void Scene::setSkinProfile(const std::string& materialName, int profile) {
    if (profile < -1 || profile >= static_cast<int>(profiles.size())) {
        throw Error(sourcePath.string() + ": profile: " + std::to_string(profile) + " is out of range: the scene has " +
                    std::to_string(profiles.size()) + " profiles (-1: the default)");
    }
    makeSkin(materialName);
    for (Material& material : materials) {
        if (materialName == "all" || material.name == materialName) material.skin->profile = profile;
    }
}

}  // namespace preskin
