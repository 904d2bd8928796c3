// Bad glTF input: every case must throw exactly one preskin::Error whose one-line message names
// the file, the field or element, and the problem; none may crash, hang or read outside the
// scene's folder. The committed cases live in tests/data/gltf (made by make_test_files.py);
// more are generated here into a temporary folder.
#include "unit/GltfTestFiles.h"

#include <preskin/Error.h>
#include <preskin/Scene.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <limits>

using nlohmann::json;
namespace fs = std::filesystem;

namespace preskin::test {

namespace {

const fs::path kData = fs::path(PRESKIN_SOURCE_DIR) / "tests/data/gltf";

// CRC-32 as PNG chunks use it (ISO 3309, polynomial 0xEDB88320).
uint32_t crc32(const std::vector<uint8_t>& bytes) {
    uint32_t crc = 0xFFFFFFFFu;
    for (uint8_t byte : bytes) {
        crc ^= byte;
        for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return crc ^ 0xFFFFFFFFu;
}

void expectError(const fs::path& path, std::initializer_list<const char*> fragments) {
    const std::string message = loadError(path);
    EXPECT_EQ(message.rfind(path.string() + ": ", 0), 0u) << "does not start with the file: " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line: " << message;
    for (const char* fragment : fragments) {
        EXPECT_NE(message.find(fragment), std::string::npos) << "'" << fragment << "' missing in: " << message;
    }
}

}  // namespace

TEST(GltfErrors, CommittedValidTriangleLoads) {
    const auto s = preskin::Scene::load(kData / "triangle.gltf");
    EXPECT_EQ(s.meshes.at(0).primitives.at(0).vertices.size(), 3u);
}

struct CommittedCase {
    const char* file;
    std::vector<const char*> fragments;
};

class GltfErrorFiles : public ::testing::TestWithParam<CommittedCase> {};

TEST_P(GltfErrorFiles, NamesFileFieldAndProblem) {
    const CommittedCase& c = GetParam();
    const std::string message = loadError(kData / c.file);
    EXPECT_EQ(message.rfind((kData / c.file).string() + ": ", 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    for (const char* fragment : c.fragments)
        EXPECT_NE(message.find(fragment), std::string::npos) << fragment << " | " << message;
}

INSTANTIATE_TEST_SUITE_P(
    Committed, GltfErrorFiles,
    ::testing::Values(
        CommittedCase{"truncated.glb", {"GLB header length", "truncated"}},
        CommittedCase{"bad_magic.glb", {"GLB header magic"}},
        CommittedCase{"bad_chunk_length.glb", {"GLB chunk 0 length", "past the end"}},
        CommittedCase{"bad_json.gltf", {"JSON", "parse error"}},
        CommittedCase{"missing_buffer.gltf", {"buffers[0].uri", "'absent.bin' not found"}},
        CommittedCase{"missing_image.gltf", {"images[0].uri", "'absent.png' not found"}},
        CommittedCase{"required_extension.gltf",
                      {"extensionsRequired[0]", "KHR_draco_mesh_compression", "not supported"}},
        CommittedCase{"accessor_out_of_range.gltf", {"accessors[0]", "100 elements", "exceeds bufferViews[0]"}},
        CommittedCase{"bufferview_out_of_range.gltf", {"bufferViews[2]", "exceeds buffers[0] (104 bytes)"}},
        CommittedCase{"huge_count.gltf", {"accessors[0].count", "4294967295", "limit"}},
        CommittedCase{"index_out_of_range.gltf",
                      {"accessors[3]", "index 7", "vertex count 3", "meshes[0].primitives[0].indices"}},
        CommittedCase{"nan_position.gltf", {"accessors[0]", "nan is not a finite number", "element 1", "POSITION"}},
        CommittedCase{"uri_parent.gltf", {"buffers[0].uri", "leaves the scene's folder"}},
        CommittedCase{"uri_absolute.gltf", {"buffers[0].uri", "absolute path"}},
        CommittedCase{"uri_file_scheme.gltf", {"buffers[0].uri", "scheme"}},
        CommittedCase{"bad_image.gltf", {"images[0]", "cannot decode the PNG data"}},
        CommittedCase{"unsupported_image.gltf", {"baseColorTexture", "images[0] is GIF", "unsupported image format"}},
        CommittedCase{"node_cycle.gltf", {"nodes[0]", "cycle of children"}}),
    [](const ::testing::TestParamInfo<CommittedCase>& param) {
        std::string name = param.param.file;
        for (char& c : name)
            if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
        return name;
    });

TEST(GltfErrors, FileLevelProblems) {
    TempDir dir;
    expectError(dir / "absent.gltf", {"file: not found"});
    fs::create_directory(dir / "folder.gltf");
    expectError(dir / "folder.gltf", {"file: is a folder, not a glTF scene"});
    preskin::test::writeText(dir / "scene.obj", "v 0 0 0");
    expectError(dir / "scene.obj", {"unsupported file type '.obj'"});
    preskin::test::writeText(dir / "empty.gltf", "");
    expectError(dir / "empty.gltf", {"empty file"});
    preskin::test::writeText(dir / "array.gltf", "[1, 2, 3]");
    expectError(dir / "array.gltf", {"JSON", "not an object"});
    preskin::test::writeText(dir / "deep.gltf", std::string(100000, '[') + std::string(100000, ']'));
    expectError(dir / "deep.gltf", {"JSON", "nested deeper"});
    preskin::test::writeText(dir / "noasset.gltf", "{}");
    expectError(dir / "noasset.gltf", {"asset", "missing"});
    preskin::test::writeText(dir / "v1.gltf", R"({"asset": {"version": "1.0"}})");
    expectError(dir / "v1.gltf", {"asset.version", "'1.0'"});
    // A binary file named .gltf, and 11 bytes of a .glb.
    GltfBuilder b = preskin::test::triangleScene();
    preskin::test::writeBytes(dir / "binary.gltf", b.glbBytes());
    expectError(dir / "binary.gltf", {"binary glTF content"});
    preskin::test::writeBytes(dir / "short.glb", {'g', 'l', 'T', 'F', 2, 0, 0, 0, 0, 0, 0});
    expectError(dir / "short.glb", {"GLB header", "truncated"});
}

TEST(GltfErrors, GlbChunkProblems) {
    TempDir dir;
    GltfBuilder b = preskin::test::triangleScene();
    std::vector<uint8_t> glb = b.glbBytes();
    // Version 1.
    std::vector<uint8_t> v = glb;
    v[4] = 1;
    preskin::test::writeBytes(dir / "v.glb", v);
    expectError(dir / "v.glb", {"GLB header version", "1"});
    // Length field larger than the file.
    v = glb;
    v[8] = static_cast<uint8_t>(v[8] + 4);
    preskin::test::writeBytes(dir / "len.glb", v);
    expectError(dir / "len.glb", {"GLB header length", "truncated"});
    // BIN chunk length running past the end (header length adjusted to the file).
    v = glb;
    const uint32_t jsonLength = v[12] | (v[13] << 8) | (v[14] << 16) | (uint32_t(v[15]) << 24);
    const size_t binHeader = 20 + jsonLength;
    v[binHeader + 1] = 0x10;  // + 4096 bytes
    preskin::test::writeBytes(dir / "bin.glb", v);
    expectError(dir / "bin.glb", {"GLB chunk 1 length", "past the end"});
    // The buffer claims more bytes than the BIN chunk holds.
    GltfBuilder c = preskin::test::triangleScene();
    c.glbBytes();  // sets buffers[0] to the BIN chunk
    c.doc["buffers"][0]["byteLength"] = c.bin.size() + 64;
    std::string text = c.doc.dump();
    while (text.size() % 4) text += ' ';
    std::vector<uint8_t> rebuilt;
    auto u32 = [&](uint32_t x) {
        for (int k = 0; k < 4; ++k) rebuilt.push_back(static_cast<uint8_t>(x >> (8 * k)));
    };
    std::vector<uint8_t> payload = c.bin;
    while (payload.size() % 4) payload.push_back(0);
    u32(0x46546C67);
    u32(2);
    u32(static_cast<uint32_t>(12 + 8 + text.size() + 8 + payload.size()));
    u32(static_cast<uint32_t>(text.size()));
    u32(0x4E4F534A);
    rebuilt.insert(rebuilt.end(), text.begin(), text.end());
    u32(static_cast<uint32_t>(payload.size()));
    u32(0x004E4942);
    rebuilt.insert(rebuilt.end(), payload.begin(), payload.end());
    preskin::test::writeBytes(dir / "short_bin.glb", rebuilt);
    expectError(dir / "short_bin.glb", {"buffers[0].byteLength", "exceeds the GLB BIN chunk"});
}

TEST(GltfErrors, UrisThatLeaveTheFolderAreRefusedBeforeAnyRead) {
    TempDir outer;
    fs::create_directory(outer / "scene");
    GltfBuilder b = preskin::test::triangleScene();
    b.writeGltf(outer.path(), "outside");  // outside.bin exists one folder up: it must still be refused
    const fs::path dir = outer / "scene";
    const std::vector<std::pair<std::string, std::vector<const char*>>> cases = {
        {"../outside.bin", {"leaves the scene's folder"}},
        {"sub/../../outside.bin", {"leaves the scene's folder"}},
        {"%2e%2e/outside.bin", {"leaves the scene's folder", "after percent-decoding"}},
        {"..\\outside.bin", {"leaves the scene's folder"}},
        {(outer / "outside.bin").string(), {"absolute path"}},
        {"%2F" + (outer / "outside.bin").string().substr(1), {"absolute path", "after percent-decoding"}},
        {"file:" + (outer / "outside.bin").string(), {"scheme"}},
        {"file://localhost/etc/hostname", {"scheme"}},
        {"http://example.com/x.bin", {"scheme"}},
        {"C:/x.bin", {"scheme or drive"}},
        {"x%00.bin", {"NUL"}},
        {"", {"empty URI"}},
        {"data:text/html;base64,AAAA", {"unsupported data URI"}},
    };
    for (size_t i = 0; i < cases.size(); ++i) {
        GltfBuilder c = preskin::test::triangleScene();
        c.doc["buffers"] = json::array({{{"uri", cases[i].first}, {"byteLength", c.bin.size()}}});
        const fs::path file = dir / std::string("case").append(std::to_string(i)).append(".gltf");
        preskin::test::writeText(file, c.doc.dump());
        std::vector<const char*> fragments = cases[i].second;
        fragments.push_back("buffers[0].uri");
        const std::string message = loadError(file);
        for (const char* fragment : fragments) {
            EXPECT_NE(message.find(fragment), std::string::npos) << cases[i].first << " | " << message;
        }
    }
    // Images and the environment follow the same policy.
    GltfBuilder c = preskin::test::triangleScene();
    c.doc["images"] = json::array({{{"uri", "../outside.bin"}}});
    expectError(c.writeGltf(dir, "img"), {"images[0].uri", "leaves the scene's folder"});
    GltfBuilder e = preskin::test::triangleScene();
    e.doc["extensions"]["PRESKIN_environment"] = {{"uri", "/etc/hostname"}};
    expectError(e.writeGltf(dir, "env"), {"extensions.PRESKIN_environment.uri", "absolute path"});
    GltfBuilder m = preskin::test::triangleScene();
    m.doc["extensions"]["PRESKIN_environment"] = {{"uri", "sky.hdr"}};
    expectError(m.writeGltf(dir, "env2"), {"extensions.PRESKIN_environment.uri", "'sky.hdr' not found"});
}

TEST(GltfErrors, BufferSizeProblems) {
    TempDir dir;
    GltfBuilder b = preskin::test::triangleScene();
    b.writeGltf(dir.path(), "t");
    // External file shorter than byteLength.
    json doc = b.doc;
    doc["buffers"][0]["byteLength"] = b.bin.size() + 8;
    preskin::test::writeText(dir / "long.gltf", doc.dump());
    expectError(dir / "long.gltf", {"buffers[0].uri", "'t.bin' has", "truncated"});
    // Data URI size mismatch.
    doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + preskin::test::base64(b.bin);
    preskin::test::writeText(dir / "data.gltf", doc.dump());
    expectError(dir / "data.gltf", {"buffers[0].uri", "data URI holds"});
    // Absurd byteLength.
    doc["buffers"][0]["byteLength"] = 1ull << 40;
    preskin::test::writeText(dir / "huge.gltf", doc.dump());
    expectError(dir / "huge.gltf", {"buffers[0].byteLength", "exceeds the limit"});
    doc["buffers"][0]["byteLength"] = -5;
    preskin::test::writeText(dir / "neg.gltf", doc.dump());
    expectError(dir / "neg.gltf", {"buffers[0].byteLength", "negative"});
    // bufferView offset + length overflowing 64 bits.
    doc = b.doc;
    doc["bufferViews"][0]["byteOffset"] = std::numeric_limits<uint64_t>::max() - 2;
    preskin::test::writeText(dir / "overflow.gltf", doc.dump());
    expectError(dir / "overflow.gltf", {"bufferViews[0]", "exceeds buffers[0]"});
    doc = b.doc;
    doc["bufferViews"][0]["byteStride"] = 6;
    preskin::test::writeText(dir / "stride.gltf", doc.dump());
    expectError(dir / "stride.gltf", {"bufferViews[0].byteStride", "6"});
}

TEST(GltfErrors, AccessorAndIndexProblems) {
    TempDir dir;
    auto withChange = [&](const std::string& name, auto change) {
        GltfBuilder b = preskin::test::triangleScene();
        change(b);
        return b.writeGltf(dir.path(), name);
    };
    expectError(withChange("a", [](GltfBuilder& b) { b.doc["accessors"][0]["byteOffset"] = 4; }),
                {"accessors[0]", "byteOffset 4", "exceeds bufferViews[0] (36 bytes)"});
    expectError(withChange("b", [](GltfBuilder& b) { b.doc["accessors"][0]["type"] = "VEC2"; }),
                {"accessors[0].type", "VEC2", "POSITION needs VEC3"});
    expectError(withChange("c", [](GltfBuilder& b) { b.doc["accessors"][3]["componentType"] = 5126; }),
                {"accessors[3].componentType", "FLOAT", "indices"});
    expectError(withChange("d", [](GltfBuilder& b) { b.doc["accessors"][1]["count"] = 2; }),
                {"attributes.NORMAL", "2 elements, POSITION has 3"});
    expectError(withChange("e", [](GltfBuilder& b) { b.doc["accessors"][0]["count"] = 0; }),
                {"accessors[0].count", "0"});
    expectError(withChange("f", [](GltfBuilder& b) { b.doc["meshes"][0]["primitives"][0]["indices"] = 9; }),
                {"meshes[0].primitives[0].indices", "9 is out of range"});
    expectError(
        withChange("g", [](GltfBuilder& b) { b.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 42; }),
        {"attributes.POSITION", "42 is out of range"});
    expectError(
        withChange("h", [](GltfBuilder& b) { b.doc["meshes"][0]["primitives"][0]["attributes"].erase("POSITION"); }),
        {"meshes[0].primitives[0].attributes", "no POSITION"});
    expectError(withChange("i", [](GltfBuilder& b) { b.doc["meshes"][0]["primitives"][0]["mode"] = 9; }),
                {"meshes[0].primitives[0].mode", "9"});
    {
        // Valid glTF (a validator warning): the trailing indices are ignored, here leaving no triangle.
        const fs::path j = withChange("j", [](GltfBuilder& b) { b.doc["accessors"][3]["count"] = 2; });
        const preskin::Scene scene = preskin::Scene::load(j);
        std::string warnings;
        for (const std::string& w : scene.warnings) warnings += w + "\n";
        EXPECT_NE(warnings.find(j.string() +
                                ": meshes[0].primitives[0].indices: index count 2 is not a multiple of 3 for a "
                                "triangle list; the last 2 ignored"),
                  std::string::npos)
            << warnings;
        EXPECT_NE(warnings.find("meshes[0].primitives[0]: no triangles; primitive skipped"), std::string::npos)
            << warnings;
    }
    expectError(withChange("k", [](GltfBuilder& b) { b.doc["accessors"][0]["bufferView"] = 17; }),
                {"accessors[0].bufferView", "17 is out of range"});
    // Non-finite normals and UVs.
    expectError(withChange("l",
                           [](GltfBuilder& b) {
                               const float inf = std::numeric_limits<float>::infinity();
                               b.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] =
                                   b.addFloats({0, 0, 1, 0, inf, 1, 0, 0, 1}, "VEC3");
                           }),
                {"inf is not a finite number", "element 1", "NORMAL"});
    expectError(withChange("m",
                           [](GltfBuilder& b) {
                               const float nan = std::numeric_limits<float>::quiet_NaN();
                               b.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] =
                                   b.addFloats({0, 0, 1, 0, 0, nan}, "VEC2");
                           }),
                {"nan is not a finite number", "element 2", "TEXCOORD_0"});
    // Sparse substitutions out of range and unordered.
    auto sparse = [](std::vector<uint16_t> indices) {
        return [indices](GltfBuilder& b) {
            const int iv = b.addView(indices);
            const int vv = b.addView(std::vector<float>(indices.size() * 3, 0.5f));
            b.doc["accessors"][0]["sparse"] = {{"count", indices.size()},
                                               {"indices", {{"bufferView", iv}, {"componentType", 5123}}},
                                               {"values", {{"bufferView", vv}}}};
        };
    };
    expectError(withChange("n", sparse({5})), {"accessors[0].sparse.indices", "5 >= the accessor's count 3"});
    expectError(withChange("o", sparse({2, 1})), {"accessors[0].sparse.indices", "not greater"});
}

TEST(GltfErrors, ReferenceProblems) {
    TempDir dir;
    auto withChange = [&](const std::string& name, auto change) {
        GltfBuilder b = preskin::test::triangleScene();
        change(b);
        return b.writeGltf(dir.path(), name);
    };
    expectError(withChange("a", [](GltfBuilder& b) { b.doc["meshes"][0]["primitives"][0]["material"] = 3; }),
                {"meshes[0].primitives[0].material", "3 is out of range"});
    expectError(
        withChange(
            "b",
            [](GltfBuilder& b) {
                b.doc["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 4}}}}}}});
            }),
        {"materials[0].pbrMetallicRoughness.baseColorTexture.index", "4 is out of range"});
    expectError(withChange("c", [](GltfBuilder& b) { b.doc["scene"] = 5; }), {"scene", "5 is out of range"});
    // Values of the extensions preskin reads that a JSON reader would drop or wrap: null, an empty
    // array, an integer beyond 32 bits (4294967297 would read as 1).
    const std::pair<json, const char*> dropped[] = {{json(), "null is not a value"},
                                                    {json::array(), "an empty array is not a value"},
                                                    {json(4294967297LL), "4294967297 is out of range for an integer"}};
    for (const auto& entry : dropped) {
        const json& value = entry.first;
        expectError(withChange("x",
                               [&](GltfBuilder& b) {
                                   b.doc["extensionsUsed"] = {"PRESKIN_materials_skin"};
                                   b.doc["materials"] = json::array(
                                       {{{"extensions", {{"PRESKIN_materials_skin", {{"profile", value}}}}}}});
                               }),
                    {"materials[0].extensions.PRESKIN_materials_skin.profile", entry.second});
    }
    expectError(withChange("d", [](GltfBuilder& b) { b.doc["nodes"][0]["children"] = {7}; }),
                {"nodes[0].children[0]", "7 is out of range"});
    expectError(withChange("e", [](GltfBuilder& b) { b.doc["nodes"][0]["mesh"] = 2; }),
                {"nodes[0].mesh", "2 is out of range"});
    expectError(withChange("f",
                           [](GltfBuilder& b) {
                               b.doc["scenes"][0]["nodes"] = {0, 0};
                           }),
                {"nodes[0]", "reached twice"});
    expectError(withChange("g",
                           [](GltfBuilder& b) {
                               b.doc["nodes"][0]["rotation"] = {0, 0, 0, 0};
                           }),
                {"nodes[0].rotation", "zero-length quaternion"});
    expectError(withChange("h",
                           [](GltfBuilder& b) {
                               b.doc["nodes"][0]["matrix"] = {1, 0, 0};
                           }),
                {"nodes[0].matrix", "3 numbers, expected 16"});
    expectError(withChange("i",
                           [](GltfBuilder& b) {
                               b.doc["nodes"][0]["extensions"] = {{"KHR_lights_punctual", {{"light", 0}}}};
                           }),
                {"nodes[0].extensions.KHR_lights_punctual.light", "0 is out of range"});
    expectError(withChange("j",
                           [](GltfBuilder& b) {
                               b.doc["extensions"]["KHR_lights_punctual"]["lights"] = {
                                   {{"type", "spot"}, {"spot", {{"innerConeAngle", 1.0}, {"outerConeAngle", 0.5}}}}};
                               b.doc["nodes"][0]["extensions"] = {{"KHR_lights_punctual", {{"light", 0}}}};
                           }),
                {"extensions.KHR_lights_punctual.lights[0].spot", "cone angles inner 1, outer 0.5"});
    expectError(
        withChange("k",
                   [](GltfBuilder& b) {
                       b.doc["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.0}}}}};
                       b.doc["nodes"][0]["camera"] = 0;
                   }),
        {"cameras[0].perspective.znear"});
    expectError(withChange("l",
                           [](GltfBuilder& b) {
                               b.doc["samplers"] = {{{"wrapS", 1234}}};
                           }),
                {"samplers[0].wrapS", "1234"});
    expectError(
        withChange("m",
                   [](GltfBuilder& b) {
                       b.doc["materials"] = {{{"extensions", {{"PRESKIN_materials_skin", {{"lobeMix", 2.0}}}}}}};
                   }),
        {"materials[0].extensions.PRESKIN_materials_skin.lobeMix", "2 is outside [0, 1]"});
    expectError(
        withChange(
            "n",
            [](GltfBuilder& b) {
                b.doc["materials"] = {{{"extensions", {{"PRESKIN_materials_skin", {{"curvatureSource", "texture"}}}}}}};
            }),
        {"PRESKIN_materials_skin.curvatureSource", "no usable curvatureTexture"});
    expectError(
        withChange(
            "o",
            [](GltfBuilder& b) {
                b.doc["materials"] = {{{"extensions", {{"PRESKIN_materials_skin", {{"transmissionColor", {1, 0}}}}}}}};
            }),
        {"PRESKIN_materials_skin.transmissionColor", "array of 3 numbers"});
    expectError(withChange("p",
                           [](GltfBuilder& b) {
                               b.doc["materials"] = {{{"alphaMode", "CUTOUT"}}};
                           }),
                {"materials[0].alphaMode", "'CUTOUT'"});
}

TEST(GltfErrors, ImageProblems) {
    TempDir dir;
    // A truncated JPEG file referenced by URI.
    const std::vector<uint8_t> jpeg =
        preskin::test::encodeImage(dir.path(), "full.jpg", 64, 64, 3, std::vector<uint8_t>(64 * 64 * 3, 90));
    preskin::test::writeBytes(
        dir / "cut.jpg",
        std::vector<uint8_t>(jpeg.begin(), jpeg.begin() + static_cast<std::ptrdiff_t>(jpeg.size() / 2)));
    GltfBuilder b = preskin::test::triangleScene();
    b.doc["images"] = json::array({{{"uri", "cut.jpg"}}});
    expectError(b.writeGltf(dir.path(), "cut"), {"images[0] ('cut.jpg')", "cannot decode the JPEG data"});
    // A PNG whose header claims an absurd size.
    std::vector<uint8_t> png = preskin::test::encodeImage(dir.path(), "p.png", 2, 2, 3, std::vector<uint8_t>(12, 1));
    // IHDR width and height (big endian at 16..19 and 20..23) = 20000: 400 million pixels.
    for (size_t at : {size_t(16), size_t(20)}) {
        png[at] = 0;
        png[at + 1] = 0;
        png[at + 2] = 0x4E;
        png[at + 3] = 0x20;
    }
    const uint32_t crc = crc32(std::vector<uint8_t>(png.begin() + 12, png.begin() + 29));  // IHDR type + data
    for (int k = 0; k < 4; ++k) png[static_cast<size_t>(29 + k)] = static_cast<uint8_t>(crc >> (24 - 8 * k));
    preskin::test::writeBytes(dir / "big.png", png);
    GltfBuilder c = preskin::test::triangleScene();
    c.doc["images"] = json::array({{{"uri", "big.png"}}});
    expectError(c.writeGltf(dir.path(), "big"), {"images[0] ('big.png')", "20000 x 20000 pixels exceeds the limit"});
    // A WebP image used by a material.
    preskin::test::writeBytes(dir / "x.webp", {'R', 'I', 'F', 'F', 0, 0, 0, 0, 'W', 'E', 'B', 'P', 'V', 'P', '8', ' '});
    GltfBuilder d = preskin::test::triangleScene();
    d.doc["images"] = json::array({{{"uri", "x.webp"}}});
    d.doc["textures"] = json::array({{{"source", 0}}});
    d.doc["materials"] = json::array({{{"normalTexture", {{"index", 0}}}}});
    expectError(d.writeGltf(dir.path(), "webp"),
                {"materials[0].normalTexture", "images[0] is WebP", "unsupported image format"});
}

TEST(GltfErrors, RandomCorruptionOnlyEverThrowsPreskinErrors) {
    // Deterministic byte flips and truncations of a valid .glb and .gltf: every load either
    // succeeds or throws preskin::Error naming the file; nothing else escapes, nothing crashes.
    TempDir dir;
    GltfBuilder b = preskin::test::triangleScene();
    const std::vector<uint8_t> png =
        preskin::test::encodeImage(dir.path(), "i.png", 2, 2, 4, std::vector<uint8_t>(16, 7));
    const int view = b.addView(png);
    b.doc["images"] = json::array({{{"bufferView", view}, {"mimeType", "image/png"}}});
    b.doc["textures"] = json::array({{{"source", 0}}});
    b.doc["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
    b.doc["meshes"][0]["primitives"][0]["material"] = 0;
    const std::vector<uint8_t> glb = b.glbBytes();
    b.writeGltf(dir.path(), "base");  // base.bin for the .gltf variants
    const std::string text = b.doc.dump();
    uint64_t state = 0x9E3779B97F4A7C15ull;
    auto next = [&]() {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        return state;
    };
    int loaded = 0, rejected = 0;
    for (int round = 0; round < 400; ++round) {
        const bool binary = round % 2 == 0;
        std::vector<uint8_t> bytes = binary ? glb : std::vector<uint8_t>(text.begin(), text.end());
        const int flips = 1 + static_cast<int>(next() % 4);
        for (int f = 0; f < flips; ++f) bytes[next() % bytes.size()] = static_cast<uint8_t>(next());
        if (next() % 4 == 0) bytes.resize(next() % bytes.size());
        std::string name = "r";
        name.append(std::to_string(round)).append(binary ? ".glb" : ".gltf");
        const fs::path path = dir / name;
        preskin::test::writeBytes(path, bytes);
        try {
            preskin::Scene::load(path);
            ++loaded;
        } catch (const preskin::Error& e) {
            ++rejected;
            EXPECT_EQ(std::string(e.what()).rfind(path.string() + ": ", 0), 0u) << e.what();
        } catch (const std::exception& e) {
            ADD_FAILURE() << "round " << round << ": " << e.what();
        }
    }
    EXPECT_GT(rejected, 100);
    EXPECT_EQ(loaded + rejected, 400);
}

}  // namespace preskin::test
