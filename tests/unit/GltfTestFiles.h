// Test helpers that write small glTF scenes: a temporary folder, a builder for the JSON document
// and its binary buffer (written as .gltf + .bin, as .glb, or embedded as a data URI), and PNG /
// JPEG encoding through OpenImageIO. Used by the glTF loader tests.
#pragma once

#include <preskin/Error.h>
#include <preskin/Scene.h>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace preskin::test {

namespace fs = std::filesystem;

class TempDir {
public:
    TempDir() {
        std::string pattern = (fs::temp_directory_path() / "preskin-gltf-XXXXXX").string();
        if (!mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
        path_ = pattern;
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(path_, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const fs::path& path() const { return path_; }
    fs::path operator/(const std::string& name) const { return path_ / name; }

private:
    fs::path path_;
};

inline void writeBytes(const fs::path& path, const std::vector<uint8_t>& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

inline void writeText(const fs::path& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
}

inline std::vector<uint8_t> readBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), {});
}

inline std::string base64(const std::vector<uint8_t>& data) {
    static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    size_t i = 0;
    for (; i + 2 < data.size(); i += 3) {
        const uint32_t v = (uint32_t(data[i]) << 16) | (uint32_t(data[i + 1]) << 8) | data[i + 2];
        for (int k = 3; k >= 0; --k) out += table[(v >> (6 * k)) & 63];
    }
    if (i < data.size()) {
        uint32_t v = uint32_t(data[i]) << 16;
        if (i + 1 < data.size()) v |= uint32_t(data[i + 1]) << 8;
        out += table[(v >> 18) & 63];
        out += table[(v >> 12) & 63];
        out += i + 1 < data.size() ? table[(v >> 6) & 63] : '=';
        out += '=';
    }
    return out;
}

// Encodes 8-bit (uint8_t) or 16-bit (uint16_t) pixels as PNG or JPEG (by the file extension of
// `name`; JPEG only at 8 bits) and returns the bytes.
template <typename T>
std::vector<uint8_t> encodeImage(const fs::path& dir, const std::string& name, int width, int height, int channels,
                                 const std::vector<T>& pixels) {
    static_assert(std::is_same_v<T, uint8_t> || std::is_same_v<T, uint16_t>);
    const OIIO::TypeDesc type = std::is_same_v<T, uint8_t> ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::UINT16;
    const fs::path path = dir / name;
    auto out = OIIO::ImageOutput::create(path.string());
    if (!out) throw std::runtime_error("no OIIO writer for " + name);
    OIIO::ImageSpec spec(width, height, channels, type);
    spec.attribute("oiio:UnassociatedAlpha", 1);  // the pixels are straight alpha: store them as given
    if (!out->open(path.string(), spec) || !out->write_image(type, pixels.data())) {
        throw std::runtime_error("cannot write " + name + ": " + out->geterror());
    }
    out->close();
    return readBytes(path);
}
inline std::vector<uint8_t> encodeImage(const fs::path& dir, const std::string& name, int width, int height,
                                        int channels, const std::vector<uint8_t>& pixels) {
    return encodeImage<uint8_t>(dir, name, width, height, channels, pixels);
}

// Loads `path`, expects a preskin::Error, returns its message.
inline std::string loadError(const fs::path& path) {
    try {
        preskin::Scene::load(path);
    } catch (const preskin::Error& e) {
        return e.what();
    } catch (const std::exception& e) {
        return std::string("unexpected exception type: ") + e.what();
    }
    return "no error";
}

// Expects loading `path` to fail with one line that starts with the file and holds every fragment.
template <typename Fragments>
void expectLoadError(const fs::path& path, const Fragments& fragments) {
    const std::string message = loadError(path);
    EXPECT_EQ(message.rfind(path.string() + ": ", 0), 0u) << "does not start with the file: " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line: " << message;
    for (const char* fragment : fragments) {
        EXPECT_NE(message.find(fragment), std::string::npos) << "'" << fragment << "' missing in: " << message;
    }
}

// A glTF document under construction plus its one binary buffer.
struct GltfBuilder {
    nlohmann::json doc = {{"asset", {{"version", "2.0"}}}};
    std::vector<uint8_t> bin;

    template <typename T>
    int addView(const std::vector<T>& data, int byteStride = 0) {
        while (bin.size() % 4) bin.push_back(0);
        const size_t offset = bin.size();
        const size_t bytes = data.size() * sizeof(T);
        bin.resize(offset + bytes);
        std::memcpy(bin.data() + offset, data.data(), bytes);
        nlohmann::json view = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}};
        if (byteStride) view["byteStride"] = byteStride;
        doc["bufferViews"].push_back(view);
        return static_cast<int>(doc["bufferViews"].size()) - 1;
    }

    int addAccessor(int view, int componentType, size_t count, const std::string& type,
                    const nlohmann::json& extra = nlohmann::json::object()) {
        nlohmann::json accessor = {{"componentType", componentType}, {"count", count}, {"type", type}};
        if (view >= 0) accessor["bufferView"] = view;
        for (auto it = extra.begin(); it != extra.end(); ++it) accessor[it.key()] = it.value();
        doc["accessors"].push_back(accessor);
        return static_cast<int>(doc["accessors"].size()) - 1;
    }

    static int components(const std::string& type) {
        return type == "SCALAR" ? 1 : type == "VEC2" ? 2 : type == "VEC3" ? 3 : 4;
    }

    int addFloats(const std::vector<float>& values, const std::string& type) {
        return addAccessor(addView(values), 5126, values.size() / static_cast<size_t>(components(type)), type);
    }

    template <typename T>
    int addIndices(const std::vector<T>& indices) {
        const int componentType = sizeof(T) == 1 ? 5121 : sizeof(T) == 2 ? 5123 : 5125;
        return addAccessor(addView(indices), componentType, indices.size(), "SCALAR");
    }

    // Adds mesh + node + (first) scene; returns the mesh index.
    int addMeshNode(const nlohmann::json& primitive, const nlohmann::json& node = nlohmann::json::object()) {
        doc["meshes"].push_back({{"primitives", nlohmann::json::array({primitive})}});
        const int mesh = static_cast<int>(doc["meshes"].size()) - 1;
        nlohmann::json n = node;
        n["mesh"] = mesh;
        doc["nodes"].push_back(n);
        if (!doc.contains("scenes")) doc["scenes"] = nlohmann::json::array({{{"nodes", nlohmann::json::array()}}});
        doc["scenes"][0]["nodes"].push_back(static_cast<int>(doc["nodes"].size()) - 1);
        return mesh;
    }

    fs::path writeGltf(const fs::path& dir, const std::string& name = "scene") {
        doc["buffers"] = nlohmann::json::array({{{"uri", name + ".bin"}, {"byteLength", bin.size()}}});
        writeBytes(dir / (name + ".bin"), bin);
        writeText(dir / (name + ".gltf"), doc.dump(1));
        return dir / (name + ".gltf");
    }

    fs::path writeEmbedded(const fs::path& dir, const std::string& name = "scene") {
        doc["buffers"] = nlohmann::json::array(
            {{{"uri", "data:application/octet-stream;base64," + base64(bin)}, {"byteLength", bin.size()}}});
        writeText(dir / (name + ".gltf"), doc.dump(1));
        return dir / (name + ".gltf");
    }

    std::vector<uint8_t> glbBytes() {
        doc["buffers"] = nlohmann::json::array({{{"byteLength", bin.size()}}});
        std::string json = doc.dump();
        while (json.size() % 4) json += ' ';
        std::vector<uint8_t> payload = bin;
        while (payload.size() % 4) payload.push_back(0);
        std::vector<uint8_t> out;
        auto u32 = [&](uint32_t v) {
            for (int k = 0; k < 4; ++k) out.push_back(static_cast<uint8_t>(v >> (8 * k)));
        };
        const auto total = static_cast<uint32_t>(12 + 8 + json.size() + (payload.empty() ? 0 : 8 + payload.size()));
        u32(0x46546C67);
        u32(2);
        u32(total);
        u32(static_cast<uint32_t>(json.size()));
        u32(0x4E4F534A);
        out.insert(out.end(), json.begin(), json.end());
        if (!payload.empty()) {
            u32(static_cast<uint32_t>(payload.size()));
            u32(0x004E4942);
            out.insert(out.end(), payload.begin(), payload.end());
        }
        return out;
    }

    fs::path writeGlb(const fs::path& dir, const std::string& name = "scene") {
        writeBytes(dir / (name + ".glb"), glbBytes());
        return dir / (name + ".glb");
    }
};

// One triangle in the z = 0 plane facing +Z with normals, TEXCOORD_0 and 16-bit indices:
// accessors 0 POSITION, 1 NORMAL, 2 TEXCOORD_0, 3 indices; mesh 0, node 0, scene 0.
inline GltfBuilder triangleScene() {
    GltfBuilder b;
    const int position = b.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
    const int normal = b.addFloats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
    const int uv = b.addFloats({0, 1, 1, 1, 0, 0}, "VEC2");
    const int indices = b.addIndices(std::vector<uint16_t>{0, 1, 2});
    b.addMeshNode(
        {{"attributes", {{"POSITION", position}, {"NORMAL", normal}, {"TEXCOORD_0", uv}}}, {"indices", indices}});
    return b;
}

}  // namespace preskin::test
