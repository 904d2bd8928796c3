#include "support/SkinTestSupport.h"

#include "support/ImageCompare.h"
#include "support/TestLights.h"
#include "support/TestScenes.h"

#include <preskin/Curvature.h>

#include <glm/gtc/matrix_transform.hpp>

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>

namespace preskin::test {

std::vector<SphereHit> traceSphere(const View& view, uint32_t width, uint32_t height, const glm::dvec3& centerWs,
                                   double radiusM) {
    const glm::dmat4 worldFromClip = glm::inverse(glm::dmat4(view.eye().clipFromWorld()));
    // Ray through image position (px, py) in pixels: from the near plane (reversed Z: depth 1)
    // towards depth 0.5, which works for perspective and orthographic projections.
    auto hit = [&](double px, double py, glm::dvec3& p) {
        const glm::dvec2 ndc(px / width * 2.0 - 1.0, py / height * 2.0 - 1.0);
        const glm::dvec4 a = worldFromClip * glm::dvec4(ndc, 1.0, 1.0);
        const glm::dvec4 b = worldFromClip * glm::dvec4(ndc, 0.5, 1.0);
        const glm::dvec3 origin = glm::dvec3(a) / a.w;
        const glm::dvec3 dir = glm::normalize(glm::dvec3(b) / b.w - origin);
        const glm::dvec3 oc = origin - centerWs;
        const double half = glm::dot(oc, dir);
        const double c = glm::dot(oc, oc) - radiusM * radiusM;
        const double disc = half * half - c;
        if (disc <= 0.0) return false;
        const double t = -half - std::sqrt(disc);
        if (t <= 0.0) return false;
        p = origin + dir * t;
        return true;
    };
    std::vector<SphereHit> hits(size_t(width) * height);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            SphereHit& h = hits[size_t(y) * width + x];
            glm::dvec3 p;
            bool inside = true;
            for (int dy = -1; dy <= 2 && inside; ++dy)
                for (int dx = -1; dx <= 2 && inside; ++dx) inside = hit(double(x) + dx, double(y) + dy, p);
            h.interior = inside && hit(x + 0.5, y + 0.5, h.positionWs);
        }
    return hits;
}

Environment makeEnvironment(uint32_t width, const std::function<glm::vec3(const glm::vec3&)>& radiance) {
    static std::atomic<int> counter{0};
    const uint32_t height = width / 2;
    RenderedImage image;
    image.width = width;
    image.height = height;
    image.encoding = OutputEncoding::LinearFloat;
    image.rgba32f.resize(size_t(width) * height * 4);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            const float u = (float(x) + 0.5f) / float(width);
            const float v = (float(y) + 0.5f) / float(height);
            const glm::vec3 l = radiance(EquirectImage::directionAt(u, v));
            float* px = &image.rgba32f[(size_t(y) * width + x) * 4];
            px[0] = l.r;
            px[1] = l.g;
            px[2] = l.b;
            px[3] = 1.0f;
        }
    const std::filesystem::path dir = std::filesystem::temp_directory_path() /
        ("preskin_test_env_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    std::filesystem::create_directories(dir);
    const std::filesystem::path file = dir / "environment.exr";
    try {
        writeImage(file, image);
        Environment env = Environment::load(file);
        std::filesystem::remove_all(dir);
        return env;
    } catch (...) {
        std::error_code ec;
        std::filesystem::remove_all(dir, ec);
        throw;
    }
}

int addNormalMap(Scene& scene, uint32_t width, uint32_t height, const std::function<glm::vec3(glm::vec2)>& normalAt) {
    Image image;
    image.name = "procedural normal map";
    image.width = width;
    image.height = height;
    image.rgba8.resize(size_t(width) * height * 4);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            const glm::vec2 uv((float(x) + 0.5f) / float(width), (float(y) + 0.5f) / float(height));
            const glm::vec3 n = glm::normalize(normalAt(uv)) * 0.5f + 0.5f;
            uint8_t* px = &image.rgba8[(size_t(y) * width + x) * 4];
            for (int c = 0; c < 3; ++c)
                px[c] = static_cast<uint8_t>(std::lround(std::clamp(n[c], 0.0f, 1.0f) * 255.0f));
            px[3] = 255;
        }
    scene.images.push_back(std::move(image));
    return static_cast<int>(scene.images.size()) - 1;
}

void recomputeCurvature(Primitive& primitive) {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    for (const Vertex& v : primitive.vertices) {
        positions.push_back(v.positionOs);
        normals.push_back(v.normalOs);
    }
    const std::vector<float> curvature = computeVertexCurvature(positions, normals, primitive.indices);
    for (size_t i = 0; i < primitive.vertices.size(); ++i) primitive.vertices[i].curvaturePerM = curvature[i];
}

glm::dvec3 pixelLinear(const RenderedImage& image, uint32_t x, uint32_t y) {
    const float* p = &image.rgba32f[(size_t(y) * image.width + x) * 4];
    return {p[0], p[1], p[2]};
}

double srgbDifference(const glm::dvec3& a, const glm::dvec3& b) {
    double d = 0.0;
    for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(srgb255(a[c]) - srgb255(b[c])));
    return d;
}

size_t countDifferingPixels(const RenderedImage& a, const RenderedImage& b, double steps) {
    size_t n = 0;
    for (uint32_t y = 0; y < a.height; ++y)
        for (uint32_t x = 0; x < a.width; ++x)
            if (srgbDifference(pixelLinear(a, x, y), pixelLinear(b, x, y)) > steps) ++n;
    return n;
}

double maxSrgbDifference(const RenderedImage& a, const RenderedImage& b) {
    double worst = 0.0;
    for (uint32_t y = 0; y < a.height; ++y)
        for (uint32_t x = 0; x < a.width; ++x)
            worst = std::max(worst, srgbDifference(pixelLinear(a, x, y), pixelLinear(b, x, y)));
    return worst;
}

namespace {

constexpr double kPiD = 3.14159265358979323846;

glm::dvec3 schlick(double F0, double VoH) {
    return glm::dvec3(F0 + (1.0 - F0) * std::pow(1.0 - std::clamp(VoH, 0.0, 1.0), 5.0));
}

// GGX D * height-correlated Smith V * Schlick F for perceptual roughness r.
glm::dvec3 ggxLobe(double F0, double r, double NoL, double NoV, double NoH, double VoH) {
    const double alpha = std::max(r * r, 1e-3);
    const double a2 = alpha * alpha;
    const double denom = NoH * NoH * (a2 - 1.0) + 1.0;
    const double D = a2 / (kPiD * denom * denom);
    const double Vis =
        0.5 / (NoL * std::sqrt(NoV * NoV * (1.0 - a2) + a2) + NoV * std::sqrt(NoL * NoL * (1.0 - a2) + a2));
    return D * Vis * schlick(F0, VoH);
}

}  // namespace

DiffuseLookup lutDiffuse(const LutSet& luts) {
    return [&luts](double NoL, double curvaturePerMm) {
        return glm::dvec3(luts.lookupDiffuse(float(NoL), float(curvaturePerMm)));
    };
}

Light sphereLight() {
    Light light;
    light.type = LightType::Directional;
    light.directionWs = glm::normalize(glm::vec3(-0.8f, -0.35f, 0.3f));
    light.color = glm::vec3(1.0f, 0.96f, 0.92f);
    light.intensity = 3.0f;
    return light;
}

View sphereView(double radiusM) {
    const glm::vec3 eye = glm::vec3(0.3f, 0.4f, 3.6f) * float(radiusM);
    const glm::mat4 worldFromView = glm::inverse(glm::lookAt(eye, glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f)));
    return perspectiveView(worldFromView, 0.7f, 1.0f, 0.1f * float(radiusM), 10.0f * float(radiusM));
}

SphereAgreement compareWithSkinReference(const RenderedImage& image, const View& view, double radiusM,
                                         const Light& light, const SkinMaterial& skin, const glm::dvec3& albedo,
                                         double roughness, const DiffuseLookup& diffuse) {
    const uint32_t size = image.width;
    const double curvaturePerMm = 1.0 / radiusM * 0.001 / double(skin.scatterScale);
    const std::vector<SphereHit> hits = traceSphere(view, size, size, glm::dvec3(0.0), radiusM);
    const glm::dvec3 L = -glm::normalize(glm::dvec3(light.directionWs));
    const glm::dvec3 E = glm::dvec3(light.color) * double(light.intensity);
    const glm::dvec3 eye(view.eye().positionWs);
    const double F0 = 0.028 * double(skin.specularIntensity);
    SphereAgreement a;
    for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 0; x < size; ++x) {
            const SphereHit& h = hits[size_t(y) * size + x];
            if (!h.interior) continue;
            const glm::dvec3 N = glm::normalize(h.positionWs);
            const glm::dvec3 V = glm::normalize(eye - h.positionWs);
            const glm::dvec3 H = glm::normalize(L + V);
            const double NoL = glm::dot(N, L);
            const double VoH = glm::dot(V, H);
            const glm::dvec3 D = diffuse(NoL, curvaturePerMm);
            const glm::dvec3 diffuseScale = (glm::dvec3(1.0) - schlick(F0, VoH)) * albedo / kPiD * E;
            glm::dvec3 specular(0.0);
            if (NoL > 0.0) {
                const double NoV = std::max(glm::dot(N, V), 1e-4);
                const double NoH = std::clamp(glm::dot(N, H), 0.0, 1.0);
                const double r0 = std::clamp(roughness * double(skin.lobeRoughness0), 0.03, 1.0);
                const double r1 = std::clamp(roughness * double(skin.lobeRoughness1), 0.03, 1.0);
                specular = glm::mix(ggxLobe(F0, r0, NoL, NoV, NoH, VoH), ggxLobe(F0, r1, NoL, NoV, NoH, VoH),
                                    double(skin.lobeMix)) *
                    NoL * E;
            }
            const glm::dvec3 expected = diffuseScale * D + specular;
            const glm::dvec3 lambert = diffuseScale * std::clamp(NoL, 0.0, 1.0) + specular;
            const glm::dvec3 got = pixelLinear(image, x, y);
            const double diff = srgbDifference(got, expected);
            a.worst = std::max(a.worst, diff);
            ++a.interior;
            if (diff <= 2.0) ++a.within;
            if (srgbDifference(got, lambert) <= 2.0) ++a.lambertWithin;
        }
    return a;
}

Scene overhangScene() {
    Primitive floor = makeQuad(0.08f, 80);  // 1 mm cells, facing up
    Primitive underside = makeQuad(0.04f, 40);
    for (Vertex& v : underside.vertices) {  // facing down, x from -40 to 0 mm, 1 mm up
        v.positionOs = glm::vec3(v.positionOs.x - 0.02f, v.positionOs.y, 0.001f);
        v.normalOs = glm::vec3(0.0f, 0.0f, -1.0f);
    }
    for (size_t t = 0; t < underside.indices.size(); t += 3)
        std::swap(underside.indices[t + 1], underside.indices[t + 2]);
    underside.boundsOs = {};
    for (const Vertex& v : underside.vertices) underside.boundsOs.extend(v.positionOs);
    floor.material = underside.material = 0;
    Primitive body = makeBox(glm::vec3(0.04f, 0.04f, 0.008f));  // the plate's other faces, casting its shadow
    body.material = 0;
    Scene scene = makeScene({{body, glm::translate(glm::mat4(1.0f), glm::vec3(-0.02f, 0.0f, 0.00501f))}},
                            {skinMaterial({0.8f, 0.6f, 0.5f})});
    Mesh gap;
    gap.primitives = {floor, underside};
    scene.instances.push_back({int(scene.meshes.size()), glm::mat4(1.0f), ""});
    scene.meshes.push_back(std::move(gap));
    scene.lights = {shadowedDirectionalLight({-0.866f, 0.0f, -0.5f}, 3.0f)};
    return scene;
}

StraightEdgeScene straightEdgeScene(float planeM, float lightElevationDeg, float lightAzimuthDeg, float casterWidthM) {
    const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), glm::radians(25.0f), glm::vec3(0.0f, 0.0f, 1.0f));
    Material plate;
    plate.baseColorFactor = glm::vec4(0.2f, 0.2f, 0.2f, 1.0f);
    plate.metallicFactor = 0.0f;
    plate.doubleSided = true;
    Primitive plane = makeQuad(planeM, 2);  // in z = 0, facing +z
    plane.material = 0;
    Primitive caster = makeQuad(0.6f, 2);
    caster.material = 1;
    // The light travels along (cos a cos e, sin a cos e, -sin e) before the turn: the plate's edge,
    // 30 mm up, casts its shadow at x' = 0 from x' = -30 mm cot(e) cos(a).
    const float e = glm::radians(lightElevationDeg), a = glm::radians(lightAzimuthDeg);
    const float edgeM = -0.03f * std::cos(e) / std::sin(e) * std::cos(a);
    StraightEdgeScene out;
    out.scene =
        makeScene({{plane, glm::mat4(1.0f)},
                   {caster,
                    turn * glm::translate(glm::mat4(1.0f), glm::vec3(edgeM - 0.5f * casterWidthM, 0.0f, 0.03f)) *
                        glm::scale(glm::mat4(1.0f), glm::vec3(casterWidthM / 0.6f, 1.0f, 1.0f))}},
                  {skinMaterial(glm::vec3(0.8f, 0.6f, 0.5f)), plate});
    Light light;
    light.type = LightType::Directional;
    light.directionWs = glm::normalize(
        glm::vec3(turn * glm::vec4(std::cos(a) * std::cos(e), std::sin(a) * std::cos(e), -std::sin(e), 0.0f)));
    light.intensity = 3.0f;
    light.castsShadow = true;
    out.scene.lights = {light};
    const float spanM = 0.012f;
    const glm::mat4 worldFromView = glm::inverse(glm::lookAt(glm::vec3(0.0f, 0.0f, 0.08f), glm::vec3(0.0f),
                                                             glm::vec3(turn * glm::vec4(0.0f, 1.0f, 0.0f, 0.0f))));
    const float aspect = float(out.width) / float(out.height);
    out.view = perspectiveView(worldFromView, 2.0f * std::atan(0.5f * spanM / aspect / 0.08f), aspect, 0.01f, 1.0f);
    return out;
}

std::vector<glm::dvec3> columnMeans(const std::vector<float>& rgba, uint32_t width, uint32_t height) {
    std::vector<glm::dvec3> means(width, glm::dvec3(0.0));
    for (uint32_t x = 0; x < width; ++x) {
        for (uint32_t y = 0; y < height; ++y)
            for (int c = 0; c < 3; ++c) means[x][c] += double(rgba[(size_t(y) * width + x) * 4 + size_t(c)]);
        means[x] /= double(height);
    }
    return means;
}

glm::dvec3 largestColumnDifference(const RenderedImage& render, const ReferenceImage& truth) {
    const uint32_t width = truth.width, height = truth.height;
    const std::vector<glm::dvec3> rendered = columnMeans(render.rgba32f, width, height);
    const std::vector<glm::dvec3> reference = columnMeans(truth.rgba32f, width, height);
    glm::dvec3 lit(0.0);
    for (uint32_t x = width - 4; x < width; ++x) lit += reference[x] / 4.0;
    glm::dvec3 worst(0.0);
    for (uint32_t x = 0; x < width; ++x) worst = glm::max(worst, glm::abs(rendered[x] - reference[x]) / lit);
    return worst;
}

StereoAgainstMono stereoAgainstMono(Context& context, const RenderSettings& settings) {
    Primitive sphere = makeSphere(0.04f, 64, 32);
    sphere.material = 0;
    Scene scene = makeScene({{sphere, glm::mat4(1.0f)}}, {skinMaterial(glm::vec3(0.8f, 0.6f, 0.5f))});
    Light light = sphereLight();
    light.castsShadow = true;
    scene.lights = {light};
    Renderer renderer(context, scene, Environment::constant(glm::vec3(0.05f)), &LutSet::loadDefault(), settings);
    const glm::mat4 worldFromHead =
        glm::inverse(glm::lookAt(glm::vec3(0.0f, 0.0f, 0.25f), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f)));
    const FovAngles fov{-0.3f, 0.3f, 0.3f, -0.3f};
    const View stereo = stereoView(worldFromHead, 0.064f, fov, fov, 0.05f, 2.0f);
    StereoAgainstMono out;
    const RenderedImage both = renderer.render(stereo, 96, 96, OutputEncoding::LinearFloat);
    out.stereoStats = renderer.frameStats();
    for (uint32_t e = 0; e < 2; ++e)
        out.worst[e] = maxSrgbDifference(eyeImage(both, e),
                                         renderer.render(View(stereo.eyes[e]), 96, 96, OutputEncoding::LinearFloat));
    return out;
}

}  // namespace preskin::test
