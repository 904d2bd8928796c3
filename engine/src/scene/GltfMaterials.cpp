// glTF samplers, textures and materials, core and extensions (see GltfMaterials.h).
#include "scene/GltfMaterials.h"

#include <preskin/Error.h>

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <set>
#include <utility>

namespace preskin::gltf {

namespace {

// A string field that names one of `names`: its value into `out`; another string is refused,
// naming the field and listing the names.
template <typename T>
void namedField(const LoadContext& ctx, const tinygltf::Value& object, const char* key, const std::string& where,
                std::initializer_list<std::pair<const char*, T>> names, T& out) {
    const auto text = stringField(ctx, object, key, where);
    if (!text) return;
    std::string expected;
    size_t i = 0;
    for (const auto& [name, value] : names) {
        if (*text == name) {
            out = value;
            return;
        }
        expected += std::string(i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + name;
        ++i;
    }
    ctx.fail(where + "." + key, "'" + io::messageText(*text) + "' (expected " + expected + ")");
}

Filter filterOf(bool nearest) { return nearest ? Filter::Nearest : Filter::Linear; }

Wrap wrapOf(const LoadContext& ctx, int mode, const std::string& where) {
    switch (mode) {
    case TINYGLTF_TEXTURE_WRAP_REPEAT: return Wrap::Repeat;
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return Wrap::ClampToEdge;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return Wrap::MirroredRepeat;
    default: ctx.fail(where, std::to_string(mode) + " is not a glTF wrap mode");
    }
}

// The image and sampler a texture index resolves to; image -1 when the texture has no source
// preskin can read (a warning says so).
std::pair<int, int> resolveTexture(const LoadContext& ctx, int textureIndex, const std::string& where) {
    const tinygltf::Model& model = *ctx.model;
    if (textureIndex < 0 || static_cast<size_t>(textureIndex) >= model.textures.size()) {
        ctx.fail(where + ".index",
                 std::to_string(textureIndex) + " is out of range: the file has " +
                     std::to_string(model.textures.size()) + " textures");
    }
    const std::string textureName = indexed("textures", static_cast<size_t>(textureIndex));
    const tinygltf::Texture& texture = model.textures[static_cast<size_t>(textureIndex)];
    if (texture.sampler >= 0 && static_cast<size_t>(texture.sampler) >= model.samplers.size()) {
        ctx.fail(textureName + ".sampler",
                 std::to_string(texture.sampler) + " is out of range: the file has " +
                     std::to_string(model.samplers.size()) + " samplers");
    }
    if (texture.source < 0) {
        ctx.warn(where, textureName + " has no PNG or JPEG source (only an extension's); the texture is ignored");
        return {-1, -1};
    }
    if (static_cast<size_t>(texture.source) >= model.images.size()) {
        ctx.fail(textureName + ".source",
                 std::to_string(texture.source) + " is out of range: the file has " +
                     std::to_string(model.images.size()) + " images");
    }
    const auto image = static_cast<size_t>(texture.source);
    if (!ctx.unsupportedImageFormat[image].empty()) {
        ctx.fail(where,
                 indexed("images", image) + " is " + ctx.unsupportedImageFormat[image] +
                     ", an unsupported image format (PNG and JPEG are supported)");
    }
    return {texture.source, texture.sampler};
}

void warnTexCoord(const LoadContext& ctx, int texCoord, const std::string& where) {
    if (texCoord != 0) {
        ctx.warn(where, "uses TEXCOORD_" + std::to_string(texCoord) + "; only TEXCOORD_0 is loaded, so set 0 is used");
    }
}

template <typename Info>
TextureRef textureRef(const LoadContext& ctx, const Info& info, const std::string& where) {
    TextureRef ref;
    if (info.index < 0) return ref;  // absent
    const auto [image, sampler] = resolveTexture(ctx, info.index, where);
    if (image < 0) return ref;
    ref.image = image;
    ref.sampler = sampler;
    warnTexCoord(ctx, info.texCoord, where + ".texCoord");
    auto it = info.extensions.find("KHR_texture_transform");
    if (it != info.extensions.end()) {
        const tinygltf::Value& t = it->second;
        const std::string at = where + ".extensions.KHR_texture_transform";
        if (!t.IsObject()) ctx.fail(at, "not an object");
        ref.uvOffset = vec2Field(ctx, t, "offset", at).value_or(glm::vec2(0.0f));
        ref.uvRotation = static_cast<float>(numberField(ctx, t, "rotation", at).value_or(0.0));
        ref.uvScale = vec2Field(ctx, t, "scale", at).value_or(glm::vec2(1.0f));
        if (auto texCoord = integerField(ctx, t, "texCoord", at)) warnTexCoord(ctx, *texCoord, at + ".texCoord");
    }
    return ref;
}

SkinTextureRef skinTextureRef(const LoadContext& ctx, const tinygltf::Value& skin, const char* key,
                              const std::string& where, float* scaleOut) {
    SkinTextureRef ref;
    if (!skin.Has(key)) return ref;
    const tinygltf::Value& info = skin.Get(key);
    const std::string at = where + "." + key;
    if (!info.IsObject()) ctx.fail(at, "not a textureInfo object");
    const auto index = integerField(ctx, info, "index", at);
    if (!index) ctx.fail(at + ".index", "missing");
    const auto [image, sampler] = resolveTexture(ctx, *index, at);
    ref.image = image;
    ref.sampler = sampler;
    if (auto texCoord = integerField(ctx, info, "texCoord", at)) warnTexCoord(ctx, *texCoord, at + ".texCoord");
    if (scaleOut) {
        if (auto scale = numberField(ctx, info, "scale", at)) *scaleOut = static_cast<float>(*scale);
    }
    if (info.Has("extensions") && info.Get("extensions").Has("KHR_texture_transform")) {
        ctx.warn(at, "KHR_texture_transform is not applied to skin textures; ignored");
    }
    return ref;
}

float clampedFactor(const LoadContext& ctx, double value, double lo, double hi, const std::string& where) {
    checkedNumber(ctx, value, where);
    if (value < lo || value > hi) {
        ctx.warn(where, number(value) + " is outside [" + number(lo) + ", " + number(hi) + "]; clamped");
        value = std::clamp(value, lo, hi);
    }
    return static_cast<float>(value);
}

// A PRESKIN_materials_skin number with its allowed range.
void skinNumber(const LoadContext& ctx, const tinygltf::Value& skin, const char* key, const std::string& where,
                float& out, double lo, double hi, bool loOpen = false) {
    auto v = numberField(ctx, skin, key, where);
    if (!v) return;
    if (*v < lo || *v > hi || (loOpen && *v == lo)) {
        ctx.fail(where + "." + key,
                 number(*v) + " is outside " + (loOpen ? "(" : "[") + number(lo) + ", " +
                     (std::isinf(hi) ? "inf)" : number(hi) + "]"));
    }
    out = static_cast<float>(*v);
}

// An index into the scene's profiles (the root extension's "profiles").
int profileIndex(const LoadContext& ctx, const tinygltf::Value& value, const std::string& where) {
    if (!value.IsInt() && !value.IsNumber()) ctx.fail(where, "not an integer");
    const double index = value.IsInt() ? value.GetNumberAsInt() : value.GetNumberAsDouble();
    const size_t count = ctx.scene->profiles.size();
    if (index != std::floor(index) || index < 0.0 || index >= static_cast<double>(count)) {
        ctx.fail(where,
                 number(index) + " is out of range: the file has " + std::to_string(count) +
                     " profiles (extensions.PRESKIN_materials_skin.profiles)");
    }
    return static_cast<int>(index);
}

// "profile": index; "profileBlend": {"profiles": [up to 3 indices], "weightTexture": textureInfo}.
void parseProfileChoice(const LoadContext& ctx, const tinygltf::Value& skin, const std::string& where,
                        SkinMaterial& s) {
    if (skin.Has("profile")) s.profile = profileIndex(ctx, skin.Get("profile"), where + ".profile");
    if (!skin.Has("profileBlend")) return;
    const tinygltf::Value& blend = skin.Get("profileBlend");
    const std::string at = where + ".profileBlend";
    if (!blend.IsObject()) ctx.fail(at, "not an object");
    for (const std::string& key : blend.Keys()) {
        if (key != "profiles" && key != "weightTexture") ctx.fail(at + "." + key, "unknown field");
    }
    if (!blend.Has("profiles") || !blend.Get("profiles").IsArray())
        ctx.fail(at + ".profiles", "missing or not an array");
    const tinygltf::Value& list = blend.Get("profiles");
    if (list.ArrayLen() < 1 || list.ArrayLen() > size_t(kMaxBlendedProfiles - 1)) {
        ctx.fail(at + ".profiles",
                 std::to_string(list.ArrayLen()) + " entries (expected 1 to " +
                     std::to_string(kMaxBlendedProfiles - 1) + ", one per weight-texture channel)");
    }
    for (size_t i = 0; i < list.ArrayLen(); ++i)
        s.blendProfiles.push_back(profileIndex(ctx, list.Get(static_cast<int>(i)), indexed(at + ".profiles", i)));
    s.profileWeightTexture = skinTextureRef(ctx, blend, "weightTexture", at, nullptr);
    if (!s.profileWeightTexture.valid()) ctx.fail(at + ".weightTexture", "missing or without a usable image");
}

SkinMaterial parseSkinExtension(const LoadContext& ctx, const tinygltf::Value& skin, const std::string& where,
                                SkinMaterial s) {
    if (!skin.IsObject()) ctx.fail(where, "not an object");
    static const std::set<std::string> known = {"scatterScale",
                                                "curvatureSource",
                                                "curvatureTexture",
                                                "curvatureTextureScalePerM",
                                                "curvatureTextureBias",
                                                "deformedCurvature",
                                                "normalLodBias",
                                                "detailNormalTexture",
                                                "detailUvScale",
                                                "transmission",
                                                "transmissionColor",
                                                "thicknessScale",
                                                "specularIntensity",
                                                "specularTexture",
                                                "lobeRoughness0",
                                                "lobeRoughness1",
                                                "lobeMix",
                                                "profile",
                                                "quality",
                                                "profileBlend"};
    for (const std::string& key : skin.Keys()) {
        if (!known.count(key) && key != "extensions" && key != "extras")
            ctx.warn(where + "." + key, "unknown field; ignored");
    }
    constexpr double inf = std::numeric_limits<double>::infinity();
    skinNumber(ctx, skin, "scatterScale", where, s.scatterScale, 0.0, inf, true);
    namedField(ctx, skin, "quality", where,
               {{"low", SkinQuality::Low}, {"medium", SkinQuality::Medium}, {"high", SkinQuality::High}}, s.quality);
    namedField(ctx, skin, "curvatureSource", where,
               {{"vertex", CurvatureSource::Vertex},
                {"texture", CurvatureSource::Texture},
                {"derivatives", CurvatureSource::Derivatives}},
               s.curvatureSource);
    s.curvatureTexture = skinTextureRef(ctx, skin, "curvatureTexture", where, nullptr);
    if (s.curvatureSource == CurvatureSource::Texture && !s.curvatureTexture.valid()) {
        ctx.fail(where + ".curvatureSource", "'texture' but there is no usable curvatureTexture");
    }
    skinNumber(ctx, skin, "curvatureTextureScalePerM", where, s.curvatureTextureScalePerM, 0.0, inf);
    skinNumber(ctx, skin, "curvatureTextureBias", where, s.curvatureTextureBias, 0.0, 1.0);
    namedField(ctx, skin, "deformedCurvature", where,
               {{"recomputed", DeformedCurvature::Recomputed}, {"bindPose", DeformedCurvature::BindPose}},
               s.deformedCurvature);
    if (auto bias = vec3Field(ctx, skin, "normalLodBias", where)) s.normalLodBias = *bias;
    s.detailNormalTexture = skinTextureRef(ctx, skin, "detailNormalTexture", where, &s.detailNormalScale);
    skinNumber(ctx, skin, "detailUvScale", where, s.detailUvScale, 0.0, inf, true);
    skinNumber(ctx, skin, "transmission", where, s.transmission, 0.0, inf);
    if (auto color = vec3Field(ctx, skin, "transmissionColor", where)) {
        if (glm::any(glm::lessThan(*color, glm::vec3(0.0f))))
            ctx.fail(where + ".transmissionColor", "negative component");
        s.transmissionColor = *color;
    }
    skinNumber(ctx, skin, "thicknessScale", where, s.thicknessScale, 0.0, inf, true);
    skinNumber(ctx, skin, "specularIntensity", where, s.specularIntensity, 0.0, inf);
    s.specularTexture = skinTextureRef(ctx, skin, "specularTexture", where, nullptr);
    skinNumber(ctx, skin, "lobeRoughness0", where, s.lobeRoughness0, 0.0, inf, true);
    skinNumber(ctx, skin, "lobeRoughness1", where, s.lobeRoughness1, 0.0, inf, true);
    skinNumber(ctx, skin, "lobeMix", where, s.lobeMix, 0.0, 1.0);
    parseProfileChoice(ctx, skin, where, s);
    return s;
}

// KHR_materials_volume's attenuation with the multiple-scattering albedo and anisotropy of
// KHR_materials_scatter (the successor draft, read first) or KHR_materials_volume_scatter.
void parseKhronosScatter(const LoadContext& ctx, const tinygltf::ExtensionMap& ext, const std::string& where,
                         Material& out) {
    const auto successor = ext.find("KHR_materials_scatter");
    const auto draft = ext.find("KHR_materials_volume_scatter");
    if (successor == ext.end() && draft == ext.end()) return;
    const bool isSuccessor = successor != ext.end();
    const tinygltf::Value& scatter = isSuccessor ? successor->second : draft->second;
    const std::string at =
        where + ".extensions." + (isSuccessor ? "KHR_materials_scatter" : "KHR_materials_volume_scatter");
    if (isSuccessor && draft != ext.end())
        ctx.warn(where + ".extensions.KHR_materials_volume_scatter", "not used: KHR_materials_scatter is read instead");
    KhronosScatter k;
    const char* colorKey = scatter.Has("multiscatterColorFactor") ? "multiscatterColorFactor" : "multiscatterColor";
    const glm::vec3 color = vec3Field(ctx, scatter, colorKey, at).value_or(glm::vec3(0.0f));
    for (int c = 0; c < 3; ++c) k.multiscatterColor[c] = clampedFactor(ctx, color[c], 0.0, 1.0, at + "." + colorKey);
    const double g = numberField(ctx, scatter, "scatterAnisotropy", at).value_or(0.0);
    k.scatterAnisotropy = clampedFactor(ctx, g, -0.99, 0.99, at + ".scatterAnisotropy");
    if (isSuccessor) {
        const double factor = clampedFactor(ctx, numberField(ctx, scatter, "scatterFactor", at).value_or(0.0), 0.0, 1.0,
                                            at + ".scatterFactor");
        if (factor == 0.0) {
            ctx.warn(at + ".scatterFactor", "0 (the default): scattering is off, no profile is made from it");
            return;
        }
        k.multiscatterColor *= factor;
    }
    for (const char* texture : {"multiscatterColorTexture", "scatterTexture"})
        if (scatter.Has(texture)) ctx.warn(at + "." + texture, "not used; only the factors are read");
    if (auto volume = ext.find("KHR_materials_volume"); volume != ext.end()) {
        const std::string vat = where + ".extensions.KHR_materials_volume";
        if (auto distance = numberField(ctx, volume->second, "attenuationDistance", vat)) {
            if (!(*distance > 0.0)) ctx.fail(vat + ".attenuationDistance", "must be > 0");
            k.attenuationDistanceM = *distance;
        }
        const glm::vec3 attenuation = vec3Field(ctx, volume->second, "attenuationColor", vat).value_or(glm::vec3(1.0f));
        for (int c = 0; c < 3; ++c)
            k.attenuationColor[c] = clampedFactor(ctx, attenuation[c], 0.0, 1.0, vat + ".attenuationColor");
        if (volume->second.Has("thicknessTexture"))
            ctx.warn(vat + ".thicknessTexture", "not used; thicknessFactor seeds the skin's thickness scale");
    }
    out.khronosScatter = k;
}

}  // namespace

SkinMaterial seededSkin(const Material& material, const SkinMaterial& defaults) {
    SkinMaterial s = defaults;
    if (material.diffuseTransmissionFactor) s.transmission = *material.diffuseTransmissionFactor;
    if (material.diffuseTransmissionColor) s.transmissionColor = *material.diffuseTransmissionColor;
    if (material.volumeThicknessFactor) s.thicknessScale = *material.volumeThicknessFactor;
    return s;
}

void convertSamplers(const LoadContext& ctx) {
    const tinygltf::Model& model = *ctx.model;
    for (size_t i = 0; i < model.samplers.size(); ++i) {
        const tinygltf::Sampler& in = model.samplers[i];
        const std::string where = indexed("samplers", i);
        Sampler out;
        switch (in.magFilter) {
        case -1:
        case TINYGLTF_TEXTURE_FILTER_LINEAR: out.magFilter = Filter::Linear; break;
        case TINYGLTF_TEXTURE_FILTER_NEAREST: out.magFilter = Filter::Nearest; break;
        default: ctx.fail(where + ".magFilter", std::to_string(in.magFilter) + " is not a glTF magnification filter");
        }
        switch (in.minFilter) {
        case -1: break;  // undefined: trilinear
        case TINYGLTF_TEXTURE_FILTER_NEAREST:
        case TINYGLTF_TEXTURE_FILTER_LINEAR:
            out.minFilter = filterOf(in.minFilter == TINYGLTF_TEXTURE_FILTER_NEAREST);
            out.mipmaps = false;
            break;
        case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST:
        case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST:
        case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR:
        case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR:
            out.minFilter = filterOf(in.minFilter == TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST ||
                                     in.minFilter == TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR);
            out.mipFilter = filterOf(in.minFilter == TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST ||
                                     in.minFilter == TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST);
            out.mipmaps = true;
            break;
        default: ctx.fail(where + ".minFilter", std::to_string(in.minFilter) + " is not a glTF minification filter");
        }
        out.wrapU = wrapOf(ctx, in.wrapS, where + ".wrapS");
        out.wrapV = wrapOf(ctx, in.wrapT, where + ".wrapT");
        ctx.scene->samplers.push_back(out);
    }
}

void convertMaterials(const LoadContext& ctx) {
    const tinygltf::Model& model = *ctx.model;
    for (size_t i = 0; i < model.materials.size(); ++i) {
        const tinygltf::Material& in = model.materials[i];
        const std::string where = indexed("materials", i);
        const std::string pbr = where + ".pbrMetallicRoughness";
        Material out;
        out.name = in.name.empty() ? where : in.name;

        if (auto c = fixedArray(ctx, in.pbrMetallicRoughness.baseColorFactor, 4, pbr + ".baseColorFactor")) {
            for (int k = 0; k < 4; ++k) {
                out.baseColorFactor[k] =
                    clampedFactor(ctx, (*c)[static_cast<size_t>(k)], 0.0, 1.0, pbr + ".baseColorFactor");
            }
        }
        out.metallicFactor =
            clampedFactor(ctx, in.pbrMetallicRoughness.metallicFactor, 0.0, 1.0, pbr + ".metallicFactor");
        out.roughnessFactor =
            clampedFactor(ctx, in.pbrMetallicRoughness.roughnessFactor, 0.0, 1.0, pbr + ".roughnessFactor");
        out.baseColor = textureRef(ctx, in.pbrMetallicRoughness.baseColorTexture, pbr + ".baseColorTexture");
        out.metallicRoughness =
            textureRef(ctx, in.pbrMetallicRoughness.metallicRoughnessTexture, pbr + ".metallicRoughnessTexture");
        out.normal = textureRef(ctx, in.normalTexture, where + ".normalTexture");
        out.normal.scale =
            static_cast<float>(checkedNumber(ctx, in.normalTexture.scale, where + ".normalTexture.scale"));
        out.occlusion = textureRef(ctx, in.occlusionTexture, where + ".occlusionTexture");
        out.occlusion.scale =
            clampedFactor(ctx, in.occlusionTexture.strength, 0.0, 1.0, where + ".occlusionTexture.strength");
        out.emissive = textureRef(ctx, in.emissiveTexture, where + ".emissiveTexture");
        if (auto e = fixedArray(ctx, in.emissiveFactor, 3, where + ".emissiveFactor")) {
            for (int k = 0; k < 3; ++k) {
                out.emissiveFactor[k] =
                    clampedFactor(ctx, (*e)[static_cast<size_t>(k)], 0.0, 1.0, where + ".emissiveFactor");
            }
        }

        if (in.alphaMode == "OPAQUE")
            out.alphaMode = AlphaMode::Opaque;
        else if (in.alphaMode == "MASK")
            out.alphaMode = AlphaMode::Mask;
        else if (in.alphaMode == "BLEND")
            out.alphaMode = AlphaMode::Blend;
        else
            ctx.fail(where + ".alphaMode", "'" + in.alphaMode + "' (expected OPAQUE, MASK or BLEND)");
        if (checkedNumber(ctx, in.alphaCutoff, where + ".alphaCutoff") < 0.0)
            ctx.fail(where + ".alphaCutoff", "must be >= 0");
        out.alphaCutoff = static_cast<float>(in.alphaCutoff);
        out.doubleSided = in.doubleSided;

        const auto& ext = in.extensions;
        if (auto it = ext.find("KHR_materials_emissive_strength"); it != ext.end()) {
            const std::string at = where + ".extensions.KHR_materials_emissive_strength";
            const double strength = numberField(ctx, it->second, "emissiveStrength", at).value_or(1.0);
            if (strength < 0.0) ctx.fail(at + ".emissiveStrength", "negative");
            out.emissiveFactor *= static_cast<float>(strength);
        }
        if (auto it = ext.find("KHR_materials_diffuse_transmission"); it != ext.end()) {
            const std::string at = where + ".extensions.KHR_materials_diffuse_transmission";
            out.diffuseTransmissionFactor =
                clampedFactor(ctx, numberField(ctx, it->second, "diffuseTransmissionFactor", at).value_or(0.0), 0.0,
                              1.0, at + ".diffuseTransmissionFactor");
            // As PRESKIN_materials_skin's transmissionColor: a negative component is refused; above 1
            // (more light out than in) is clamped with a warning, as the factors are.
            glm::vec3 color =
                vec3Field(ctx, it->second, "diffuseTransmissionColorFactor", at).value_or(glm::vec3(1.0f));
            if (glm::any(glm::lessThan(color, glm::vec3(0.0f))))
                ctx.fail(at + ".diffuseTransmissionColorFactor", "negative component");
            if (glm::any(glm::greaterThan(color, glm::vec3(1.0f))))
                ctx.warn(at + ".diffuseTransmissionColorFactor",
                         fmt::format("({}, {}, {}) has components above 1; clamped", number(color.r), number(color.g),
                                     number(color.b)));
            out.diffuseTransmissionColor = glm::min(color, glm::vec3(1.0f));
            if (it->second.Has("diffuseTransmissionTexture") || it->second.Has("diffuseTransmissionColorTexture")) {
                ctx.warn(at, "transmission textures are not used; only the factors are read");
            }
        }
        if (auto it = ext.find("KHR_materials_volume"); it != ext.end()) {
            const std::string at = where + ".extensions.KHR_materials_volume";
            const double thickness = numberField(ctx, it->second, "thicknessFactor", at).value_or(0.0);
            if (thickness < 0.0) ctx.fail(at + ".thicknessFactor", "negative");
            if (thickness > 0.0) out.volumeThicknessFactor = static_cast<float>(thickness);
        }
        parseKhronosScatter(ctx, ext, where, out);
        if (auto it = ext.find("PRESKIN_materials_skin"); it != ext.end()) {
            out.skin = parseSkinExtension(ctx, it->second, where + ".extensions.PRESKIN_materials_skin",
                                          seededSkin(out, SkinMaterial{}));
        }
        ctx.scene->materials.push_back(std::move(out));
    }
    for (size_t i = 0; i < ctx.scene->materials.size(); ++i) applyKhronosScatter(*ctx.scene, i);
}

void applyKhronosScatter(Scene& scene, size_t index) {
    Material& material = scene.materials[index];
    if (!material.skin || !material.khronosScatter) return;
    const std::string where =
        scene.sourcePath.string() + ": " + indexed("materials", index) + " ('" + material.name + "')";
    if (material.skin->profile >= 0) {
        scene.warnings.push_back(where +
                                 ": the Khronos scatter parameters are not used: PRESKIN_materials_skin names " +
                                 "profile " + std::to_string(material.skin->profile));
        return;
    }
    try {
        const DiffusionProfile profile = profileFromKhronosScatter(*material.khronosScatter, "Khronos scatter");
        // Materials with the same parameters share one profile (one LUT layer, one bake).
        const std::string json = profile.toJson();
        auto same = std::find_if(scene.profiles.begin(), scene.profiles.end(), [&](const SkinProfile& p) {
            return p.profile && p.lutFolder.empty() && p.profile->toJson() == json;
        });
        if (same == scene.profiles.end()) {
            scene.profiles.push_back({material.name + " (Khronos scatter)", profile, {}});
            same = scene.profiles.end() - 1;
        }
        material.skin->profile = int(same - scene.profiles.begin());
    } catch (const Error& e) {
        scene.warnings.push_back(where + ": the Khronos scatter parameters define no profile (" + e.what() +
                                 "); the default profile is used");
    }
}

}  // namespace preskin::gltf
