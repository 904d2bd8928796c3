// glTF loading features, each checked against values computed here by hand: index widths and
// non-indexed primitives, normalized integer attributes, sparse accessors, strips and fans, flat
// normals, generated tangents (direction and handedness), node hierarchies (TRS and matrix),
// scene selection, KHR_texture_transform, materials and samplers, KHR_lights_punctual, cameras,
// images (PNG/JPEG, files, data URIs and GLB buffer views), PRESKIN_materials_skin and
// PRESKIN_environment.
#include "unit/GltfTestFiles.h"

#include <preskin/Error.h>
#include <preskin/Scene.h>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using nlohmann::json;

namespace preskin::test {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

bool hasWarning(const preskin::Scene& s, const std::string& text) {
    for (const auto& w : s.warnings)
        if (w.find(text) != std::string::npos) return true;
    return false;
}

// Two triangles (a unit quad in z = 0) with glTF-style UVs: u right, v down the image (= -y).
GltfBuilder quadScene(const std::vector<float>& uvs) {
    GltfBuilder b;
    const int position = b.addFloats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3");
    const int normal = b.addFloats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
    const int uv = b.addFloats(uvs, "VEC2");
    const int indices = b.addIndices(std::vector<uint16_t>{0, 1, 2, 0, 2, 3});
    b.addMeshNode(
        {{"attributes", {{"POSITION", position}, {"NORMAL", normal}, {"TEXCOORD_0", uv}}}, {"indices", indices}});
    return b;
}

}  // namespace

TEST(GltfLoading, TriangleFromGltfGlbAndDataUriAgree) {
    TempDir dir;
    GltfBuilder b = preskin::test::triangleScene();
    const auto fromGltf = preskin::Scene::load(b.writeGltf(dir.path(), "a"));
    const auto fromGlb = preskin::Scene::load(b.writeGlb(dir.path(), "b"));
    const auto fromData = preskin::Scene::load(b.writeEmbedded(dir.path(), "c"));
    for (const auto* s : {&fromGltf, &fromGlb, &fromData}) {
        EXPECT_TRUE(s->warnings.empty());
        ASSERT_EQ(s->meshes.size(), 1u);
        const auto& p = s->meshes[0].primitives.at(0);
        ASSERT_EQ(p.vertices.size(), 3u);
        EXPECT_EQ(p.indices, (std::vector<uint32_t>{0, 1, 2}));
        EXPECT_EQ(p.vertices[1].positionOs, glm::vec3(1, 0, 0));
        EXPECT_EQ(p.vertices[2].uv0, glm::vec2(0, 0));
        EXPECT_EQ(p.material, -1);
        EXPECT_EQ(p.boundsOs.max, glm::vec3(1, 1, 0));
        ASSERT_EQ(s->instances.size(), 1u);
    }
}

TEST(GltfLoading, AllIndexWidthsAndNonIndexed) {
    TempDir dir;
    const std::vector<uint32_t> expected = {0, 1, 2, 2, 1, 3};
    for (int width : {1, 2, 4, 0}) {
        GltfBuilder b;
        const int position = b.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0}, "VEC3");
        json primitive = {{"attributes", {{"POSITION", position}}}};
        if (width == 1) primitive["indices"] = b.addIndices(std::vector<uint8_t>{0, 1, 2, 2, 1, 3});
        if (width == 2) primitive["indices"] = b.addIndices(std::vector<uint16_t>{0, 1, 2, 2, 1, 3});
        if (width == 4) primitive["indices"] = b.addIndices(std::vector<uint32_t>{0, 1, 2, 2, 1, 3});
        if (width == 0) {  // non-indexed: six vertices
            b = GltfBuilder();
            const int pos6 = b.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0}, "VEC3");
            primitive = {{"attributes", {{"POSITION", pos6}}}};
        }
        b.addMeshNode(primitive);
        const auto s = preskin::Scene::load(b.writeGltf(dir.path(), std::string("w").append(std::to_string(width))));
        const auto& p = s.meshes[0].primitives.at(0);
        // No NORMAL: flat normals, three vertices per triangle, in triangle order.
        ASSERT_EQ(p.vertices.size(), 6u) << width;
        EXPECT_EQ(p.indices, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5}));
        const glm::vec3 corners[4] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
        for (size_t i = 0; i < 6; ++i) {
            EXPECT_EQ(p.vertices[i].positionOs, corners[expected[i]]) << "width " << width << " vertex " << i;
        }
    }
}

TEST(GltfLoading, MissingNormalsAreFlatFaceNormals) {
    TempDir dir;
    GltfBuilder b;
    // A tent: two triangles meeting at a ridge along y, tilted +-45 degrees.
    const int position = b.addFloats({-1, 0, 0, 0, 0, 1, 0, 1, 1, 1, 0, 0}, "VEC3");
    const int indices = b.addIndices(std::vector<uint16_t>{0, 1, 2, 1, 3, 2});
    b.addMeshNode({{"attributes", {{"POSITION", position}}}, {"indices", indices}});
    const auto s = preskin::Scene::load(b.writeGltf(dir.path()));
    const auto& p = s.meshes[0].primitives.at(0);
    ASSERT_EQ(p.vertices.size(), 6u);
    const float h = std::sqrt(0.5f);
    for (size_t i = 0; i < 3; ++i) {
        EXPECT_NEAR(glm::distance(p.vertices[i].normalOs, glm::vec3(-h, 0, h)), 0.0f, 1e-6f);
        EXPECT_NEAR(glm::distance(p.vertices[i + 3].normalOs, glm::vec3(h, 0, h)), 0.0f, 1e-6f);
    }
}

TEST(GltfLoading, NormalizedIntegerUvs) {
    TempDir dir;
    for (int type : {5121, 5123}) {
        GltfBuilder b;
        const int position = b.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
        int uv;
        if (type == 5121) {
            // byteStride 4: each 2-byte element padded to 4 bytes, as vertex attributes must be.
            uv = b.addAccessor(b.addView(std::vector<uint8_t>{0, 255, 0, 0, 255, 255, 0, 0, 0, 51, 0, 0}, 4), 5121, 3,
                               "VEC2", {{"normalized", true}});
        } else {
            uv = b.addAccessor(b.addView(std::vector<uint16_t>{0, 65535, 65535, 65535, 0, 13107}), 5123, 3, "VEC2",
                               {{"normalized", true}});
        }
        b.addMeshNode({{"attributes", {{"POSITION", position}, {"TEXCOORD_0", uv}}}});
        const auto s = preskin::Scene::load(b.writeGltf(dir.path()));
        const auto& v = s.meshes[0].primitives.at(0).vertices;
        EXPECT_NEAR(v[0].uv0.x, 0.0f, 1e-7f);
        EXPECT_NEAR(v[0].uv0.y, 1.0f, 1e-7f);
        EXPECT_NEAR(v[1].uv0.x, 1.0f, 1e-7f);
        EXPECT_NEAR(v[2].uv0.y, 0.2f, 1e-6f);  // 51/255 = 13107/65535 = 0.2
    }
}

TEST(GltfLoading, SparseAccessorOverridesValues) {
    TempDir dir;
    GltfBuilder b;
    const int base = b.addView(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0, 5, 5, 5});
    const int sparseIndices = b.addView(std::vector<uint16_t>{1, 3});
    const int sparseValues = b.addView(std::vector<float>{2, 0, 0, 1, 1, 0});
    const int position = b.addAccessor(base, 5126, 4, "VEC3",
                                       {{"sparse",
                                         {{"count", 2},
                                          {"indices", {{"bufferView", sparseIndices}, {"componentType", 5123}}},
                                          {"values", {{"bufferView", sparseValues}}}}}});
    const int indices = b.addIndices(std::vector<uint16_t>{0, 1, 3});
    b.addMeshNode({{"attributes", {{"POSITION", position}}}, {"indices", indices}});
    const auto s = preskin::Scene::load(b.writeGltf(dir.path()));
    const auto& v = s.meshes[0].primitives.at(0).vertices;  // flat: vertices 0, 1, 3
    EXPECT_EQ(v[0].positionOs, glm::vec3(0, 0, 0));
    EXPECT_EQ(v[1].positionOs, glm::vec3(2, 0, 0));
    EXPECT_EQ(v[2].positionOs, glm::vec3(1, 1, 0));
}

TEST(GltfLoading, StripsAndFansBecomeLists) {
    TempDir dir;
    for (int mode : {5, 6}) {
        GltfBuilder b;
        const int position = b.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 2, 0}, "VEC3");
        const int normal = b.addFloats(std::vector<float>(15, 0.0f), "VEC3");
        // Valid normals: +Z everywhere.
        b.doc["accessors"][static_cast<size_t>(normal)]["bufferView"] =
            b.addView(std::vector<float>{0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1});
        b.addMeshNode({{"attributes", {{"POSITION", position}, {"NORMAL", normal}}}, {"mode", mode}});
        const auto s = preskin::Scene::load(b.writeGltf(dir.path()));
        const auto& idx = s.meshes[0].primitives.at(0).indices;
        // glTF 2.0, 3.7.2.1: strip p_i = {v_i, v_{i+(1+i%2)}, v_{i+(2-i%2)}}; fan p_i = {v_{i+1}, v_{i+2}, v_0}.
        if (mode == 5)
            EXPECT_EQ(idx, (std::vector<uint32_t>{0, 1, 2, 1, 3, 2, 2, 3, 4}));
        else
            EXPECT_EQ(idx, (std::vector<uint32_t>{1, 2, 0, 2, 3, 0, 3, 4, 0}));
    }
}

TEST(GltfLoading, PointsAndLinesAreSkippedWithAWarning) {
    TempDir dir;
    GltfBuilder b = preskin::test::triangleScene();
    b.doc["meshes"][0]["primitives"].push_back({{"attributes", {{"POSITION", 0}}}, {"mode", 1}});
    const auto s = preskin::Scene::load(b.writeGltf(dir.path()));
    EXPECT_EQ(s.meshes[0].primitives.size(), 1u);
    EXPECT_TRUE(hasWarning(s, "meshes[0].primitives[1].mode"));
}

TEST(GltfLoading, GeneratedTangentsFollowUAndTheGltfHandedness) {
    TempDir dir;
    // glTF UVs: u along +x, v down the image (v = 0 at y = 1): bitangent (image up) = +y,
    // so T = +x and cross(N, T) * w = +y -> w = +1.
    auto s = preskin::Scene::load(quadScene({0, 1, 1, 1, 1, 0, 0, 0}).writeGltf(dir.path(), "a"));
    for (const auto& v : s.meshes[0].primitives[0].vertices) {
        EXPECT_NEAR(glm::distance(glm::vec3(v.tangentOs), glm::vec3(1, 0, 0)), 0.0f, 1e-5f);
        EXPECT_EQ(v.tangentOs.w, 1.0f);
    }
    // V mirrored (v grows up the quad): w flips.
    s = preskin::Scene::load(quadScene({0, 0, 1, 0, 1, 1, 0, 1}).writeGltf(dir.path(), "b"));
    for (const auto& v : s.meshes[0].primitives[0].vertices) {
        EXPECT_NEAR(glm::distance(glm::vec3(v.tangentOs), glm::vec3(1, 0, 0)), 0.0f, 1e-5f);
        EXPECT_EQ(v.tangentOs.w, -1.0f);
    }
    // U along +y (texture rotated): T = +y.
    s = preskin::Scene::load(quadScene({0, 0, 0, 1, 1, 1, 1, 0}).writeGltf(dir.path(), "c"));
    for (const auto& v : s.meshes[0].primitives[0].vertices) {
        EXPECT_NEAR(glm::distance(glm::vec3(v.tangentOs), glm::vec3(0, 1, 0)), 0.0f, 1e-5f);
    }
}

// Vertices whose UVs give no direction get an arbitrary orthonormal tangent; that is warned only
// where a tangent-space normal map would read it (a UV sphere's poles without one stay quiet).
TEST(GltfLoading, DegenerateUvsStillGiveAnOrthonormalFrame) {
    TempDir dir;
    GltfBuilder b = quadScene({0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f});
    const auto s = preskin::Scene::load(b.writeGltf(dir.path(), "plain"));
    for (const auto& v : s.meshes[0].primitives[0].vertices) {
        EXPECT_NEAR(glm::length(glm::vec3(v.tangentOs)), 1.0f, 1e-6f);
        EXPECT_NEAR(glm::dot(glm::vec3(v.tangentOs), v.normalOs), 0.0f, 1e-6f);
        EXPECT_TRUE(std::isfinite(v.tangentOs.w));
    }
    EXPECT_FALSE(hasWarning(s, "TEXCOORD_0")) << "no normal map reads the tangent";

    const std::vector<uint8_t> flat = preskin::test::encodeImage(dir.path(), "n.png", 1, 1, 3, {128, 128, 255});
    b.doc["images"] = json::array({{{"uri", "n.png"}}});
    b.doc["textures"] = json::array({{{"source", 0}}});
    b.doc["materials"] = json::array({{{"normalTexture", {{"index", 0}}}}});
    b.doc["meshes"][0]["primitives"][0]["material"] = 0;
    const auto mapped = preskin::Scene::load(b.writeGltf(dir.path(), "mapped"));
    EXPECT_TRUE(hasWarning(mapped, "attributes.TEXCOORD_0: 4 vertices have no usable UV direction"));
}

TEST(GltfLoading, GivenTangentsAreKeptAndOrthonormalised) {
    TempDir dir;
    GltfBuilder b = preskin::test::triangleScene();
    const int tangent = b.addFloats({2, 0, 0.1f, -1, 0, 3, 0, -1, 1, 0, 0, 1}, "VEC4");
    b.doc["meshes"][0]["primitives"][0]["attributes"]["TANGENT"] = tangent;
    const auto s = preskin::Scene::load(b.writeGltf(dir.path()));
    const auto& v = s.meshes[0].primitives[0].vertices;
    EXPECT_NEAR(glm::distance(v[0].tangentOs, glm::vec4(1, 0, 0, -1)), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::distance(v[1].tangentOs, glm::vec4(0, 1, 0, -1)), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::distance(v[2].tangentOs, glm::vec4(1, 0, 0, 1)), 0.0f, 1e-6f);
}

TEST(GltfLoading, NodeHierarchyWithTrsAndMatrix) {
    TempDir dir;
    GltfBuilder b = preskin::test::triangleScene();
    const float h = std::sqrt(0.5f);
    // Parent: T(1, 2, 3) * R(90 degrees about +Y) * S(2); child: matrix with translation (0, 0, 1).
    b.doc["nodes"] = json::array({
        {{"name", "parent"},
         {"translation", {1, 2, 3}},
         {"rotation", {0, h, 0, h}},
         {"scale", {2, 2, 2}},
         {"children", {1}}},
        {{"name", "child"}, {"mesh", 0}, {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1}}},
    });
    b.doc["scenes"] = json::array({{{"nodes", {0}}}});
    const auto s = preskin::Scene::load(b.writeGltf(dir.path()));
    ASSERT_EQ(s.instances.size(), 1u);
    EXPECT_EQ(s.instances[0].nodeName, "child");
    const glm::mat4& m = s.instances[0].worldFromObject;
    // R_y(90): x -> -z, z -> +x. Child origin: (1,2,3) + R * 2 * (0,0,1) = (3, 2, 3).
    auto apply = [&](glm::vec3 p) { return glm::vec3(m * glm::vec4(p, 1.0f)); };
    EXPECT_NEAR(glm::distance(apply({0, 0, 0}), glm::vec3(3, 2, 3)), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::distance(apply({1, 0, 0}), glm::vec3(3, 2, 1)), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::distance(apply({0, 1, 0}), glm::vec3(3, 4, 3)), 0.0f, 1e-5f);
    EXPECT_NEAR(s.instances[0].curvatureScale(), 2.0f, 1e-5f);
    // World bounds of the triangle (0,0,0), (1,0,0), (0,1,0).
    const preskin::Bounds wb = s.worldBounds();
    EXPECT_NEAR(glm::distance(wb.min, glm::vec3(3, 2, 1)), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::distance(wb.max, glm::vec3(3, 4, 3)), 0.0f, 1e-5f);
}

TEST(GltfLoading, SceneSelection) {
    TempDir dir;
    GltfBuilder b = preskin::test::triangleScene();
    b.doc["nodes"] = json::array(
        {{{"mesh", 0}, {"name", "a"}}, {{"mesh", 0}, {"name", "b"}}, {{"mesh", 0}, {"name", "c"}, {"children", {1}}}});
    b.doc["scenes"] = json::array({{{"nodes", {0}}}, {{"nodes", {2}}}});
    b.doc["scene"] = 1;
    auto s = preskin::Scene::load(b.writeGltf(dir.path(), "a"));
    ASSERT_EQ(s.instances.size(), 2u);
    EXPECT_EQ(s.instances[0].nodeName, "c");
    EXPECT_EQ(s.instances[1].nodeName, "b");
    b.doc.erase("scene");  // scene 0
    s = preskin::Scene::load(b.writeGltf(dir.path(), "b"));
    ASSERT_EQ(s.instances.size(), 1u);
    EXPECT_EQ(s.instances[0].nodeName, "a");
    b.doc.erase("scenes");  // all root nodes: a and c (b is c's child)
    s = preskin::Scene::load(b.writeGltf(dir.path(), "c"));
    ASSERT_EQ(s.instances.size(), 3u);
}

TEST(GltfLoading, TextureTransformMatchesTheSpecFormula) {
    TempDir dir;
    GltfBuilder b = preskin::test::triangleScene();
    const std::vector<uint8_t> png =
        preskin::test::encodeImage(dir.path(), "t.png", 2, 2, 3, std::vector<uint8_t>(12, 100));
    b.doc["images"] = json::array({{{"uri", "t.png"}}});
    b.doc["textures"] = json::array({{{"source", 0}}});
    b.doc["materials"] = json::array(
        {{{"pbrMetallicRoughness",
           {{"baseColorTexture",
             {{"index", 0},
              {"extensions",
               {{"KHR_texture_transform",
                 {{"offset", {0.25, -0.5}}, {"rotation", 0.3}, {"scale", {2.0, 3.0}}, {"texCoord", 1}}}}}}}}}}});
    b.doc["meshes"][0]["primitives"][0]["material"] = 0;
    const auto s = preskin::Scene::load(b.writeGltf(dir.path()));
    const preskin::TextureRef& t = s.materials.at(0).baseColor;
    EXPECT_EQ(t.uvOffset, glm::vec2(0.25f, -0.5f));
    EXPECT_FLOAT_EQ(t.uvRotation, 0.3f);
    EXPECT_EQ(t.uvScale, glm::vec2(2.0f, 3.0f));
    EXPECT_TRUE(hasWarning(s, "KHR_texture_transform.texCoord"));
    // KHR_texture_transform's reference shader: uv' = T * R * S * uv with
    // R = mat3(cos, sin, 0, -sin, cos, 0, 0, 0, 1) written column by column (GLSL).
    const glm::mat3 m = t.uvTransform();
    for (glm::vec2 uv : {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(0, 1), glm::vec2(0.3f, 0.7f)}) {
        const float c = std::cos(0.3f), sn = std::sin(0.3f);
        const glm::vec2 scaled(uv.x * 2.0f, uv.y * 3.0f);
        const glm::vec2 rotated(c * scaled.x + sn * scaled.y, -sn * scaled.x + c * scaled.y);
        const glm::vec2 expected = rotated + glm::vec2(0.25f, -0.5f);
        const glm::vec3 got = m * glm::vec3(uv, 1.0f);
        EXPECT_NEAR(got.x, expected.x, 1e-6f);
        EXPECT_NEAR(got.y, expected.y, 1e-6f);
        EXPECT_FLOAT_EQ(got.z, 1.0f);
    }
    // A quarter turn maps u to -v: (1, 0) -> (0, -1).
    preskin::TextureRef quarter;
    quarter.uvRotation = kPi / 2;
    const glm::vec3 q = quarter.uvTransform() * glm::vec3(1, 0, 1);
    EXPECT_NEAR(q.x, 0.0f, 1e-6f);
    EXPECT_NEAR(q.y, -1.0f, 1e-6f);
}

TEST(GltfLoading, MaterialsSamplersAndImages) {
    TempDir dir;
    GltfBuilder b = preskin::test::triangleScene();
    // 2x2 RGB PNG with known texels, a 1-channel JPEG, and a PNG inside the GLB / data URI.
    const std::vector<uint8_t> rgb = {255, 0, 0, 0, 255, 0, 0, 0, 255, 10, 20, 30};
    preskin::test::encodeImage(dir.path(), "c.png", 2, 2, 3, rgb);
    preskin::test::encodeImage(dir.path(), "g.jpg", 8, 8, 1, std::vector<uint8_t>(64, 128));
    const std::vector<uint8_t> embeddedPng = preskin::test::encodeImage(dir.path(), "e.png", 1, 1, 4, {1, 2, 3, 4});
    b.doc["images"] = json::array({{{"uri", "c.png"}},
                                   {{"uri", "g.jpg"}},
                                   {{"uri", "data:image/png;base64," + preskin::test::base64(embeddedPng)}}});
    b.doc["samplers"] = json::array(
        {{{"magFilter", 9728}, {"minFilter", 9986}, {"wrapS", 33071}, {"wrapT", 33648}}, {{"minFilter", 9729}}});
    b.doc["textures"] =
        json::array({{{"source", 0}, {"sampler", 0}}, {{"source", 1}, {"sampler", 1}}, {{"source", 2}}});
    b.doc["extensionsUsed"] = {"KHR_materials_emissive_strength"};
    b.doc["materials"] = json::array({{
        {"name", "m"},
        {"pbrMetallicRoughness",
         {{"baseColorFactor", {0.5, 0.25, 1.0, 0.75}},
          {"baseColorTexture", {{"index", 0}}},
          {"metallicFactor", 0.2},
          {"roughnessFactor", 0.6},
          {"metallicRoughnessTexture", {{"index", 1}}}}},
        {"normalTexture", {{"index", 2}, {"scale", 0.5}}},
        {"occlusionTexture", {{"index", 1}, {"strength", 0.25}}},
        {"emissiveTexture", {{"index", 0}}},
        {"emissiveFactor", {1.0, 0.5, 0.0}},
        {"alphaMode", "MASK"},
        {"alphaCutoff", 0.3},
        {"doubleSided", true},
        {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4.0}}}}},
    }});
    b.doc["meshes"][0]["primitives"][0]["material"] = 0;
    const auto s = preskin::Scene::load(b.writeGltf(dir.path()));
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();

    ASSERT_EQ(s.images.size(), 3u);
    EXPECT_EQ(s.images[0].name, "c.png");
    EXPECT_EQ(s.images[0].width, 2u);
    EXPECT_EQ(s.images[0].rgba8,
              (std::vector<uint8_t>{255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 10, 20, 30, 255}));
    EXPECT_EQ(s.images[1].width, 8u);
    EXPECT_NEAR(s.images[1].rgba8[0], 128, 2);  // grey JPEG: R = G = B, A = 255
    EXPECT_EQ(s.images[1].rgba8[0], s.images[1].rgba8[2]);
    EXPECT_EQ(s.images[1].rgba8[3], 255);
    EXPECT_EQ(s.images[2].rgba8, (std::vector<uint8_t>{1, 2, 3, 4}));

    ASSERT_EQ(s.samplers.size(), 2u);
    EXPECT_EQ(s.samplers[0].magFilter, preskin::Filter::Nearest);
    EXPECT_EQ(s.samplers[0].minFilter, preskin::Filter::Nearest);
    EXPECT_EQ(s.samplers[0].mipFilter, preskin::Filter::Linear);
    EXPECT_TRUE(s.samplers[0].mipmaps);
    EXPECT_EQ(s.samplers[0].wrapU, preskin::Wrap::ClampToEdge);
    EXPECT_EQ(s.samplers[0].wrapV, preskin::Wrap::MirroredRepeat);
    EXPECT_FALSE(s.samplers[1].mipmaps);
    EXPECT_EQ(s.samplers[1].magFilter, preskin::Filter::Linear);

    const preskin::Material& m = s.materials.at(0);
    EXPECT_EQ(m.name, "m");
    EXPECT_EQ(m.baseColorFactor, glm::vec4(0.5f, 0.25f, 1.0f, 0.75f));
    EXPECT_FLOAT_EQ(m.metallicFactor, 0.2f);
    EXPECT_FLOAT_EQ(m.roughnessFactor, 0.6f);
    EXPECT_EQ(m.baseColor.image, 0);
    EXPECT_EQ(m.baseColor.sampler, 0);
    EXPECT_EQ(m.metallicRoughness.image, 1);
    EXPECT_EQ(m.metallicRoughness.sampler, 1);
    EXPECT_EQ(m.normal.image, 2);
    EXPECT_EQ(m.normal.sampler, -1);
    EXPECT_FLOAT_EQ(m.normal.scale, 0.5f);
    EXPECT_FLOAT_EQ(m.occlusion.scale, 0.25f);
    EXPECT_EQ(m.emissiveFactor, glm::vec3(4.0f, 2.0f, 0.0f));
    EXPECT_EQ(m.alphaMode, preskin::AlphaMode::Mask);
    EXPECT_FLOAT_EQ(m.alphaCutoff, 0.3f);
    EXPECT_TRUE(m.doubleSided);
    EXPECT_FALSE(m.skin.has_value());

    // The same scene as .glb with the PNG in a buffer view.
    GltfBuilder g = preskin::test::triangleScene();
    const int view = g.addView(embeddedPng);
    g.doc["images"] = json::array({{{"bufferView", view}, {"mimeType", "image/png"}}});
    g.doc["textures"] = json::array({{{"source", 0}}});
    g.doc["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
    const auto sg = preskin::Scene::load(g.writeGlb(dir.path(), "g"));
    EXPECT_EQ(sg.images.at(0).rgba8, (std::vector<uint8_t>{1, 2, 3, 4}));
    EXPECT_EQ(sg.images.at(0).name, "images[0]");
}

TEST(GltfLoading, LightsAndShadowFlags) {
    TempDir dir;
    GltfBuilder b = preskin::test::triangleScene();
    const float h = std::sqrt(0.5f);
    b.doc["extensionsUsed"] = {"KHR_lights_punctual"};
    b.doc["extensions"]["KHR_lights_punctual"]["lights"] = json::array({
        {{"type", "point"}, {"color", {1, 0.5, 0.25}}, {"intensity", 20}, {"range", 4}},
        {{"type", "spot"}, {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.5}}}},
        {{"type", "directional"}, {"name", "sun"}},
        {{"type", "directional"}, {"name", "fill"}},
    });
    auto lightNode = [](int light, json extra) {
        extra["extensions"] = {{"KHR_lights_punctual", {{"light", light}}}};
        return extra;
    };
    b.doc["nodes"].push_back(lightNode(0, {{"translation", {1, 2, 3}}}));
    b.doc["nodes"].push_back(lightNode(1, {{"rotation", {-h, 0, 0, h}}}));  // -90 deg about x: -Z -> -Y
    b.doc["nodes"].push_back(lightNode(2, {{"rotation", {0, h, 0, h}}}));   // 90 deg about y: -Z -> -X
    b.doc["nodes"].push_back(lightNode(3, json::object()));
    b.doc["scenes"][0]["nodes"] = {0, 1, 2, 3, 4};
    auto s = preskin::Scene::load(b.writeGltf(dir.path(), "a"));
    ASSERT_EQ(s.lights.size(), 4u);
    EXPECT_EQ(s.lights[0].type, preskin::LightType::Point);
    EXPECT_EQ(s.lights[0].positionWs, glm::vec3(1, 2, 3));
    EXPECT_EQ(s.lights[0].color, glm::vec3(1, 0.5f, 0.25f));
    EXPECT_FLOAT_EQ(s.lights[0].intensity, 20.0f);
    EXPECT_FLOAT_EQ(s.lights[0].range, 4.0f);
    EXPECT_EQ(s.lights[1].type, preskin::LightType::Spot);
    EXPECT_FLOAT_EQ(s.lights[1].innerConeAngle, 0.2f);
    EXPECT_FLOAT_EQ(s.lights[1].outerConeAngle, 0.5f);
    EXPECT_NEAR(glm::distance(s.lights[1].directionWs, glm::vec3(0, -1, 0)), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::distance(s.lights[2].directionWs, glm::vec3(-1, 0, 0)), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::distance(s.lights[3].directionWs, glm::vec3(0, 0, -1)), 0.0f, 1e-6f);
    // No castsShadow anywhere: the first directional light casts.
    EXPECT_FALSE(s.lights[0].castsShadow);
    EXPECT_TRUE(s.lights[2].castsShadow);
    EXPECT_FALSE(s.lights[3].castsShadow);
    // An explicit flag wins: only "fill" casts.
    b.doc["extensions"]["KHR_lights_punctual"]["lights"][3]["extras"] = {{"castsShadow", true}};
    s = preskin::Scene::load(b.writeGltf(dir.path(), "b"));
    EXPECT_FALSE(s.lights[2].castsShadow);
    EXPECT_TRUE(s.lights[3].castsShadow);
    // Explicitly off everywhere: nothing casts.
    b.doc["extensions"]["KHR_lights_punctual"]["lights"][3]["extras"] = {{"castsShadow", false}};
    s = preskin::Scene::load(b.writeGltf(dir.path(), "c"));
    for (const auto& light : s.lights) EXPECT_FALSE(light.castsShadow);
}

TEST(GltfLoading, CamerasAreRigidAndKeepTheirProjection) {
    TempDir dir;
    GltfBuilder b = preskin::test::triangleScene();
    b.doc["cameras"] = json::array({
        {{"type", "perspective"},
         {"name", "p"},
         {"perspective", {{"yfov", 0.7}, {"znear", 0.1}, {"aspectRatio", 1.5}}}},
        {{"type", "orthographic"}, {"orthographic", {{"xmag", 2}, {"ymag", 1}, {"znear", 0.5}, {"zfar", 10}}}},
    });
    b.doc["nodes"].push_back({{"camera", 0}, {"translation", {0, 0, 5}}, {"scale", {3, 3, 3}}});
    b.doc["nodes"].push_back({{"camera", 1}, {"name", "ortho"}});
    b.doc["scenes"][0]["nodes"] = {0, 1, 2};
    const auto s = preskin::Scene::load(b.writeGltf(dir.path()));
    ASSERT_EQ(s.cameras.size(), 2u);
    const preskin::Camera& p = s.cameras[0];
    EXPECT_EQ(p.name, "p");
    EXPECT_FALSE(p.orthographic);
    EXPECT_FLOAT_EQ(p.yfov, 0.7f);
    EXPECT_FLOAT_EQ(p.aspectRatio, 1.5f);
    EXPECT_FLOAT_EQ(p.zfar, 0.0f);  // infinite
    EXPECT_EQ(p.worldFromView,
              glm::mat4(glm::vec4(1, 0, 0, 0), glm::vec4(0, 1, 0, 0), glm::vec4(0, 0, 1, 0), glm::vec4(0, 0, 5, 1)));
    const preskin::Camera& o = s.cameras[1];
    EXPECT_EQ(o.name, "ortho");
    EXPECT_TRUE(o.orthographic);
    EXPECT_FLOAT_EQ(o.xmag, 2.0f);
    EXPECT_FLOAT_EQ(o.zfar, 10.0f);
}

// A 16-bit PNG keeps its 16 bits (rgba16, for linear uses such as curvature maps) beside the
// 8-bit rounding; 8-bit images have no rgba16.
TEST(GltfLoading, SixteenBitPngsKeepTheirPrecision) {
    TempDir dir;
    GltfBuilder b = preskin::test::triangleScene();
    preskin::test::encodeImage(dir.path(), "grey16.png", 4, 1, 1, std::vector<uint16_t>{0, 1, 32768, 65535});
    preskin::test::encodeImage(dir.path(), "rgba16.png", 1, 1, 4, std::vector<uint16_t>{129, 383, 40000, 1000});
    preskin::test::encodeImage(dir.path(), "grey8.png", 1, 1, 1, {7});
    b.doc["images"] = json::array({{{"uri", "grey16.png"}}, {{"uri", "rgba16.png"}}, {{"uri", "grey8.png"}}});
    const auto s = preskin::Scene::load(b.writeGltf(dir.path()));
    ASSERT_EQ(s.images.size(), 3u);
    EXPECT_EQ(s.images[0].rgba16,
              (std::vector<uint16_t>{0, 0, 0, 65535, 1, 1, 1, 65535, 32768, 32768, 32768, 65535, 65535, 65535, 65535,
                                     65535}));
    // 8 bits: round(v * 255 / 65535)
    EXPECT_EQ(s.images[0].rgba8,
              (std::vector<uint8_t>{0, 0, 0, 255, 0, 0, 0, 255, 128, 128, 128, 255, 255, 255, 255, 255}));
    EXPECT_EQ(s.images[1].rgba16, (std::vector<uint16_t>{129, 383, 40000, 1000}));  // alpha straight, as stored
    EXPECT_EQ(s.images[1].rgba8, (std::vector<uint8_t>{1, 1, 156, 4}));
    EXPECT_TRUE(s.images[2].rgba16.empty());
    EXPECT_EQ(s.images[2].rgba8, (std::vector<uint8_t>{7, 7, 7, 255}));
}

TEST(GltfLoading, SkinExtensionAndKhrTransmission) {
    TempDir dir;
    GltfBuilder b = preskin::test::triangleScene();
    preskin::test::encodeImage(dir.path(), "s.png", 2, 2, 1, {0, 64, 128, 255});
    b.doc["images"] = json::array({{{"uri", "s.png"}}});
    b.doc["textures"] = json::array({{{"source", 0}}});
    b.doc["extensionsUsed"] = {"PRESKIN_materials_skin", "KHR_materials_diffuse_transmission", "KHR_materials_volume"};
    b.doc["materials"] = json::array({
        {{"name", "face"},
         {"extensions",
          {{"PRESKIN_materials_skin",
            {{"scatterScale", 2.0},
             {"curvatureSource", "texture"},
             {"curvatureTexture", {{"index", 0}}},
             {"curvatureTextureScalePerM", 50.0},
             {"normalLodBias", {1.5, 0.5, 0.0}},
             {"detailNormalTexture", {{"index", 0}, {"scale", 0.3}}},
             {"detailUvScale", 16.0},
             {"transmissionColor", {1.0, 0.3, 0.2}},
             {"specularIntensity", 0.8},
             {"specularTexture", {{"index", 0}}},
             {"lobeRoughness0", 0.5},
             {"lobeRoughness1", 1.5},
             {"lobeMix", 0.25}}},
           {"KHR_materials_diffuse_transmission",
            {{"diffuseTransmissionFactor", 0.4}, {"diffuseTransmissionColorFactor", {0.9, 0.1, 0.1}}}},
           {"KHR_materials_volume", {{"thicknessFactor", 0.02}}}}}},
        {{"name", "plain"},
         {"extensions", {{"KHR_materials_diffuse_transmission", {{"diffuseTransmissionFactor", 0.7}}}}}},
        {{"name", "other"}},
    });
    const auto path = b.writeGltf(dir.path());
    auto s = preskin::Scene::load(path);
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
    const preskin::SkinMaterial& k = s.materials.at(0).skin.value();
    EXPECT_FLOAT_EQ(k.scatterScale, 2.0f);
    EXPECT_EQ(k.curvatureSource, preskin::CurvatureSource::Texture);
    EXPECT_EQ(k.curvatureTexture.image, 0);
    EXPECT_FLOAT_EQ(k.curvatureTextureScalePerM, 50.0f);
    ASSERT_TRUE(k.normalLodBias.has_value());
    EXPECT_EQ(*k.normalLodBias, glm::vec3(1.5f, 0.5f, 0.0f));
    EXPECT_EQ(k.detailNormalTexture.image, 0);
    EXPECT_FLOAT_EQ(k.detailNormalScale, 0.3f);
    EXPECT_FLOAT_EQ(k.detailUvScale, 16.0f);
    EXPECT_FLOAT_EQ(k.transmission, 0.4f);                        // from KHR (not set in the extension)
    EXPECT_EQ(k.transmissionColor, glm::vec3(1.0f, 0.3f, 0.2f));  // the extension wins over KHR
    EXPECT_FLOAT_EQ(k.thicknessScale, 0.02f);                     // KHR_materials_volume
    EXPECT_FLOAT_EQ(k.specularIntensity, 0.8f);
    EXPECT_EQ(k.specularTexture.image, 0);
    EXPECT_FLOAT_EQ(k.lobeRoughness0, 0.5f);
    EXPECT_FLOAT_EQ(k.lobeRoughness1, 1.5f);
    EXPECT_FLOAT_EQ(k.lobeMix, 0.25f);

    // "plain" is not skin until makeSkin; then it gets the defaults seeded with its KHR values.
    EXPECT_FALSE(s.materials[1].skin.has_value());
    preskin::SkinMaterial defaults;
    defaults.scatterScale = 3.0f;
    s.makeSkin("plain", defaults);
    ASSERT_TRUE(s.materials[1].skin.has_value());
    EXPECT_FLOAT_EQ(s.materials[1].skin->transmission, 0.7f);
    EXPECT_FLOAT_EQ(s.materials[1].skin->scatterScale, 3.0f);
    EXPECT_FALSE(s.materials[2].skin.has_value());
    s.makeSkin("all");
    EXPECT_FLOAT_EQ(s.materials[0].skin->scatterScale, 2.0f);  // existing parameters kept
    EXPECT_TRUE(s.materials[2].skin.has_value());
    try {
        s.makeSkin("nose");
        FAIL() << "no error";
    } catch (const preskin::Error& e) {
        EXPECT_NE(std::string(e.what()).find("'nose'"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("scene.gltf"), std::string::npos) << e.what();
    }
}

TEST(GltfLoading, EnvironmentExtension) {
    TempDir dir;
    GltfBuilder b = preskin::test::triangleScene();
    std::filesystem::create_directory(dir / "env");
    preskin::test::writeText(dir / "env" / "sky.hdr", "#?RADIANCE\n");
    b.doc["extensionsUsed"] = {"PRESKIN_environment"};
    b.doc["extensions"]["PRESKIN_environment"] = {{"uri", "env/sky.hdr"}, {"intensity", 0.5}};
    const auto s = preskin::Scene::load(b.writeGltf(dir.path()));
    ASSERT_TRUE(s.environmentPath.has_value());
    EXPECT_TRUE(std::filesystem::equivalent(*s.environmentPath, dir / "env" / "sky.hdr"));
    EXPECT_TRUE(s.environmentPath->is_absolute());
    EXPECT_FLOAT_EQ(s.environmentIntensity, 0.5f);
}

TEST(GltfLoading, UnknownUsedExtensionsAndUnusedUnsupportedImagesOnlyWarn) {
    TempDir dir;
    GltfBuilder b = preskin::test::triangleScene();
    b.doc["extensionsUsed"] = {"KHR_materials_clearcoat"};
    preskin::test::writeBytes(dir / "x.gif", {'G', 'I', 'F', '8', '9', 'a', 1, 0, 1, 0, 0, 0, 0});
    b.doc["images"] = json::array({{{"uri", "x.gif"}}});
    const auto s = preskin::Scene::load(b.writeGltf(dir.path()));
    EXPECT_TRUE(hasWarning(s, "KHR_materials_clearcoat"));
    EXPECT_TRUE(hasWarning(s, "images[0]: GIF"));
    EXPECT_EQ(s.images.at(0).width, 0u);
}

}  // namespace preskin::test
