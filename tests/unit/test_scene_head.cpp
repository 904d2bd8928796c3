// Loads the bundled sample scene (samples/assets/head) and checks it against independent facts:
// the source scan's counts and bounds (LeePerrySmith.glb: 9,279 vertices, 17,684 triangles,
// bounds +-4.2763 x +-3.9725 x +-2.5904 units) times the documented 0.048 m per unit, the JPEG
// sizes, the tangent frames, and the V flip (the lips, the brightest part of Map-SPEC.jpg, must
// land on the mouth of the mesh).
#include <preskin/Scene.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace preskin::test {

namespace {

const std::filesystem::path kHead = std::filesystem::path(PRESKIN_SOURCE_DIR) / "samples/assets/head/head.gltf";
constexpr float kMetresPerUnit = 0.048f;

const preskin::Scene& head() {
    static const preskin::Scene scene = preskin::Scene::load(kHead);
    return scene;
}

}  // namespace

TEST(SceneHead, CountsAndBoundsInMetres) {
    const preskin::Scene& s = head();
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
    ASSERT_EQ(s.meshes.size(), 1u);
    ASSERT_EQ(s.meshes[0].primitives.size(), 1u);
    const preskin::Primitive& p = s.meshes[0].primitives[0];
    EXPECT_EQ(p.vertices.size(), 9279u);
    EXPECT_EQ(p.indices.size(), 17684u * 3u);
    EXPECT_EQ(p.material, 0);
    ASSERT_EQ(s.instances.size(), 1u);
    EXPECT_EQ(s.instances[0].worldFromObject, glm::mat4(1.0f));

    const preskin::Bounds b = s.worldBounds();
    const glm::vec3 expectedMax =
        kMetresPerUnit * glm::vec3(4.276320934295654f, 3.9725468158721924f, 2.5903584957122803f);
    const glm::vec3 expectedMin =
        kMetresPerUnit * glm::vec3(-4.276320934295654f, -3.9725465774536133f, -2.5903775691986084f);
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(b.max[k], expectedMax[k], 1e-5f);
        EXPECT_NEAR(b.min[k], expectedMin[k], 1e-5f);
    }
    // A bust in metres: about 0.4 m tall (head and shoulders), face toward +Z.
    EXPECT_GT(b.extent().y, 0.3f);
    EXPECT_LT(b.extent().y, 0.5f);
}

TEST(SceneHead, TexturesDecodedAtTheirSizes) {
    const preskin::Scene& s = head();
    ASSERT_EQ(s.images.size(), 3u);
    for (const preskin::Image& image : s.images) {
        EXPECT_EQ(image.width, 1024u) << image.name;
        EXPECT_EQ(image.height, 1024u) << image.name;
        EXPECT_EQ(image.rgba8.size(), 1024u * 1024u * 4u) << image.name;
    }
    ASSERT_EQ(s.materials.size(), 1u);
    const preskin::Material& m = s.materials[0];
    EXPECT_EQ(m.name, "skin");
    EXPECT_EQ(s.images[static_cast<size_t>(m.baseColor.image)].name, "Map-COL.jpg");
    EXPECT_EQ(s.images[static_cast<size_t>(m.normal.image)].name, "Infinite-Level_02_Tangent_SmoothUV.jpg");
    ASSERT_TRUE(m.skin.has_value());
    ASSERT_TRUE(m.skin->specularTexture.valid());
    EXPECT_EQ(s.images[static_cast<size_t>(m.skin->specularTexture.image)].name, "Map-SPEC.jpg");
    EXPECT_FLOAT_EQ(m.roughnessFactor, 0.45f);
    EXPECT_FLOAT_EQ(m.metallicFactor, 0.0f);
    EXPECT_EQ(m.skin->curvatureSource, preskin::CurvatureSource::Vertex);

    // The base colour map is skin-toned on average (red > green > blue).
    const preskin::Image& col = s.images[static_cast<size_t>(m.baseColor.image)];
    double sum[3] = {0, 0, 0};
    for (size_t i = 0; i < col.rgba8.size(); i += 4)
        for (size_t c = 0; c < 3; ++c) sum[c] += col.rgba8[i + c];
    EXPECT_GT(sum[0], sum[1]);
    EXPECT_GT(sum[1], sum[2]);
    // The normal map points mostly out of the surface (blue high).
    const preskin::Image& nrm = s.images[static_cast<size_t>(m.normal.image)];
    double blue = 0;
    for (size_t i = 0; i < nrm.rgba8.size(); i += 4) blue += nrm.rgba8[i + 2];
    EXPECT_GT(blue / (1024.0 * 1024.0), 200.0);
}

TEST(SceneHead, TangentFramesAreOrthonormal) {
    const preskin::Primitive& p = head().meshes[0].primitives[0];
    size_t negative = 0;
    for (const preskin::Vertex& v : p.vertices) {
        const glm::vec3 t(v.tangentOs);
        ASSERT_NEAR(glm::length(v.normalOs), 1.0f, 1e-4f);
        ASSERT_NEAR(glm::length(t), 1.0f, 1e-4f);
        ASSERT_NEAR(glm::dot(t, v.normalOs), 0.0f, 1e-4f);
        ASSERT_TRUE(v.tangentOs.w == 1.0f || v.tangentOs.w == -1.0f);
        negative += v.tangentOs.w < 0.0f;
    }
    // Mirrored UVs (w = -1) only where the layout mirrors: the eyeballs (the circles in the top
    // corners of the image, v < 0.1) and the bust's bottom cap (v > 0.85).
    size_t mirroredWhereExpected = 0;
    for (const preskin::Vertex& v : p.vertices) {
        if (v.tangentOs.w < 0.0f && (v.uv0.y < 0.1f || v.uv0.y > 0.85f)) ++mirroredWhereExpected;
    }
    EXPECT_GT(negative, 0u);
    EXPECT_GE(mirroredWhereExpected, negative * 95 / 100);
    // On the face (the centre of the image, facing +Z), u grows toward +x: the image's left-right
    // is the head's right-left seen from the front, and the frame is right-handed (w = +1).
    size_t total = 0, alongX = 0, rightHanded = 0;
    for (const preskin::Vertex& v : p.vertices) {
        if (v.uv0.x > 0.25f && v.uv0.x < 0.75f && v.uv0.y > 0.15f && v.uv0.y < 0.75f && v.normalOs.z > 0.7f) {
            ++total;
            alongX += v.tangentOs.x > 0.5f;
            rightHanded += v.tangentOs.w > 0.0f;
        }
    }
    ASSERT_GT(total, 1000u);
    EXPECT_GE(alongX, total * 95 / 100);
    EXPECT_GE(rightHanded, total * 99 / 100);
}

TEST(SceneHead, VFlipPutsTheLipsOnTheMouth) {
    const preskin::Scene& s = head();
    const preskin::Primitive& p = s.meshes[0].primitives[0];
    const preskin::Image& spec = s.images[static_cast<size_t>(s.materials[0].skin->specularTexture.image)];
    auto texel = [&](glm::vec2 uv) {
        const auto x = std::min<uint32_t>(spec.width - 1, static_cast<uint32_t>(uv.x * static_cast<float>(spec.width)));
        const auto y =
            std::min<uint32_t>(spec.height - 1, static_cast<uint32_t>(uv.y * static_cast<float>(spec.height)));
        return spec.rgba8[(size_t(y) * spec.width + x) * 4];
    };
    // glTF UVs: (0, 0) is the image's top-left texel. The lips are pure white in the spec map.
    const preskin::Vertex* noseTip = &p.vertices[0];
    for (const preskin::Vertex& v : p.vertices)
        if (v.positionOs.z > noseTip->positionOs.z) noseTip = &v;
    size_t bright = 0, onMouth = 0;
    for (const preskin::Vertex& v : p.vertices) {
        if (texel(v.uv0) < 250) continue;
        ++bright;
        // The mouth: below the nose tip, above the chin, on the front, near the midline.
        const glm::vec3 q = v.positionOs;
        onMouth += q.y < noseTip->positionOs.y - 0.01f && q.y > noseTip->positionOs.y - 0.06f && q.z > 0.08f &&
            std::abs(q.x) < 0.04f;
    }
    EXPECT_GT(bright, 200u);
    EXPECT_GT(onMouth, bright * 95 / 100);
    // The nose tip sits between the eyes (v ~ 0.29) and the mouth (v ~ 0.47) in the image.
    EXPECT_GT(noseTip->uv0.y, 0.3f);
    EXPECT_LT(noseTip->uv0.y, 0.45f);
}

TEST(SceneHead, CurvatureIsHeadSized) {
    const preskin::Primitive& p = head().meshes[0].primitives[0];
    std::vector<float> k;
    size_t concave = 0;
    for (const preskin::Vertex& v : p.vertices) {
        ASSERT_TRUE(std::isfinite(v.curvaturePerM));
        k.push_back(std::abs(v.curvaturePerM));
        concave += v.curvaturePerM < 0.0f;
    }
    // Signed: mostly convex, with concave folds (eye sockets, ears, nostrils, the neck's crease).
    EXPECT_GT(concave, k.size() / 20);
    EXPECT_LT(concave, k.size() / 2);
    std::nth_element(k.begin(), k.begin() + static_cast<std::ptrdiff_t>(k.size() / 2), k.end());
    const float median = k[k.size() / 2];
    // A head is roughly a 0.08 m sphere (12.5 / m); features make the median larger, not tenfold.
    EXPECT_GT(median, 6.0f);
    EXPECT_LT(median, 60.0f);
    // The top of the skull is close to a sphere of 8 to 12 cm radius.
    for (const preskin::Vertex& v : p.vertices) {
        if (v.positionOs.y > 0.18f) {
            EXPECT_GT(v.curvaturePerM, 1.0f / 0.2f);
            EXPECT_LT(v.curvaturePerM, 1.0f / 0.05f);
        }
    }
}

TEST(SceneHead, KeyLightCameraAndEnvironment) {
    const preskin::Scene& s = head();
    ASSERT_EQ(s.lights.size(), 1u);
    const preskin::Light& key = s.lights[0];
    EXPECT_EQ(key.type, preskin::LightType::Directional);
    EXPECT_TRUE(key.castsShadow);
    EXPECT_FLOAT_EQ(key.intensity, 3.0f);
    // Travels right, down and away from the viewer: lit from the upper front-left.
    const glm::vec3 expected = glm::normalize(glm::vec3(0.6f, -0.55f, -0.58f));
    EXPECT_NEAR(glm::dot(key.directionWs, expected), 1.0f, 1e-5f);

    // The front view, then close-ups of the nose and cheek, the lips and the ear (docs/fidelity.md).
    ASSERT_EQ(s.cameras.size(), 4u);
    EXPECT_EQ(s.cameras[0].name, "front");
    const preskin::Camera& cam = s.cameras[0];
    EXPECT_FALSE(cam.orthographic);
    EXPECT_FLOAT_EQ(cam.yfov, 0.5f);
    const glm::vec3 position(cam.worldFromView[3]);
    EXPECT_NEAR(position.z, 0.7f, 1e-6f);
    const glm::vec3 forward = -glm::vec3(cam.worldFromView[2]);
    EXPECT_NEAR(glm::dot(forward, glm::vec3(0, 0, -1)), 1.0f, 1e-6f);
    // The head (crown to chin) is inside the vertical field of view.
    const float halfHeight = position.z * std::tan(cam.yfov * 0.5f);
    EXPECT_LT(0.19f - position.y, halfHeight);
    EXPECT_LT(position.y - (-0.04f), halfHeight);

    const char* closeUps[] = {"cheek_nose", "lips", "ear"};
    for (size_t i = 0; i < 3; ++i) {
        const preskin::Camera& c = s.cameras[i + 1];
        EXPECT_EQ(c.name, closeUps[i]);
        // Aimed at the head, framing at most 100 mm where the view meets it: >= 7.6 pixels per mm at 768.
        const glm::vec3 eye(c.worldFromView[3]), look = -glm::vec3(c.worldFromView[2]);
        float hitM = -1.0f;
        const preskin::Bounds b = s.worldBounds();
        for (float t = 0.0f; t < 0.5f; t += 0.0005f)
            if (glm::all(glm::greaterThanEqual(eye + t * look, b.min)) &&
                glm::all(glm::lessThanEqual(eye + t * look, b.max))) {
                hitM = t;
                break;
            }
        ASSERT_GT(hitM, 0.0f) << closeUps[i] << " looks past the head";
        EXPECT_LT(2.0f * hitM * std::tan(0.5f * c.yfov), 0.1f) << closeUps[i];
    }

    ASSERT_TRUE(s.environmentPath.has_value());
    EXPECT_EQ(s.environmentPath->filename(), "studio_small_05_1k.hdr");
    EXPECT_TRUE(std::filesystem::is_regular_file(*s.environmentPath));
    EXPECT_FLOAT_EQ(s.environmentIntensity, 0.5f);
    EXPECT_NEAR(s.environmentRotation, 1.5f * 3.14159265f, 1e-5f);  // the softbox to the side as fill
}

}  // namespace preskin::test
