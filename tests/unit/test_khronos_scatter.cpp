// Diffusion profiles from Khronos scattering parameters (<preskin/KhronosScatter.h>):
//  - the single-scattering albedo against the forward relation the inversion comes from: with
//    s = sqrt(1 - alpha_0) (alpha_0 the reduced albedo), Chiang et al.'s fit
//    s = 4.09712 + 4.20863 A - sqrt(9.59217 + 41.6808 A + 17.7126 A^2) is a quadratic in A,
//    solved here for A and fed back: within 1e-4 over A in [0.01, 0.99], g in {-0.5, 0, 0.8};
//  - the mean free path of three parameter sets against values computed by hand (each step in
//    the comments);
//  - parameters that define no profile are refused naming the field;
//  - glTF: a skin material naming no profile gets the Khronos profile (shared by materials with
//    the same parameters), one naming a profile keeps it with a warning, makeSkin applies it,
//    KHR_materials_scatter's scatterFactor scales the albedo, unused textures are warned about.
#include "unit/GltfTestFiles.h"

#include <preskin/Error.h>
#include <preskin/KhronosScatter.h>
#include <preskin/Scene.h>

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace preskin::test {
namespace {

using nlohmann::json;

// The multiple-scattering albedo A whose fit gives s (the root in [0, 1] of the quadratic
// (4.09712 - s + 4.20863 A)^2 = 9.59217 + 41.6808 A + 17.7126 A^2).
double multiscatterOf(double s) {
    const double p = 4.09712 - s, q = 4.20863;
    const double a = q * q - 17.7126, b = 2.0 * p * q - 41.6808, c = p * p - 9.59217;
    const double disc = std::sqrt(b * b - 4.0 * a * c);
    for (double root : {(-b - disc) / (2.0 * a), (-b + disc) / (2.0 * a)})
        if (root >= -1e-9 && root <= 1.0 + 1e-9) return root;
    return std::nan("");
}

TEST(KhronosScatter, InversionAgreesWithTheFitItInverts) {
    for (double g : {-0.5, 0.0, 0.8}) {
        for (int i = 1; i <= 99; ++i) {
            const double A = i / 100.0;
            const double alpha = singleScatteringAlbedo(glm::dvec3(A), g).x;
            // Back from alpha to the reduced albedo alpha_0 = (1 - g) alpha / (1 - g alpha), then s.
            const double reduced = (1.0 - g) * alpha / (1.0 - g * alpha);
            EXPECT_NEAR(multiscatterOf(std::sqrt(1.0 - reduced)), A, 1e-4) << "A " << A << " g " << g;
            EXPECT_GT(alpha, 0.0);
            EXPECT_LT(alpha, 1.0);
        }
    }
}

TEST(KhronosScatter, MeanFreePathOfThreeParameterSets) {
    // 1. d = 5 mm, c = (0.5, 0.25, 0.125), A = (0.8, 0.6, 0.4), g = 0: sigma_t = -ln(c) / d =
    //    (138.629, 277.259, 415.888) 1/m; isotropic, so l = 1000 / sigma_t mm.
    KhronosScatter one;
    one.attenuationDistanceM = 0.005;
    one.attenuationColor = {0.5, 0.25, 0.125};
    one.multiscatterColor = {0.8, 0.6, 0.4};
    // 2. d = 10 mm, c = (0.8, 0.5, 0.2), A = (0.9, 0.5, 0.1), g = 0.8: s = (0.134672, 0.416604,
    //    0.826543), alpha = (1 - s^2) / (1 - 0.8 s^2) = (0.999581, 0.981000, 0.757285); sigma_t =
    //    (22.3144, 69.3147, 160.944) 1/m; l = 1000 / (sigma_t (1 - 0.8 alpha)).
    KhronosScatter two;
    two.attenuationDistanceM = 0.01;
    two.attenuationColor = {0.8, 0.5, 0.2};
    two.multiscatterColor = {0.9, 0.5, 0.1};
    two.scatterAnisotropy = 0.8;
    // 3. KHR_materials_scatter's scatterFactor 0.5 times (0.7, 0.5, 0.4): A = (0.35, 0.25, 0.2);
    //    d = 2 mm, c = (0.9, 0.7, 0.6), g = -0.3: alpha = (0.765303, 0.635021, 0.549607).
    KhronosScatter three;
    three.attenuationDistanceM = 0.002;
    three.attenuationColor = {0.9, 0.7, 0.6};
    three.multiscatterColor = {0.35, 0.25, 0.2};
    three.scatterAnisotropy = -0.3;
    // 4. The material of Khronos's ScatteringSkull sample (glTF-Sample-Assets, CC0): d = 16.8918 mm,
    //    c = (0.367879, 0.485731, 0.396410), A = (0.168271, 0.527120, 0.590625), g = 0:
    //    sigma_t = (1.000000, 0.722070, 0.925281) / 0.0168918 m = (59.2004, 42.7470, 54.7771) 1/m; l = 1000 / sigma_t mm.
    KhronosScatter skull;
    skull.attenuationDistanceM = 0.016891848295927049;
    skull.attenuationColor = {0.3678794503211975, 0.4857314527034759, 0.3964099884033203};
    skull.multiscatterColor = {0.16827136278152467, 0.5271198749542236, 0.5906253457069397};
    const struct {
        const KhronosScatter& scatter;
        glm::dvec3 mfpMm;
        glm::dvec3 alpha;
    } cases[] = {
        {one, {7.213475, 3.606738, 2.404492}, {0.990589, 0.951179, 0.850796}},
        {two, {223.6958, 67.03966, 15.76303}, {0.999581, 0.981000, 0.757285}},
        {three, {15.43802, 4.710052, 3.361053}, {0.765303, 0.635021, 0.549607}},
        {skull, {16.89185, 23.39269, 18.25541}, singleScatteringAlbedo(skull.multiscatterColor, 0.0)},
    };
    for (const auto& c : cases) {
        const glm::dvec3 mfp = khronosMeanFreePathMm(c.scatter);
        const glm::dvec3 alpha = singleScatteringAlbedo(c.scatter.multiscatterColor, c.scatter.scatterAnisotropy);
        for (int ch = 0; ch < 3; ++ch) {
            EXPECT_NEAR(mfp[ch], c.mfpMm[ch], 1e-6 * c.mfpMm[ch] + 1e-5);
            EXPECT_NEAR(alpha[ch], c.alpha[ch], 2e-6);
        }
        const DiffusionProfile p = profileFromKhronosScatter(c.scatter, "k");
        EXPECT_EQ(p.kind(), DiffusionProfile::Kind::NormalizedDiffusion);
        for (int ch = 0; ch < 3; ++ch) {
            EXPECT_NEAR(p.meanFreePathMm()[ch], c.mfpMm[ch], 1e-6 * c.mfpMm[ch] + 1e-5);
            EXPECT_NEAR(p.albedo()[ch], c.scatter.multiscatterColor[ch], 1e-6);
        }
    }
}

void expectRefused(const KhronosScatter& k, const std::string& field) {
    try {
        (void)profileFromKhronosScatter(k, "k");
        FAIL() << "no error for " << field;
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
}

TEST(KhronosScatter, ParametersWithoutAProfileAreRefused) {
    KhronosScatter k;
    k.attenuationColor = {0.5, 0.5, 0.5};
    k.multiscatterColor = {0.8, 0.6, 0.4};
    expectRefused(k, "attenuationDistance");  // absent: infinite
    k.attenuationDistanceM = 0.01;
    EXPECT_NO_THROW((void)profileFromKhronosScatter(k, "k"));
    KhronosScatter clear = k;
    clear.attenuationColor.y = 1.0;
    expectRefused(clear, "attenuationColor: the green channel");
    KhronosScatter black = k;
    black.multiscatterColor.z = 0.0;
    expectRefused(black, "multiscatterColor: the blue channel");
    KhronosScatter nan = k;
    nan.scatterAnisotropy = std::nan("");
    expectRefused(nan, "scatterAnisotropy");
}

json scatterMaterial(const std::string& name, const json& skin, double distance, const char* scatterExtension,
                     const json& scatter) {
    json ext = {
        {"KHR_materials_volume",
         {{"thicknessFactor", 0.01}, {"attenuationDistance", distance}, {"attenuationColor", {0.5, 0.25, 0.125}}}},
        {scatterExtension, scatter}};
    if (!skin.is_null()) ext["PRESKIN_materials_skin"] = skin;
    return {{"name", name}, {"extensions", ext}};
}

bool hasWarning(const Scene& s, const std::string& fragment) {
    for (const std::string& w : s.warnings)
        if (w.find(fragment) != std::string::npos) return true;
    return false;
}

TEST(KhronosScatter, GltfSkinMaterialsTakeTheProfile) {
    TempDir dir;
    GltfBuilder b = triangleScene();
    b.doc["extensionsUsed"] = {"PRESKIN_materials_skin", "KHR_materials_volume", "KHR_materials_volume_scatter",
                               "KHR_materials_scatter"};
    b.doc["extensions"]["PRESKIN_materials_skin"]["profiles"] = json::array({{{"type", "deonLuebke"}}});
    const json volumeScatter = {{"multiscatterColor", {0.8, 0.6, 0.4}}};
    b.doc["materials"] = json::array({
        scatterMaterial("cheek", json::object(), 0.005, "KHR_materials_volume_scatter", volumeScatter),
        scatterMaterial("lips", json::object(), 0.005, "KHR_materials_volume_scatter", volumeScatter),
        scatterMaterial("named", {{"profile", 0}}, 0.005, "KHR_materials_volume_scatter", volumeScatter),
        scatterMaterial("later", json(), 0.005, "KHR_materials_scatter",
                        {{"multiscatterColor", {0.7, 0.5, 0.4}},
                         {"scatterFactor", 0.5},
                         {"scatterAnisotropy", -0.3},
                         {"scatterTexture", {{"index", 0}}}}),
        scatterMaterial("off", json::object(), 0.005, "KHR_materials_scatter",
                        {{"multiscatterColor", {0.7, 0.5, 0.4}}}),
    });
    b.doc["images"] = json::array({{{"uri", "s.png"}}});
    b.doc["textures"] = json::array({{{"source", 0}}});
    encodeImage(dir.path(), "s.png", 2, 2, 1, {0, 64, 128, 255});
    Scene s = Scene::load(b.writeGltf(dir.path()));
    EXPECT_FALSE(hasWarning(s, "extensionsUsed"));  // both drafts are read
    // cheek and lips share one Khronos profile after the scene's own.
    ASSERT_EQ(s.profiles.size(), 2u);
    EXPECT_EQ(s.materials[0].skin->profile, 1);
    EXPECT_EQ(s.materials[1].skin->profile, 1);
    ASSERT_TRUE(s.profiles[1].profile.has_value());
    EXPECT_NEAR(s.profiles[1].profile->meanFreePathMm().x, 7.213475, 1e-5);
    EXPECT_NEAR(s.profiles[1].profile->albedo().y, 0.6, 1e-6);
    EXPECT_EQ(s.materials[2].skin->profile, 0);
    EXPECT_TRUE(hasWarning(s, "materials[2] ('named'): the Khronos scatter parameters are not used"))
        << s.warnings.size();
    EXPECT_TRUE(hasWarning(s, "materials[3].extensions.KHR_materials_scatter.scatterTexture: not used"));
    EXPECT_TRUE(hasWarning(s, "materials[4].extensions.KHR_materials_scatter.scatterFactor: 0 (the default)"));
    EXPECT_FALSE(s.materials[4].khronosScatter.has_value());
    // "later" becomes skin in makeSkin, with its own profile (scatterFactor halves the albedo).
    EXPECT_FALSE(s.materials[3].skin.has_value());
    s.makeSkin("later");
    ASSERT_EQ(s.profiles.size(), 3u);
    EXPECT_EQ(s.materials[3].skin->profile, 2);
    EXPECT_NEAR(s.profiles[2].profile->albedo().x, 0.35, 1e-6);
    EXPECT_NEAR(s.profiles[2].profile->meanFreePathMm().x, 1000.0 / (-std::log(0.5) / 0.005 * (1.0 + 0.3 * 0.765303)),
                1e-3);
}

TEST(KhronosScatter, GltfAttenuationErrorsNameTheField) {
    TempDir dir;
    GltfBuilder b = triangleScene();
    b.doc["extensionsUsed"] = {"PRESKIN_materials_skin", "KHR_materials_volume", "KHR_materials_volume_scatter"};
    b.doc["materials"] = json::array({scatterMaterial("bad", json::object(), -1.0, "KHR_materials_volume_scatter",
                                                      {{"multiscatterColor", {0.8, 0.6, 0.4}}})});
    const char* fragments[] = {"materials[0].extensions.KHR_materials_volume.attenuationDistance", "must be > 0"};
    expectLoadError(b.writeGltf(dir.path()), fragments);
    // Wrong types and shapes name the field.
    const struct {
        const char* extension;
        const char* key;
        json value;
        const char* field;
    } bad[] = {
        {"KHR_materials_volume", "attenuationDistance", "far", "KHR_materials_volume.attenuationDistance"},
        {"KHR_materials_volume", "attenuationColor", {0.5, 0.5}, "KHR_materials_volume.attenuationColor"},
        {"KHR_materials_volume_scatter",
         "multiscatterColor",
         {0.5, "red", 0.5},
         "KHR_materials_volume_scatter.multiscatterColor"},
        {"KHR_materials_volume_scatter", "scatterAnisotropy", "strong",
         "KHR_materials_volume_scatter.scatterAnisotropy"},
    };
    for (const auto& c : bad) {
        GltfBuilder broken = b;
        broken.doc["materials"][0]["extensions"]["KHR_materials_volume"]["attenuationDistance"] = 0.01;
        broken.doc["materials"][0]["extensions"][c.extension][c.key] = c.value;
        const char* expected[] = {c.field};
        expectLoadError(broken.writeGltf(dir.path()), expected);
    }
    // No extinction: a warning, the default profile.
    b.doc["materials"][0]["extensions"]["KHR_materials_volume"].erase("attenuationDistance");
    const Scene s = Scene::load(b.writeGltf(dir.path()));
    EXPECT_EQ(s.materials[0].skin->profile, -1);
    EXPECT_TRUE(hasWarning(s, "define no profile (attenuationDistance")) << (s.warnings.empty() ? "" : s.warnings[0]);
}

}  // namespace
}  // namespace preskin::test
