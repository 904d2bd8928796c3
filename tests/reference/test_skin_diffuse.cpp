// Skin direct lighting on a sphere of known radius under one directional light, with per-vertex
// curvature recomputed from the mesh (computeVertexCurvature): every interior pixel against a CPU
// evaluation at the analytic hit point of
//   (1 - F) * albedo / pi * D(NoL, curvature) * E  +  dual-lobe GGX specular * NoL * E,
// D from LutSet::lookupDiffuse at the analytic curvature 1/r converted to profile units
// (1/m * 0.001 / scatterScale), F Schlick's with F0 = 0.028, and the specular written from the
// GGX / height-correlated Smith / Schlick formulas (compareWithSkinReference,
// support/SkinTestSupport.h). No shadows, no environment, no normal map.
// The test also checks that it can tell: Lambert in place of D must miss the 2/255 bound on many
// pixels.
#include "support/GpuTest.h"
#include "support/ImageCompare.h"
#include "support/SkinTestSupport.h"
#include "support/TestScenes.h"

#include <preskin/LutSet.h>
#include <preskin/Renderer.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace preskin::test {
namespace {

class SkinDiffuse : public GpuTest {};

TEST_F(SkinDiffuse, SphereWithVertexCurvatureMatchesLutAtAnalyticCurvature) {
    const LutSet& luts = LutSet::loadDefault();
    const double radiusM = 1.0;
    // A 1 m sphere scattering like a 5 mm one: profile curvature 1/m * 0.001 / 0.005 = 0.2 / mm.
    SkinMaterial skin;
    skin.scatterScale = 0.005f;
    const glm::dvec3 albedo(0.76, 0.52, 0.42);
    const double roughness = 0.5;
    Material material;
    material.baseColorFactor = glm::vec4(glm::vec3(albedo), 1.0f);
    material.metallicFactor = 0.0f;
    material.roughnessFactor = float(roughness);
    material.skin = skin;

    Primitive sphere = makeSphere(float(radiusM), 256, 128);
    recomputeCurvature(sphere);
    float minCurvature = 1e30f;
    float maxCurvature = 0.0f;
    for (const Vertex& v : sphere.vertices) {
        minCurvature = std::min(minCurvature, v.curvaturePerM);
        maxCurvature = std::max(maxCurvature, v.curvaturePerM);
    }
    sphere.material = 0;
    Scene scene = makeScene({{sphere, glm::mat4(1.0f)}}, {material});
    const Light light = sphereLight();
    scene.lights = {light};

    RenderSettings settings;
    settings.shadows = false;
    Renderer renderer(context(), scene, Environment::constant(glm::vec3(0.0f)), &luts, settings);
    const uint32_t size = 160;
    const View view = sphereView(radiusM);
    const RenderedImage image = renderer.render(view, size, size, OutputEncoding::LinearFloat);
    dumpImage("skin_diffuse_sphere", image);

    const SphereAgreement a =
        compareWithSkinReference(image, view, radiusM, light, skin, albedo, roughness, lutDiffuse(luts));
    std::printf(
        "[ skin     ] sphere diffuse: %zu of %zu interior pixels within 2/255 (worst %.2f/255); "
        "Lambert reference: %zu within; vertex curvature %.4f..%.4f 1/m (analytic %.4f)\n",
        a.within, a.interior, a.worst, a.lambertWithin, double(minCurvature), double(maxCurvature), 1.0 / radiusM);
    ASSERT_GT(a.interior, size_t(size * size / 4)) << "the sphere should cover a good part of the image";
    EXPECT_GE(double(a.within), 0.999 * double(a.interior))
        << a.within << " of " << a.interior << " interior pixels within 2/255; worst " << a.worst << "/255";
    EXPECT_LT(double(a.lambertWithin), 0.9 * double(a.interior))
        << "Lambert in place of the LUT should miss the bound on many pixels, or the test cannot tell them apart";
}

// makeSkin("all") (preskin render --skin all) on a primitive without a material: it gets glTF's
// default material (white, metallic 1, roughness 1) as skin with default parameters, so it must
// render as the CPU skin model with albedo 1 and roughness 1 (skin ignores metallic). The
// standard render of the same primitive (a rough white metal: no diffuse at all) must miss that
// reference on most pixels.
TEST_F(SkinDiffuse, SkinAllCoversPrimitivesWithoutMaterial) {
    const LutSet& luts = LutSet::loadDefault();
    const double radiusM = 0.005;  // curvature 0.2 / mm at scatter scale 1
    Primitive sphere = makeSphere(float(radiusM), 256, 128);
    recomputeCurvature(sphere);
    ASSERT_EQ(sphere.material, -1);
    Scene scene = makeScene({{sphere, glm::mat4(1.0f)}}, {});
    const Light light = sphereLight();
    scene.lights = {light};
    RenderSettings settings;
    settings.shadows = false;
    const uint32_t size = 128;
    const View view = sphereView(radiusM);
    const Environment dark = Environment::constant(glm::vec3(0.0f));

    const RenderedImage standard =
        Renderer(context(), scene, dark, &luts, settings).render(view, size, size, OutputEncoding::LinearFloat);
    scene.makeSkin("all");
    ASSERT_EQ(scene.materials.size(), 1u);
    EXPECT_EQ(scene.materials[0].name, Scene::kDefaultMaterialName);
    EXPECT_EQ(scene.meshes[0].primitives[0].material, 0);
    ASSERT_TRUE(scene.materials[0].skin.has_value());
    const RenderedImage skin =
        Renderer(context(), scene, dark, &luts, settings).render(view, size, size, OutputEncoding::LinearFloat);
    dumpImage("skin_all_default_material", skin);

    const SphereAgreement s =
        compareWithSkinReference(skin, view, radiusM, light, SkinMaterial{}, glm::dvec3(1.0), 1.0, lutDiffuse(luts));
    const SphereAgreement d = compareWithSkinReference(standard, view, radiusM, light, SkinMaterial{}, glm::dvec3(1.0),
                                                       1.0, lutDiffuse(luts));
    std::printf(
        "[ skin     ] --skin all on a primitive without material: %zu of %zu interior pixels within 2/255 "
        "of the skin reference (worst %.2f/255); the standard render: %zu within\n",
        s.within, s.interior, s.worst, d.within);
    ASSERT_GT(s.interior, size_t(size * size / 4));
    EXPECT_GE(double(s.within), 0.999 * double(s.interior)) << "worst " << s.worst << "/255";
    EXPECT_LT(double(s.lambertWithin), 0.9 * double(s.interior)) << "the curvature should show in the reference";
    EXPECT_LT(double(d.within), 0.1 * double(d.interior)) << "the standard render should not look like skin";
}

}  // namespace
}  // namespace preskin::test
