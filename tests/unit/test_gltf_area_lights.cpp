// PRESKIN_lights_area (docs/gltf-extensions.md): shapes and sizes read onto point lights, the
// light's frame from its node (a tube along +X; a rectangle's width along +X, height along +Y,
// facing -Z; a disc facing -Z), the GPU record's layout (shared/light.h), and every refusal
// naming the file and the field.
#include "unit/GltfTestFiles.h"

#include <preskin/Error.h>
#include <preskin/LightRecord.h>
#include <preskin/Limits.h>
#include <preskin/Scene.h>

#include <gtest/gtest.h>

#include <cmath>

using nlohmann::json;

namespace preskin::test {
namespace {

GltfBuilder sceneWithLight(const json& light, const json& node = json::object()) {
    GltfBuilder b = triangleScene();
    b.doc["extensionsUsed"] = {"KHR_lights_punctual", "PRESKIN_lights_area"};
    b.doc["extensions"]["KHR_lights_punctual"]["lights"] = json::array({light});
    json n = node;
    n["extensions"] = {{"KHR_lights_punctual", {{"light", 0}}}};
    b.doc["nodes"].push_back(n);
    b.doc["scenes"][0]["nodes"] = {0, 1};
    return b;
}

json areaLight(const json& shape) {
    return {{"type", "point"}, {"intensity", 5}, {"extensions", {{"PRESKIN_lights_area", shape}}}};
}

TEST(GltfAreaLights, ShapesSizesAndFrames) {
    TempDir dir;
    const float h = std::sqrt(0.5f);
    // 90 degrees about +Y: +X -> -Z, -Z -> -X, +Y stays.
    const json turned = {{"translation", {1, 2, 3}}, {"rotation", {0, h, 0, h}}, {"scale", {4, 4, 4}}};
    struct Case {
        json shape;
        LightType type;
    };
    const Case cases[] = {
        {{{"shape", "sphere"}, {"radius", 0.1}}, LightType::Sphere},
        {{{"shape", "tube"}, {"radius", 0.02}, {"length", 0.6}}, LightType::Tube},
        {{{"shape", "rectangle"}, {"width", 1.0}, {"height", 0.5}}, LightType::Rectangle},
        {{{"shape", "disc"}, {"radius", 0.25}}, LightType::Disc},
    };
    for (const Case& c : cases) {
        const Scene s = Scene::load(sceneWithLight(areaLight(c.shape), turned).writeGltf(dir.path(), "a"));
        ASSERT_EQ(s.lights.size(), 1u);
        const Light& l = s.lights[0];
        EXPECT_EQ(l.type, c.type);
        EXPECT_EQ(l.positionWs, glm::vec3(1, 2, 3));
        EXPECT_FLOAT_EQ(l.intensity, 5.0f);
        EXPECT_TRUE(isAreaLight(l.type));
        // Sizes in metres, the node's scale not applied.
        EXPECT_FLOAT_EQ(l.radius, float(c.shape.value("radius", 0.0)));
        EXPECT_FLOAT_EQ(l.length, float(c.shape.value("length", 0.0)));
        EXPECT_FLOAT_EQ(l.width, float(c.shape.value("width", 0.0)));
        EXPECT_FLOAT_EQ(l.height, float(c.shape.value("height", 0.0)));
        EXPECT_LT(glm::distance(l.directionWs, glm::vec3(-1, 0, 0)), 1e-6f);
        EXPECT_LT(glm::distance(l.axisWs, glm::vec3(0, 0, -1)), 1e-6f);
        const AreaLightAxes axes = areaLightAxes(l);
        EXPECT_LT(glm::distance(axes.height, glm::vec3(0, 1, 0)), 1e-6f) << "the node's +Y";
        EXPECT_LT(glm::distance(glm::cross(axes.height, axes.width), axes.normal), 1e-6f);
        // The GPU record (shared/light.h).
        const gpu::GpuLight g = toGpuLight(l, false);
        if (c.type == LightType::Rectangle) {
            EXPECT_LT(glm::distance(glm::vec3(g.directionType), glm::vec3(0, 0, -0.5f)), 1e-6f);
            EXPECT_LT(glm::distance(glm::vec3(g.spotScaleOffset), glm::vec3(0, 0.25f, 0)), 1e-6f);
        } else {
            EXPECT_FLOAT_EQ(g.spotScaleOffset.x, l.radius);
        }
        if (c.type == LightType::Tube) {
            EXPECT_LT(glm::distance(glm::vec3(g.directionType), glm::vec3(0, 0, -0.3f)), 1e-6f);
        }
        if (c.type == LightType::Disc) {
            EXPECT_LT(glm::distance(glm::vec3(g.directionType), glm::vec3(-1, 0, 0)), 1e-6f);
        }
    }
    // A size the shape does not use is ignored with a warning naming it.
    const Scene extra = Scene::load(
        sceneWithLight(areaLight({{"shape", "sphere"}, {"radius", 0.1}, {"width", 2.0}})).writeGltf(dir.path(), "c"));
    ASSERT_EQ(extra.warnings.size(), 1u);
    EXPECT_NE(extra.warnings[0].find("PRESKIN_lights_area.width: not a size of a sphere light; ignored"),
              std::string::npos)
        << extra.warnings[0];
    // Without the extension the same light is a point light.
    const Scene plain =
        Scene::load(sceneWithLight({{"type", "point"}, {"intensity", 5}}, turned).writeGltf(dir.path(), "b"));
    EXPECT_EQ(plain.lights.at(0).type, LightType::Point);
}

// Sizes inside (0, 1e6] that single precision cannot hold (1e-300 was 0, then refused with a
// message printing 0 and no file) are taken at the floor, limits::kMinAreaLightSizeM.
TEST(GltfAreaLights, SizesBelowTheFloorAreTakenAtTheFloor) {
    TempDir dir;
    for (const json& shape : {json{{"shape", "disc"}, {"radius", 1e-300}},
                              json{{"shape", "rectangle"}, {"width", 1e-30}, {"height", 1e-300}},
                              json{{"shape", "tube"}, {"radius", 1e-45}, {"length", 2e-9}}}) {
        const Scene s = Scene::load(sceneWithLight(areaLight(shape)).writeGltf(dir.path(), "tiny"));
        const Light& l = s.lights.at(0);
        EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
        for (const float size : {l.radius, l.width, l.height})
            if (size != 0.0f) {
                EXPECT_FLOAT_EQ(size, float(limits::kMinAreaLightSizeM)) << shape.dump();
            }
        if (l.type == LightType::Tube) {
            EXPECT_FLOAT_EQ(l.length, 2e-9f);
        }
    }
}

json sunLight(const json& shape) {
    return {{"type", "directional"}, {"intensity", 3}, {"extensions", {{"PRESKIN_lights_area", shape}}}};
}

TEST(GltfAreaLights, DirectionalSphereIsASunWithAnAngularRadius) {
    TempDir dir;
    json light = sunLight({{"shape", "sphere"}, {"angularRadius", 0.00465}, {"radius", 2.0}});
    light["extras"] = {{"castsShadow", true}};
    const Scene s = Scene::load(sceneWithLight(light).writeGltf(dir.path(), "sun"));
    ASSERT_EQ(s.lights.size(), 1u);
    const Light& l = s.lights[0];
    EXPECT_EQ(l.type, LightType::Directional);
    EXPECT_FLOAT_EQ(l.angularRadius, 0.00465f);
    EXPECT_TRUE(l.castsShadow);
    ASSERT_EQ(s.warnings.size(), 1u);
    EXPECT_NE(s.warnings[0].find("PRESKIN_lights_area.radius: not a size of a directional light; ignored"),
              std::string::npos)
        << s.warnings[0];
    // The GPU record carries sin(angular radius) (shared/light.h); a parallel light 0.
    EXPECT_NEAR(toGpuLight(l, true).spotScaleOffset.z, std::sin(0.00465f), 1e-9f);
    Light parallel = l;
    parallel.angularRadius = 0.0f;
    EXPECT_EQ(toGpuLight(parallel, true).spotScaleOffset.z, 0.0f);
    // A point light's extension with an angular radius: warned about, not used.
    const Scene point =
        Scene::load(sceneWithLight(areaLight({{"shape", "sphere"}, {"radius", 0.1}, {"angularRadius", 0.1}}))
                        .writeGltf(dir.path(), "p"));
    ASSERT_EQ(point.warnings.size(), 1u);
    EXPECT_NE(point.warnings[0].find("angularRadius: a size of directional lights only; ignored"), std::string::npos);
}

TEST(GltfAreaLights, RefusalsNameTheFileAndTheField) {
    TempDir dir;
    const std::string at = "extensions.KHR_lights_punctual.lights[0].extensions.PRESKIN_lights_area";
    struct Case {
        json light;
        std::string field;
        const char* problem;
    };
    const Case cases[] = {
        {areaLight({{"radius", 0.1}}), at + ".shape", "missing"},
        {areaLight({{"shape", "cone"}, {"radius", 0.1}}), at + ".shape",
         "'cone' is not sphere, tube, rectangle or disc"},
        {areaLight({{"shape", 3}}), at + ".shape", "not a string"},
        {areaLight({{"shape", "sphere"}}), at + ".radius", "missing"},
        {areaLight({{"shape", "sphere"}, {"radius", -0.1}}), at + ".radius", "outside (0, 1e6]"},
        {areaLight({{"shape", "sphere"}, {"radius", 0}}), at + ".radius", "outside (0, 1e6]"},
        {areaLight({{"shape", "tube"}, {"radius", 0.1}}), at + ".length", "missing"},
        {areaLight({{"shape", "rectangle"}, {"width", 1.0}, {"height", 1e9}}), at + ".height", "exceeds the limit"},
        {areaLight({{"shape", "disc"}, {"radius", "big"}}), at + ".radius", "not a number"},
        {areaLight(json::array({1})), at, "not an object"},
        {{{"type", "spot"},
          {"spot", {{"outerConeAngle", 0.5}}},
          {"extensions", {{"PRESKIN_lights_area", {{"shape", "sphere"}, {"radius", 0.1}}}}}},
         at,
         "applies to lights of type point or directional only"},
        {sunLight({{"shape", "sphere"}}), at + ".angularRadius", "missing"},
        {sunLight({{"shape", "sphere"}, {"angularRadius", 0.0}}), at + ".angularRadius", "outside (0, pi/4]"},
        {sunLight({{"shape", "sphere"}, {"angularRadius", 1.0}}), at + ".angularRadius", "outside (0, pi/4]"},
        {sunLight({{"shape", "disc"}, {"radius", 1.0}}), at + ".shape", "a directional light's shape is sphere"},
    };
    int i = 0;
    for (const Case& c : cases) {
        const auto path = sceneWithLight(c.light).writeGltf(dir.path(), "bad" + std::to_string(i++));
        expectLoadError(path, std::vector<const char*>{c.field.c_str(), c.problem});
    }
}

}  // namespace
}  // namespace preskin::test
