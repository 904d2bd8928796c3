// The skin render against the diffusion reference (DiffusionReference) where the pre-integrated
// model must hold, on a skin sphere of 10 mm diameter under one shadowed directional light,
// specular off, no ambient:
//  - the unlit side: past the terminator the skin render must carry at least 90 % of the
//    reference's red light (the shadow map must not remove the light the diffuse LUT puts there);
//  - transmission must add no more than 0.5 % where the skin faces the light (the diffuse LUT
//    already holds that light), and through a 3 mm slab lit from behind it must give what the
//    reference gives (the profile's plane integral at the slab's depth).
// Pixels are the sphere's interior pixels (analytic ray-sphere hits); the reference is traced
// through the same pixel centres. And the inside of a bowl (a hemisphere seen from inside, its
// normals inwards, so its mesh curvature is negative) must be shaded with the diffuse LUT's
// concave response: D(NoL, -1/r), no light past the terminator, not the convex D(NoL, 1/r); and
// the floor of a groove lit across it must be closer to the reference than Lambert (pooled below
// 0.3 of Lambert's error, red alone below 0.7), and the shadow filter must not shadow it with its
// own walls on a coarse map (it is lit everywhere).
#include "support/GpuTest.h"
#include "support/ImageCompare.h"
#include "support/SkinTestSupport.h"
#include "support/TestLights.h"
#include "support/TestScenes.h"

#include <preskin/DiffusionReference.h>
#include <preskin/LutSet.h>
#include <preskin/Renderer.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace preskin::test {
namespace {

// Skin's RMSE over Lambert's against the reference, pooled over R, G, B, over the skin pixels
// `counts` keeps (all by default); `pixels` is how many it kept.
template <typename Keep>
double skinOverLambert(const ReferenceImage& truth, const RenderedImage& skin, const RenderedImage& lambert,
                       size_t& pixels, Keep counts) {
    double skinSquared = 0.0, lambertSquared = 0.0;
    pixels = 0;
    for (size_t i = 0; i < truth.skin.size(); ++i) {
        if (!truth.skin[i] || !counts(i)) continue;
        for (int c = 0; c < 3; ++c) {
            const double want = double(truth.rgba32f[4 * i + size_t(c)]);
            skinSquared += std::pow(double(skin.rgba32f[4 * i + size_t(c)]) - want, 2.0);
            lambertSquared += std::pow(double(lambert.rgba32f[4 * i + size_t(c)]) - want, 2.0);
        }
        ++pixels;
    }
    return std::sqrt(skinSquared / lambertSquared);
}

class SkinFidelity : public GpuTest {
protected:
    void SetUp() override {
        GpuTest::SetUp();
        Primitive sphere = makeSphere(float(kRadiusM), 64, 32);
        recomputeCurvature(sphere);
        sphere.material = 0;
        scene_ = makeScene({{sphere, glm::mat4(1.0f)}}, {skinMaterial({0.8f, 0.6f, 0.5f})});
        const Light light = shadowedDirectionalLight({0.8f, -0.35f, -0.5f}, 3.0f);
        scene_.lights = {light};
        L_ = -glm::dvec3(light.directionWs);
        view_ = orbitView(scene_.worldBounds(), 0.0f, 8.0f, 0.0f, 1.0f);
    }

    RenderedImage render(bool transmission) {
        RenderSettings settings;
        settings.specular = false;
        settings.skin.transmission = transmission;
        Renderer renderer(context(), scene_, Environment::constant(glm::vec3(0.0f)), &LutSet::loadDefault(), settings);
        return renderer.render(view_, kSize, kSize, OutputEncoding::LinearFloat);
    }

    // The ray through pixel (x, y)'s centre, as the rasterizer samples it.
    void pixelRay(uint32_t x, uint32_t y, glm::dvec3& origin, glm::dvec3& direction) const {
        const glm::dmat4 worldFromClip = glm::inverse(glm::dmat4(view_.eye().clipFromWorld()));
        const glm::dvec2 ndc((x + 0.5) / kSize * 2.0 - 1.0, (y + 0.5) / kSize * 2.0 - 1.0);
        const glm::dvec4 a = worldFromClip * glm::dvec4(ndc, 1.0, 1.0);
        const glm::dvec4 b = worldFromClip * glm::dvec4(ndc, 0.5, 1.0);
        origin = glm::dvec3(a) / a.w;
        direction = glm::normalize(glm::dvec3(b) / b.w - origin);
    }

    static constexpr double kRadiusM = 0.005;
    static constexpr uint32_t kSize = 64;
    Scene scene_;
    glm::dvec3 L_{0.0};
    View view_;
};

TEST_F(SkinFidelity, UnlitSideCarriesNinetyPercentOfTheReferenceRed) {
    const RenderedImage skin = render(true);
    const DiffusionReference reference(scene_, scene_.lights, ShRgb{}, LutSet::loadDefault().profile());
    const auto hits = traceSphere(view_, kSize, kSize, glm::dvec3(0.0), kRadiusM);
    double skinRed = 0.0, referenceRed = 0.0;
    int pixels = 0;
    for (uint32_t y = 0; y < kSize; y += 2)
        for (uint32_t x = 0; x < kSize; x += 2) {
            const SphereHit& h = hits[size_t(y) * kSize + x];
            if (!h.interior) continue;
            const double NoL = glm::dot(glm::normalize(h.positionWs), L_);
            if (NoL >= -0.02 || NoL < -0.6) continue;  // the unlit side where light still arrives
            glm::dvec3 origin, direction;
            pixelRay(x, y, origin, direction);
            const auto sample = reference.trace(origin, direction);
            ASSERT_TRUE(sample.has_value());
            skinRed += pixelLinear(skin, x, y).r;
            referenceRed += sample->radiance.r;
            ++pixels;
        }
    const double ratio = skinRed / referenceRed;
    std::printf("[ fidelity ] 10 mm sphere, unlit side (%d pixels): skin red / reference red = %.3f\n", pixels, ratio);
    ASSERT_GT(pixels, 30);
    EXPECT_GE(ratio, 0.9);
    EXPECT_LE(ratio, 1.25) << "and not far brighter either";
}

// The whole picture of the small sphere, its shadow-casting light included: every technique on
// (the wide shadow map's penumbra too, which must not darken the sphere's own terminator).
TEST_F(SkinFidelity, WholeSphereIsFarCloserToTheReferenceThanLambert) {
    const RenderedImage skin = render(true);
    RenderSettings settings;
    settings.specular = false;
    settings.skin = SkinFeatures::none();
    Renderer renderer(context(), scene_, Environment::constant(glm::vec3(0.0f)), &LutSet::loadDefault(), settings);
    const RenderedImage lambert = renderer.render(view_, kSize, kSize, OutputEncoding::LinearFloat);
    const DiffusionReference reference(scene_, scene_.lights, ShRgb{}, LutSet::loadDefault().profile());
    const ReferenceImage truth = reference.render(view_.eye(), kSize, kSize);
    size_t pixels = 0;
    const double ratio = skinOverLambert(truth, skin, lambert, pixels, [](size_t) { return true; });
    std::printf("[ fidelity ] 10 mm sphere (%zu pixels): skin / Lambert RMSE %.3f\n", pixels, ratio);
    EXPECT_GT(pixels, size_t(kSize) * 20);
    EXPECT_LT(ratio, 0.3);
}

TEST_F(SkinFidelity, TransmissionAddsAtMostHalfAPercentWhereTheSkinFacesTheLight) {
    const RenderedImage with = render(true);
    const RenderedImage without = render(false);
    const auto hits = traceSphere(view_, kSize, kSize, glm::dvec3(0.0), kRadiusM);
    glm::dvec3 added(0.0), base(0.0);
    double unlitAdded = 0.0;
    for (uint32_t y = 0; y < kSize; ++y)
        for (uint32_t x = 0; x < kSize; ++x) {
            const SphereHit& h = hits[size_t(y) * kSize + x];
            if (!h.interior) continue;
            const double NoL = glm::dot(glm::normalize(h.positionWs), L_);
            const glm::dvec3 d = pixelLinear(with, x, y) - pixelLinear(without, x, y);
            if (NoL > 0.0) {
                added += d;
                base += pixelLinear(without, x, y);
            } else {
                unlitAdded += d.r;
            }
        }
    std::printf("[ fidelity ] 10 mm sphere, lit side: transmission adds (%.4f, %.4f, %.4f) %%; unlit side red %+.4f\n",
                100.0 * added.r / base.r, 100.0 * added.g / base.g, 100.0 * added.b / base.b, unlitAdded);
    for (int c = 0; c < 3; ++c) EXPECT_LE(added[c], 0.005 * base[c]) << "channel " << c;
}

// A slab `thicknessMm` thick lit from behind, the light `degrees` off the slab's normal: skin at
// the centre of its front face against the reference, within 5 % of the reference's red.
void expectSlabTransmissionMatchesTheReference(Context& context, const Scene& base, double thicknessMm,
                                               double degrees) {
    const auto thicknessM = float(0.001 * thicknessMm);
    Primitive slab = makeBox(glm::vec3(0.08f, 0.08f, thicknessM));
    slab.material = 0;
    Scene scene =
        makeScene({{slab, glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, -0.5f * thicknessM))}}, base.materials);
    Light light = base.lights[0];
    const float angle = glm::radians(float(degrees));
    light.directionWs = glm::vec3(std::sin(angle), 0.0f, std::cos(angle));  // from behind, towards the camera
    scene.lights = {light};
    const View view = perspectiveView(
        glm::inverse(glm::lookAt(glm::vec3(0.0f, 0.0f, 0.2f), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f))), 0.5f,
        1.0f, 0.05f, 1.0f);
    RenderSettings settings;
    settings.specular = false;
    Renderer renderer(context, scene, Environment::constant(glm::vec3(0.0f)), &LutSet::loadDefault(), settings);
    const RenderedImage image = renderer.render(view, 32, 32, OutputEncoding::LinearFloat);
    const DiffusionReference reference(scene, scene.lights, ShRgb{}, LutSet::loadDefault().profile());
    const auto sample = reference.trace(glm::dvec3(0.0, 0.0, 0.2), glm::dvec3(0.0, 0.0, -1.0));
    ASSERT_TRUE(sample.has_value());
    glm::dvec3 skin(0.0);
    for (uint32_t y = 15; y <= 16; ++y)
        for (uint32_t x = 15; x <= 16; ++x) skin += 0.25 * pixelLinear(image, x, y);
    std::printf(
        "[ fidelity ] %.0f mm slab from behind, %.0f degrees off its normal: skin (%.4f, %.5f) reference "
        "(%.4f, %.5f) red, green\n",
        thicknessMm, degrees, skin.r, skin.g, sample->radiance.r, sample->radiance.g);
    EXPECT_NEAR(skin.r, sample->radiance.r, 0.05 * sample->radiance.r);
    EXPECT_NEAR(skin.g, sample->radiance.g, 0.05 * sample->radiance.r);
}

TEST_F(SkinFidelity, ThinSlabTransmissionMatchesTheReference) {
    expectSlabTransmissionMatchesTheReference(context(), scene_, 3.0, 0.0);
}

// The light crosses the slab obliquely: its path is longer than the slab is thick, but the lit
// face, and with it the light the profile carries across, stays one thickness away.
TEST_F(SkinFidelity, ObliquelyLitThinSlabTransmissionMatchesTheReference) {
    expectSlabTransmissionMatchesTheReference(context(), scene_, 4.0, 70.0);
}

TEST_F(SkinFidelity, InsideOfABowlIsShadedWithTheConcaveResponse) {
    // A 1 m bowl scattering like one of 5 mm radius (profile curvature -0.2 / mm).
    const double radiusM = 1.0;
    SkinMaterial skin;
    skin.scatterScale = 0.005f;
    const double curvaturePerMm = -1.0 / radiusM * 0.001 / double(skin.scatterScale);
    Material material;
    material.baseColorFactor = glm::vec4(0.8f, 0.6f, 0.5f, 1.0f);
    material.metallicFactor = 0.0f;
    material.skin = skin;
    // The lower hemisphere of a UV sphere turned inside out: normals inwards, winding reversed.
    const Primitive sphere = makeSphere(float(radiusM), 192, 96);
    Primitive bowl;
    std::vector<uint32_t> remap(sphere.vertices.size(), UINT32_MAX);
    for (size_t t = 0; t + 2 < sphere.indices.size(); t += 3) {
        const uint32_t tri[3] = {sphere.indices[t], sphere.indices[t + 2], sphere.indices[t + 1]};
        bool lower = true;
        for (uint32_t i : tri) lower = lower && sphere.vertices[i].positionOs.y <= 1e-6f;
        if (!lower) continue;
        for (uint32_t i : tri) {
            if (remap[i] == UINT32_MAX) {
                Vertex v = sphere.vertices[i];
                v.normalOs = -v.normalOs;
                remap[i] = uint32_t(bowl.vertices.size());
                bowl.vertices.push_back(v);
                bowl.boundsOs.extend(v.positionOs);
            }
            bowl.indices.push_back(remap[i]);
        }
    }
    recomputeCurvature(bowl);
    bowl.material = 0;
    Scene scene = makeScene({{bowl, glm::mat4(1.0f)}}, {material});
    Light light;
    light.type = LightType::Directional;
    light.directionWs = glm::normalize(glm::vec3(0.75f, -0.66f, 0.0f));  // grazes the wall nearest the light
    light.intensity = 3.0f;
    scene.lights = {light};
    const glm::dvec3 L = -glm::normalize(glm::dvec3(light.directionWs));

    RenderSettings settings;
    settings.specular = false;
    settings.shadows = false;  // the LUT's response alone
    const LutSet& luts = LutSet::loadDefault();
    Renderer renderer(context(), scene, Environment::constant(glm::vec3(0.0f)), &luts, settings);
    const uint32_t size = 96;
    const View view =
        perspectiveView(glm::inverse(glm::lookAt(glm::vec3(0.0f, 3.0f, 0.3f), glm::vec3(0.0f, -0.3f, 0.0f),
                                                 glm::vec3(0.0f, 0.0f, -1.0f))),
                        0.6f, 1.0f, 0.1f, 10.0f);
    const RenderedImage image = renderer.render(view, size, size, OutputEncoding::LinearFloat);

    // The far intersection of each pixel's ray with the sphere: the inside of the bowl.
    const glm::dmat4 worldFromClip = glm::inverse(glm::dmat4(view.eye().clipFromWorld()));
    size_t compared = 0, concaveMisses = 0, convexMisses = 0, pastTerminator = 0;
    for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 0; x < size; ++x) {
            const glm::dvec2 ndc((x + 0.5) / size * 2.0 - 1.0, (y + 0.5) / size * 2.0 - 1.0);
            const glm::dvec4 a = worldFromClip * glm::dvec4(ndc, 1.0, 1.0),
                             b = worldFromClip * glm::dvec4(ndc, 0.5, 1.0);
            const glm::dvec3 o = glm::dvec3(a) / a.w, d = glm::normalize(glm::dvec3(b) / b.w - o);
            const double half = glm::dot(o, d), disc = half * half - (glm::dot(o, o) - radiusM * radiusM);
            if (disc <= 0.0) continue;
            const glm::dvec3 p = o + d * (-half + std::sqrt(disc));
            if (p.y > -0.3 * radiusM) continue;  // away from the open rim (curvature estimate, silhouette)
            const glm::dvec3 N = -glm::normalize(p);
            const double NoL = glm::dot(N, L);
            const glm::dvec3 scale =
                glm::dvec3(material.baseColorFactor) / 3.14159265358979323846 * double(light.intensity);
            const glm::dvec3 concave = scale * glm::dvec3(luts.lookupDiffuse(float(NoL), float(curvaturePerMm)));
            const glm::dvec3 convex = scale * glm::dvec3(luts.lookupDiffuse(float(NoL), float(-curvaturePerMm)));
            const glm::dvec3 got = pixelLinear(image, x, y);
            ++compared;
            pastTerminator += NoL < 0.0;
            concaveMisses += srgbDifference(got, concave) > 2.0;
            convexMisses += srgbDifference(got, convex) > 2.0;
        }
    std::printf(
        "[ fidelity ] bowl: %zu pixels (%zu past the terminator); off the concave response by > 2/255: %zu, "
        "off the convex one: %zu\n",
        compared, pastTerminator, concaveMisses, convexMisses);
    ASSERT_GT(compared, 1000u);
    ASSERT_GT(pastTerminator, 50u);
    EXPECT_LE(concaveMisses, compared / 200);
    EXPECT_GT(convexMisses, compared / 20) << "the test must tell the two responses apart";
}

// A groove (z = -3 mm exp(-x^2 / 2 (2.5 mm)^2) in a skin plane), lit across it at 37 degrees from
// the normal: in its concave floor (mean curvature to -0.2 / mm) skin must come closer to the
// diffusion reference than Lambert, by a clear margin (a crease the concave model and the wide
// shadow map both see; the wide map's occluders there are the groove's own walls, within red's
// reach, and with its edge kept there the ratio is 0.42).
// A scene seen from 60 mm above the origin looking down (20 mm across at z = 0, kFromAboveSize
// pixels square), no ambient, specular off: skin with every technique, skin with `other`'s
// techniques, and the reference (a coarse quadrature, enough at this size).
constexpr uint32_t kFromAboveSize = 64;
struct FromAbove {
    RenderedImage skin, other;
    ReferenceImage truth;
};
// eyeZ: the eye's height (negative: from below, looking up).
// environment: the ambient light (its SH alone: no lights are extracted from it); none: dark.
FromAbove renderFromAbove(Context& context, const Scene& scene, const SkinFeatures& other, float eyeZ = 0.06f,
                          const Environment* environment = nullptr) {
    const View view = perspectiveView(
        glm::inverse(glm::lookAt(glm::vec3(0.0f, 0.0f, eyeZ), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f))),
        2.0f * std::atan(0.01f / 0.06f), 1.0f, 0.01f, 1.0f);
    const Environment dark = Environment::constant(glm::vec3(0.0f));
    const Environment& ambient = environment != nullptr ? *environment : dark;
    RenderSettings settings;
    settings.specular = false;
    settings.environmentLights = 0;
    Renderer renderer(context, scene, ambient, &LutSet::loadDefault(), settings);
    FromAbove images;
    images.skin = renderer.render(view, kFromAboveSize, kFromAboveSize, OutputEncoding::LinearFloat);
    settings.skin = other;
    renderer.setSettings(settings);
    images.other = renderer.render(view, kFromAboveSize, kFromAboveSize, OutputEncoding::LinearFloat);
    const ReferenceSettings coarse = coarseReferenceSettings();
    const DiffusionReference reference(scene, scene.lights, ambient.radianceSh(), LutSet::loadDefault().profile(),
                                       coarse);
    images.truth = reference.render(view.eye(), kFromAboveSize, kFromAboveSize);
    return images;
}

// Red in a strip of columns (xMm(x): the column's place, kept where it lies in [fromMm, toMm]),
// rows away from the image's top and bottom: the means of skin, of skin without a term and of the
// reference, and both renders' RMSE against it.
struct StripRed {
    size_t pixels = 0;
    double skin = 0.0, without = 0.0, truth = 0.0, skinRmse = 0.0, withoutRmse = 0.0;
};
template <typename Place>
StripRed stripRed(const FromAbove& images, Place xMm, double fromMm, double toMm) {
    const uint32_t size = kFromAboveSize;
    StripRed strip;
    for (uint32_t y = 8; y < size - 8; ++y)
        for (uint32_t x = 0; x < size; ++x) {
            const double place = xMm(x);
            if (place < fromMm || place > toMm) continue;
            const double r = double(images.truth.rgba32f[4 * (size_t(y) * size + x)]);
            const double s = pixelLinear(images.skin, x, y).r, w = pixelLinear(images.other, x, y).r;
            strip.skin += s;
            strip.without += w;
            strip.truth += r;
            strip.skinRmse += (s - r) * (s - r);
            strip.withoutRmse += (w - r) * (w - r);
            ++strip.pixels;
        }
    const double n = double(std::max<size_t>(strip.pixels, 1));
    strip.skin /= n;
    strip.without /= n;
    strip.truth /= n;
    strip.skinRmse = std::sqrt(strip.skinRmse / n);
    strip.withoutRmse = std::sqrt(strip.withoutRmse / n);
    return strip;
}

// Prints the strip's figures under `what` and expects the term that `without` lacks to carry the
// reference's red there: skin's RMSE below rmseRatio times skin's without it, its mean within
// meanTolerance of the reference's.
void expectStripCarriesTheRed(const StripRed& strip, const char* what, const char* term, double rmseRatio,
                              double meanTolerance) {
    std::printf(
        "[ fidelity ] %s: %zu pixels, red skin %.4f (without %s %.4f) reference %.4f; RMSE %.4f (without %.4f)\n", what,
        strip.pixels, strip.skin, term, strip.without, strip.truth, strip.skinRmse, strip.withoutRmse);
    EXPECT_GT(strip.pixels, size_t(100));
    EXPECT_LT(strip.skinRmse, rmseRatio * strip.withoutRmse);
    EXPECT_NEAR(strip.skin, strip.truth, meanTolerance * strip.truth);
}

// A skin height field over a square 2 halfM wide, n x n quads: surface(x, y) gives the height z and
// the (unnormalised) normal at (x, y), metres.
template <typename Surface>
Primitive makeHeightField(double halfM, uint32_t n, Surface surface) {
    Primitive field;
    for (uint32_t j = 0; j <= n; ++j)
        for (uint32_t i = 0; i <= n; ++i) {
            const double x = -halfM + 2.0 * halfM * i / n, y = -halfM + 2.0 * halfM * j / n;
            glm::dvec3 normal(0.0);
            const double z = surface(x, y, normal);
            Vertex v;
            v.positionOs = glm::vec3(float(x), float(y), float(z));
            v.normalOs = glm::vec3(glm::normalize(normal));
            v.uv0 = glm::vec2(float(i) / float(n), float(j) / float(n));
            field.vertices.push_back(v);
            field.boundsOs.extend(v.positionOs);
        }
    for (uint32_t j = 0; j < n; ++j)
        for (uint32_t i = 0; i < n; ++i) {
            const uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
            field.indices.insert(field.indices.end(), {a, b, d, a, d, c});
        }
    recomputeCurvature(field);
    field.material = 0;
    return field;
}

// A groove z = -depthM exp(-x^2 / 2 widthM^2) along y in a skin plane 2 halfM square, n x n quads.
Primitive makeGroove(double depthM, double widthM, double halfM, uint32_t n) {
    return makeHeightField(halfM, n, [&](double x, double, glm::dvec3& normal) {
        const double e = std::exp(-x * x / (2.0 * widthM * widthM));
        normal = glm::dvec3(-depthM * x / (widthM * widthM) * e, 0.0, 1.0);
        return -depthM * e;
    });
}

// A saddle z = (x^2 - y^2) / (2 radiusM) in a skin square 2 halfM wide, n x n quads: principal
// curvatures +-1 / radiusM, mean curvature 0.
Primitive makeSaddle(double radiusM, double halfM, uint32_t n) {
    return makeHeightField(halfM, n, [&](double x, double y, glm::dvec3& normal) {
        normal = glm::dvec3(-x / radiusM, y / radiusM, 1.0);
        return (x * x - y * y) / (2.0 * radiusM);
    });
}

// The pixels whose reference curvature is concave (below -0.01 per profile mm): a groove's floor.
auto concavePixels(const ReferenceImage& truth) {
    return [&truth](size_t i) { return truth.curvaturePerMm[i] <= -0.01f; };
}

// Red's RMSE of skin over Lambert's against the reference on the skin pixels (index y * size + x)
// that `keep` accepts.
template <typename Keep>
double redOverLambert(const FromAbove& images, Keep keep, size_t& pixels) {
    double skinRed = 0.0, lambertRed = 0.0;
    pixels = 0;
    for (size_t i = 0; i < images.truth.skin.size(); ++i) {
        if (!images.truth.skin[i] || !keep(i)) continue;
        ++pixels;
        skinRed += std::pow(double(images.skin.rgba32f[4 * i]) - double(images.truth.rgba32f[4 * i]), 2.0);
        lambertRed += std::pow(double(images.other.rgba32f[4 * i]) - double(images.truth.rgba32f[4 * i]), 2.0);
    }
    return std::sqrt(skinRed / lambertRed);
}

TEST_F(SkinFidelity, ConcaveGrooveIsCloserToTheReferenceThanLambert) {
    Scene scene =
        makeScene({{makeGroove(0.003, 0.0025, 0.02, 80), glm::mat4(1.0f)}}, {skinMaterial({0.8f, 0.6f, 0.5f})});
    const Light light = shadowedDirectionalLight({0.6f, 0.0f, -0.8f}, 3.0f);
    scene.lights = {light};
    const uint32_t size = kFromAboveSize;
    const FromAbove images = renderFromAbove(context(), scene, SkinFeatures::none());
    const ReferenceImage& truth = images.truth;
    const RenderedImage &skin = images.skin, &lambert = images.other;
    size_t pixels = 0;
    const double ratio = skinOverLambert(truth, skin, lambert, pixels, concavePixels(truth));
    // Red alone, the channel that scatters furthest (the crease's own walls shadow the floor's
    // edges: red must stay close there too).
    size_t redPixels = 0;
    const double redRatio = redOverLambert(images, concavePixels(truth), redPixels);
    std::printf("[ fidelity ] groove floor: %zu concave pixels, skin / Lambert RMSE %.3f, red %.3f\n", pixels, ratio,
                redRatio);
    EXPECT_GT(pixels, size_t(size) * 10);
    EXPECT_LT(ratio, 0.3);
    EXPECT_LT(redRatio, 0.7);
}

// The same groove under a light low across it (25 degrees up): the wall nearer the light faces
// away from it, the far wall and the floor face it. Each channel's prefiltered geometric normal
// near the floor averages both walls, so its N.L is the mean of N.L over a neighbourhood that
// takes in the facing-away wall at its negative N.L, where the diffusion integral counts that
// wall's light as none; skin reads the point's own N.L where the channel's falls below it
// (preskinSkinNoL). Red over the concave skin: 0.437 of Lambert's error against the reference
// (0.609 with the channel's N.L alone).
TEST_F(SkinFidelity, GrooveLitAcrossKeepsTheLightOfItsLitWallInRed) {
    Scene scene =
        makeScene({{makeGroove(0.003, 0.0025, 0.02, 80), glm::mat4(1.0f)}}, {skinMaterial({0.8f, 0.6f, 0.5f})});
    const glm::vec3 travel =
        glm::normalize(glm::vec3(std::cos(glm::radians(25.0f)), 0.0f, -std::sin(glm::radians(25.0f))));
    scene.lights = {shadowedDirectionalLight(travel, 3.0f)};
    const FromAbove images = renderFromAbove(context(), scene, SkinFeatures::none());
    size_t pixels = 0;
    const double redRatio = redOverLambert(images, concavePixels(images.truth), pixels);
    std::printf("[ fidelity ] groove lit across at 25 degrees: %zu concave pixels, red skin / Lambert RMSE %.3f\n",
                pixels, redRatio);
    EXPECT_GT(pixels, size_t(kFromAboveSize) * 10);
    EXPECT_LT(redRatio, 0.5);
}

// A sky whose radiance is a cosine lobe about a direction 25 degrees over the horizon across a
// groove along y (towards -x), over a faint uniform floor: an environment with a strong linear band.
Environment skyAcrossTheGroove() {
    const glm::vec3 toSky =
        glm::normalize(glm::vec3(-std::cos(glm::radians(25.0f)), 0.0f, std::sin(glm::radians(25.0f))));
    EquirectImage sky;
    sky.width = 64;
    sky.height = 32;
    for (uint32_t y = 0; y < sky.height; ++y)
        for (uint32_t x = 0; x < sky.width; ++x) {
            const glm::vec3 d =
                EquirectImage::directionAt((float(x) + 0.5f) / float(sky.width), (float(y) + 0.5f) / float(sky.height));
            const float radiance = 0.05f + 2.0f * std::max(glm::dot(d, toSky), 0.0f);
            sky.rgb.insert(sky.rgb.end(), {radiance, radiance, radiance});
        }
    return Environment::fromImage(std::move(sky));
}

// The SH ambient on curved skin against the reference, under a sky with a strong linear band
// (skyAcrossTheGroove): red over the groove's concave floor, and over the centre of a saddle of
// principal radii +-4 mm (mean curvature 0, so the SH transfer is Lambert's there and skin differs
// from Lambert by its per-channel normals alone). Two forms that brought the bundled head closer
// are farther here (docs/fidelity.md, "The SH ambient in creases"): the linear band held at the
// point's own normal as each light's N.L is held (groove floor 0.254 -> 0.349: a neighbour's
// irradiance, unlike a light's N.L, is not clamped at zero, so their linear mean is the right
// one), and the linear band at the length of the basis's mean normal instead of the transfer's
// (saddle centre 0.662 -> 0.943: the reference is brighter than Lambert there, not darker).
TEST_F(SkinFidelity, GrooveAndSaddleUnderASkyAreCloserToTheReferenceThanLambert) {
    const Environment sky = skyAcrossTheGroove();
    Scene groove =
        makeScene({{makeGroove(0.003, 0.0025, 0.02, 80), glm::mat4(1.0f)}}, {skinMaterial({0.8f, 0.6f, 0.5f})});
    const FromAbove grooveImages = renderFromAbove(context(), groove, SkinFeatures::none(), 0.06f, &sky);
    size_t floorPixels = 0;
    const double floorRed = redOverLambert(grooveImages, concavePixels(grooveImages.truth), floorPixels);

    Scene saddle = makeScene({{makeSaddle(0.004, 0.016, 128), glm::mat4(1.0f)}}, {skinMaterial({0.8f, 0.6f, 0.5f})});
    const FromAbove saddleImages = renderFromAbove(context(), saddle, SkinFeatures::none(), 0.06f, &sky);
    // The centre, within 5 mm of the axes (the square's edges, where the reference's
    // neighbourhood ends, 11 mm away): 20 mm across at z = 0 seen from 60 mm.
    const uint32_t size = kFromAboveSize;
    const auto placeMm = [&](size_t xy) { return (double(xy) + 0.5 - 0.5 * size) * 20.0 / size; };
    size_t centrePixels = 0;
    const double centreRed = redOverLambert(
        saddleImages,
        [&](size_t i) { return std::abs(placeMm(i % size)) <= 5.0 && std::abs(placeMm(i / size)) <= 5.0; },
        centrePixels);
    std::printf(
        "[ fidelity ] under a sky 25 degrees up: groove floor %zu pixels, red skin / Lambert RMSE %.3f; "
        "saddle centre %zu pixels, %.3f\n",
        floorPixels, floorRed, centrePixels, centreRed);
    EXPECT_GT(floorPixels, size_t(size) * 10);
    EXPECT_GT(centrePixels, size_t(size) * 10);
    EXPECT_LT(floorRed, 0.3);
    EXPECT_LT(centreRed, 0.8);
}

// The same groove seen by the shadow map's filter alone (the Shadow debug view: its filtered
// visibility) on a map coarse enough that the filter's window (4 texels of 0.4 mm at high, 3 at
// low) spans much of the floor's curve. The light is steeper than the groove's steepest wall
// (slope 0.75 against 0.73), so nothing shadows any of it: the visibility must be 1 on the floor.
// A filter that takes the floor's tangent plane for the receiver finds the walls within its window
// above that plane and shadows the floor: without the concave rise (preskinSkinConcaveRiseM) the
// floor's mean visibility is 0.961 at high (lowest 0.915), 0.989 at low (lowest 0.952).
TEST_F(SkinFidelity, ConcaveGrooveFloorIsNotShadowedByItsOwnWallsInTheShadowFilter) {
    Scene scene =
        makeScene({{makeGroove(0.003, 0.0025, 0.02, 80), glm::mat4(1.0f)}}, {skinMaterial({0.8f, 0.6f, 0.5f})});
    scene.lights = {shadowedDirectionalLight({0.6f, 0.0f, -0.8f}, 3.0f)};
    const View view = perspectiveView(
        glm::inverse(glm::lookAt(glm::vec3(0.0f, 0.0f, 0.06f), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f))),
        2.0f * std::atan(0.01f / 0.06f), 1.0f, 0.01f, 1.0f);
    RenderSettings settings;
    settings.specular = false;
    settings.shadowMapSize = 128;
    settings.debugView = DebugView::Shadow;
    const uint32_t size = kFromAboveSize;
    for (const SkinQuality quality : {SkinQuality::High, SkinQuality::Low}) {
        settings.skinQuality = quality;
        Renderer renderer(context(), scene, Environment::constant(glm::vec3(0.0f)), &LutSet::loadDefault(), settings);
        const RenderedImage visibility = renderer.render(view, size, size, OutputEncoding::LinearFloat);
        dumpImage(quality == SkinQuality::High ? "groove_visibility_high" : "groove_visibility_low", visibility);
        // The floor, |x| within 1 mm of the groove's axis (0.4 of its width; concave to 1), away
        // from the image's top and bottom rows: 20 mm across at z = 0 seen from 60 mm, 63 mm to the floor.
        double sum = 0.0, lowest = 1.0;
        size_t pixels = 0;
        for (uint32_t y = 8; y < size - 8; ++y)
            for (uint32_t x = 0; x < size; ++x) {
                const double xMm = (double(x) + 0.5 - 0.5 * size) * 20.0 / size * 63.0 / 60.0;
                if (std::abs(xMm) > 1.0) continue;
                const double v = pixelLinear(visibility, x, y).r;
                sum += v;
                lowest = std::min(lowest, v);
                ++pixels;
            }
        std::printf(
            "[ fidelity ] groove floor, %s tier, 128-texel shadow map: %zu pixels, visibility mean %.4f, lowest %.4f\n",
            quality == SkinQuality::High ? "high" : "low", pixels, sum / double(pixels), lowest);
        EXPECT_GT(pixels, size_t(200));
        EXPECT_GT(sum / double(pixels), 0.995);
        EXPECT_GT(lowest, 0.97);
    }
}

// A plate lying 1 mm above a floor (both skin, 2 mm thick, 40 mm wide), lit 30 degrees above
// the horizon across its edge: the floor beside the edge is in the plate's shadow, and the light
// the shadow takes lands on the plate's top, 3 mm above the floor, from where it scatters down
// through the profile's reach (the reference's integral over every surface). In the strip 0.5 to
// 2.5 mm from the plate's edge skin must carry that red: its error against the reference below
// 0.6 times that of skin without it (transmission off: the floor's own light only, the penumbra
// scattering across the shadow's far edge included), its mean within 40 % of the reference's.
TEST_F(SkinFidelity, ShadowOfANearbyPlateCarriesTheLightItsLitSideScatters) {
    Primitive floor = makeQuad(0.3f, 8);
    floor.material = 0;
    Primitive plate = makeBox(glm::vec3(0.04f, 0.08f, 0.002f));
    plate.material = 0;
    const float edgeX = -0.0002f;  // the plate's edge; its shadow on the floor ends at x = 5 mm
    Scene scene = makeScene(
        {{floor, glm::mat4(1.0f)}, {plate, glm::translate(glm::mat4(1.0f), glm::vec3(edgeX - 0.02f, 0.0f, 0.002f))}},
        {skinMaterial({0.8f, 0.6f, 0.5f})});
    scene.lights = {shadowedDirectionalLight({0.866f, 0.0f, -0.5f}, 3.0f)};
    const uint32_t size = kFromAboveSize;
    SkinFeatures noNeighbours;  // neither transmission nor the opposing neighbours' light
    noNeighbours.transmission = false;
    noNeighbours.opposingLight = false;
    const FromAbove images = renderFromAbove(context(), scene, noNeighbours);
    // The view spans x = -10 .. 10 mm at the floor.
    const StripRed strip = stripRed(
        images, [&](uint32_t x) { return (double(x) + 0.5) / size * 20.0 - 10.0; }, 0.5, 2.5);
    expectStripCarriesTheRed(strip, "floor beside a plate's edge, in its shadow", "the plate's light", 0.6, 0.4);
}

// The underside of a plate 8 mm thick lying 1 mm above a floor, both skin and one mesh, seen from
// below through the floor (its back faces are culled, as the reference skips them), lit 30
// degrees above the horizon from beyond the plate's edge: the underside faces away from the
// light, the floor beneath the edge is lit, and the floor's light crosses the 1 mm gap within
// red's reach (the reference's integral over every surface; the lips' line is such a gap). In the
// strip 0.3 to 3 mm in from the edge skin must carry that red: its error against the reference
// below 0.5 times that of skin without it (transmission off: through 8 mm the plate's lit top
// sends nothing), its mean within 30 % of the reference's.
TEST_F(SkinFidelity, UndersideOfAnOverhangCarriesTheLightOfTheLitFloorAcrossTheGap) {
    const Scene scene = overhangScene();
    const uint32_t size = kFromAboveSize;
    SkinFeatures noNeighbours;  // neither transmission nor the opposing neighbours' light
    noNeighbours.transmission = false;
    noNeighbours.opposingLight = false;
    const FromAbove images = renderFromAbove(context(), scene, noNeighbours, -0.06f);
    // From below the image's x runs along -x; the view spans 20.3 mm at the underside.
    const StripRed strip = stripRed(
        images, [&](uint32_t x) { return -((double(x) + 0.5) / size * 2.0 - 1.0) * 10.0 * 0.061 / 0.06; }, -3.0, -0.3);
    expectStripCarriesTheRed(strip, "an overhang's underside 1 mm over a lit floor", "the floor's light", 0.5, 0.3);
}

}  // namespace
}  // namespace preskin::test
