// Hostile and unusual input aimed at the newer features, through the `preskin` tool: EXR
// environments in every layout OpenEXR allows (tiled, an offset data window, channels stored in
// another order), Radiance files in XYZ and with EXPOSURE, environments in data URIs and with
// negative radiance, area lights far smaller than anything visible, texture-space diffusion and
// curvature bakes on meshes without a UV layout, out-of-range Khronos transmission colours, and
// the messages that name what is wrong. Each case ends as the README promises: a render (with a
// warning where the input is unusual but allowed) or exit 1 with one line naming file, field and
// problem; never a signal.
#include "e2e/HostileInput.h"
#include "support/ImageCompare.h"

#include <preskin/Environment.h>

#include <OpenImageIO/imageio.h>
#include <fmt/core.h>
#include <gtest/gtest.h>
#include <zlib.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <string>
#include <vector>

namespace preskin::test {
namespace {

using nlohmann::json;

// An equirectangular EXR, 64 x 32, from `texel(x, y)` (RGB), in the layout asked for.
struct ExrLayout {
    int tile = 0;      // tile size; 0: scanlines
    int x = 0, y = 0;  // data window origin
    bool half = true;
    std::vector<std::string> channels = {"R", "G", "B"};
};

fs::path writeExr(const fs::path& path, const ExrLayout& layout, glm::vec3 (*texel)(int, int)) {
    OIIO::ImageSpec spec(64, 32, 3, layout.half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT);
    spec.x = layout.x;
    spec.y = layout.y;
    spec.full_x = layout.x;
    spec.full_y = layout.y;
    spec.channelnames = layout.channels;
    if (layout.tile > 0) {
        spec.tile_width = layout.tile;
        spec.tile_height = layout.tile;
    }
    std::vector<float> pixels(64 * 32 * 3);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 64; ++x) {
            const glm::vec3 rgb = texel(x, y);
            for (int c = 0; c < 3; ++c) {
                // Stored in the order of the channel names.
                const std::string& name = layout.channels[size_t(c)];
                const int source = name == "R" ? 0 : name == "G" ? 1 : 2;
                pixels[size_t(y * 64 + x) * 3 + size_t(c)] = rgb[source];
            }
        }
    auto out = OIIO::ImageOutput::create("openexr");
    EXPECT_TRUE(out && out->open(path.string(), spec) && out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) &&
                out->close());
    return path;
}

glm::vec3 gradient(int x, int y) { return {0.1f + 0.01f * float(x), 0.2f + 0.02f * float(y), 0.5f}; }

TEST_F(HostileInput, ExrEnvironmentsInEveryLayoutLoadWithTheirOwnValues) {
    const std::vector<std::pair<std::string, ExrLayout>> layouts = {
        {"tiled16_half", {16, 0, 0, true}},  {"tiled64_float", {64, 0, 0, false}},
        {"tiled8_float", {8, 0, 0, false}},  {"offset", {0, 100, -7, true}},
        {"offset_tiled", {16, -5, 3, true}}, {"bgr", {0, 0, 0, true, {"B", "G", "R"}}},
    };
    for (const auto& [name, layout] : layouts) {
        const fs::path exr = writeExr(dir_ / (name + ".exr"), layout, &gradient);
        // The environment's own radiance, texel for texel (half precision).
        const Environment env = Environment::load(exr);
        for (int y = 0; y < 32; y += 7)
            for (int x = 0; x < 64; x += 9) {
                const glm::vec3 want = gradient(x, y), got = env.image().texel(uint32_t(x), uint32_t(y));
                EXPECT_LT(glm::length(got - want), 2e-3f) << name << " at " << x << ", " << y;
            }
        // And through the tool: a render, exit 0, nothing on stderr.
        const ProcessResult r = run(render(kTriangle, {"--env", exr.string()}), kRenderMemory);
        EXPECT_EQ(r.exitCode, 0) << name << ": " << r.err;
        EXPECT_TRUE(fs::exists(out_)) << name;
        fs::remove(out_);
    }
}

// Radiance files in CIE XYZ (FORMAT=32-bit_rle_xyze), with EXPOSURE lines, without a FORMAT line
// and with another program's signature: each as the same radiance in RGB.
TEST_F(HostileInput, RadianceXyzeExposureAndOtherHeadersLoad) {
    // One flat scanline of 16 texels of one RGBE value, 8 rows (width < 8 would be flat anyway).
    auto radiance = [&](const std::string& name, const std::string& headerLines, std::array<uint8_t, 4> rgbe) {
        std::string bytes = headerLines + "\n-Y 8 +X 16\n";
        for (int i = 0; i < 16 * 8; ++i) bytes.append(reinterpret_cast<const char*>(rgbe.data()), 4);
        writeText(dir_ / name, bytes);
        return dir_ / name;
    };
    // RGBE (128, 64, 32, 129): (0.5, 0.25, 0.125) x 2.
    const fs::path plain = radiance("plain.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n", {128, 64, 32, 129});
    const glm::vec3 rgb = Environment::load(plain).image().texel(3, 2);
    EXPECT_LT(glm::length(rgb - glm::vec3(1.0f, 0.5f, 0.25f)), 1e-6f);
    // No FORMAT line (RGBE by default), another signature: the same.
    for (const char* header : {"#?RADIANCE\n", "#?PHOTOSHOP\nFORMAT=32-bit_rle_rgbe\n"}) {
        const fs::path f = radiance("other.hdr", header, {128, 64, 32, 129});
        EXPECT_LT(glm::length(Environment::load(f).image().texel(0, 0) - rgb), 1e-6f) << header;
    }
    // EXPOSURE=2 twice: stored values are 4x the radiance.
    const fs::path exposed =
        radiance("exposed.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\nEXPOSURE=2\nEXPOSURE=2\n", {128, 64, 32, 129});
    EXPECT_LT(glm::length(Environment::load(exposed).image().texel(0, 0) - rgb * 0.25f), 1e-6f);
    // XYZE: the XYZ of equal-energy white (1, 1, 1) is RGB (1, 1, 1) with Radiance's primaries; the
    // XYZ of Radiance's red primary at Y = 0.2651 (0.5141, 0.2651, 0.0241) is RGB (1, 0, 0).
    const fs::path white = radiance("white.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_xyze\n", {128, 128, 128, 129});
    EXPECT_LT(glm::length(Environment::load(white).image().texel(5, 5) - glm::vec3(1.0f)), 1e-5f);
    // Mantissas for (0.5141, 0.2651, 0.0241) at exponent 128 (x 2^-8 of the value x 256).
    const fs::path red = radiance("red.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_xyze\n", {132, 68, 6, 128});
    const glm::vec3 r = Environment::load(red).image().texel(0, 0);
    const glm::vec3 xyz(132.0f / 256.0f, 68.0f / 256.0f, 6.0f / 256.0f);
    EXPECT_NEAR(r.x, 2.5653128f * xyz.x - 1.1668496f * xyz.y - 0.3984632f * xyz.z, 1e-5f);
    EXPECT_GT(r.x, 5.0f * std::max(std::abs(r.y), std::abs(r.z)));
    // Another FORMAT is refused by name.
    const fs::path bad = radiance("bad.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_cmyk\n", {1, 2, 3, 4});
    expectRefused(run(render(kTriangle, {"--env", bad.string()})),
                  bad.string() +
                      ": cannot decode environment image: cannot decode the Radiance HDR data: FORMAT=32-bit_rle_cmyk "
                      "is not decoded (32-bit_rle_rgbe and 32-bit_rle_xyze are)");
}

// A scene's environment as a data URI, in any media type, renders as the file does; negative
// radiance renders (as 0) with a warning naming the file and the pixels.
TEST_F(HostileInput, EnvironmentsInDataUrisAndNegativeRadiance) {
    const std::vector<uint8_t> sky =
        readBytes(fs::path(PRESKIN_SOURCE_DIR) / "tests" / "data" / "environments" / "sky.hdr");
    fs::copy_file(fs::path(PRESKIN_SOURCE_DIR) / "tests" / "data" / "environments" / "sky.hdr", dir_ / "sky.hdr");
    std::string error;
    GltfBuilder withFile = triangleScene();
    withFile.doc["extensionsUsed"] = {"PRESKIN_environment"};
    withFile.doc["extensions"]["PRESKIN_environment"] = {{"uri", "sky.hdr"}, {"intensity", 2.0}};
    ProcessResult r = run(render(withFile.writeGltf(dir_, "file")), kRenderMemory);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const RenderedImage fromFile = readPng(out_, error);
    fs::remove(out_);
    for (const char* media : {"image/vnd.radiance", "application/octet-stream", "image/x-hdr"}) {
        GltfBuilder b = withFile;
        b.doc["extensions"]["PRESKIN_environment"]["uri"] = std::string("data:") + media + ";base64," + base64(sky);
        r = run(render(b.writeGltf(dir_, "embedded")), kRenderMemory);
        ASSERT_EQ(r.exitCode, 0) << media << ": " << r.err;
        EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
        const RenderedImage embedded = readPng(out_, error);
        int largest = 0;
        EXPECT_EQ(pixelsDifferingBy(fromFile, embedded, 0, largest), 0u) << media;
        fs::remove(out_);
    }
    GltfBuilder broken = withFile;
    broken.doc["extensions"]["PRESKIN_environment"]["uri"] = "data:image/vnd.radiance;base64,#?RA";
    const fs::path brokenScene = broken.writeGltf(dir_, "broken");
    expectRefused(run(render(brokenScene)),
                  brokenScene.string() + ": extensions.PRESKIN_environment.uri: data URI: character 0 is not base64");

    // All negative: renders black from the environment, says so.
    const ExrLayout plain;
    const fs::path negative = writeExr(dir_ / "negative.exr", plain, [](int, int) { return glm::vec3(-0.5f); });
    r = run(render(kTriangle, {"--env", negative.string()}), kRenderMemory);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.err.find("preskin: warning: " + negative.string() +
                         ": pixels: 6144 of 6144 values are negative radiance (the lowest -0.5, the first at pixel "
                         "(0, 0)); taken as 0"),
              std::string::npos)
        << r.err;
}

json areaLightScene(GltfBuilder& b, const json& shape) {
    b.doc["extensionsUsed"] = {"KHR_lights_punctual", "PRESKIN_lights_area"};
    b.doc["extensions"]["KHR_lights_punctual"]["lights"] =
        json::array({{{"type", "point"}, {"intensity", 20}, {"extensions", {{"PRESKIN_lights_area", shape}}}}});
    b.doc["nodes"].push_back(
        {{"translation", {0.3, 0.3, 1.0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    b.doc["scenes"][0]["nodes"] = {0, 1};
    return b.doc;
}

double energy(const RenderedImage& image) {
    double sum = 0.0;
    for (size_t i = 0; i < image.rgba8.size(); i += 4) sum += image.rgba8[i] + image.rgba8[i + 1] + image.rgba8[i + 2];
    return sum;
}

// Sizes inside (0, 1e6] that single precision cannot hold, and sizes far below the distance: the
// light keeps its power (tests/reference/test_area_lights.cpp measures it to 1 %).
TEST_F(HostileInput, TinyRectanglesAndDiscsLightTheScene) {
    std::string error;
    GltfBuilder resolved = triangleScene();
    areaLightScene(resolved, {{"shape", "disc"}, {"radius", 0.004}});
    ProcessResult r = run(render(resolved.writeGltf(dir_, "resolved")), kRenderMemory);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const double reference = energy(readPng(out_, error));
    fs::remove(out_);
    EXPECT_GT(reference, 0.0);
    for (const json& shape : {json{{"shape", "disc"}, {"radius", 1e-300}}, json{{"shape", "disc"}, {"radius", 1e-20}},
                              json{{"shape", "rectangle"}, {"width", 1e-30}, {"height", 1e-30}}}) {
        GltfBuilder b = triangleScene();
        areaLightScene(b, shape);
        r = run(render(b.writeGltf(dir_, "tiny")), kRenderMemory);
        ASSERT_EQ(r.exitCode, 0) << shape.dump() << ": " << r.err;
        EXPECT_TRUE(r.err.empty()) << r.err;
        // A disc and a square of the same candela, both far smaller than the distance: the same light
        // (8-bit output: within 2 %).
        EXPECT_NEAR(energy(readPng(out_, error)) / reference, 1.0, 0.02) << shape.dump();
        fs::remove(out_);
    }
}

// Texture-space diffusion and curvature bakes need a UV layout: without one (no TEXCOORD_0, or
// every UV the same) both refuse, naming the scene and the material (one rule: hasUvLayout).
TEST_F(HostileInput, NoUvLayoutIsRefusedByTextureDiffusionAndCurvatureBakes) {
    GltfBuilder noUvs = triangleScene();
    noUvs.doc["meshes"][0]["primitives"][0]["attributes"].erase("TEXCOORD_0");
    noUvs.doc["materials"] = json::array({{{"name", "face"}}});
    noUvs.doc["meshes"][0]["primitives"][0]["material"] = 0;
    GltfBuilder sameUvs = triangleScene();
    const int uv = sameUvs.addFloats({0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f}, "VEC2");
    sameUvs.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = uv;
    sameUvs.doc["materials"] = json::array({{{"name", "face"}}});
    sameUvs.doc["meshes"][0]["primitives"][0]["material"] = 0;
    // The last line is the refusal (every UV the same also draws a warning about the tangents first).
    const auto expectLastLine = [&](const ProcessResult& r, const std::string& message) {
        EXPECT_EQ(r.exitCode, 1) << r.err;
        const std::string line = "preskin: error: " + message + "\n";
        EXPECT_TRUE(r.err.size() >= line.size() && r.err.compare(r.err.size() - line.size(), line.size(), line) == 0)
            << r.err;
        EXPECT_FALSE(fs::exists(out_));
    };
    for (auto* b : {&noUvs, &sameUvs}) {
        const fs::path scene = b->writeGltf(dir_, b == &noUvs ? "no_uvs" : "same_uvs");
        expectLastLine(run(render(scene, {"--skin", "all", "--diffusion", "texture"}), kRenderMemory),
                       scene.string() +
                           ": materials[0] ('face'): texture-space diffusion (--diffusion texture) lays skin out in "
                           "TEXCOORD_0, and this skin material has no UV layout (no TEXCOORD_0, or every UV the same); "
                           "use pre-integrated or screen-space diffusion");
        const fs::path bakeOut = dir_ / "maps";
        expectLastLine(run({"bake-curvature", scene.string(), "--skin", "all", "--out", bakeOut.string()}),
                       "bake-curvature: materials[0] ('face'): its triangles have no UV layout (no TEXCOORD_0, or "
                       "every UV the same); nothing baked");
        EXPECT_FALSE(fs::exists(bakeOut));
    }
    // --size 0 is not the default in disguise.
    expectRefused(
        run({"bake-curvature", kTriangle.string(), "--skin", "all", "--size", "0", "--out", (dir_ / "maps").string()}),
        "--size: value: 0 is outside [16, 8192]");
}

// A quad whose UVs span exactly (0, 0)-(1, 1) bakes every texel; charts stacked 74 deep are refused.
TEST_F(HostileInput, CurvatureBakesCoverTheWholeSquareAndRefuseStackedCharts) {
    GltfBuilder quad;
    const int position = quad.addFloats({0, 0, 0, 1, 0, 0, 1, 1, 0.2f, 0, 1, 0.2f}, "VEC3");
    const int normal = quad.addFloats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
    const int uvs = quad.addFloats({0, 1, 1, 1, 1, 0, 0, 0}, "VEC2");
    const int indices = quad.addIndices(std::vector<uint16_t>{0, 1, 2, 0, 2, 3});
    quad.doc["materials"] = json::array({{{"name", "face"}}});
    quad.addMeshNode({{"attributes", {{"POSITION", position}, {"NORMAL", normal}, {"TEXCOORD_0", uvs}}},
                      {"indices", indices},
                      {"material", 0}});
    const fs::path scene = quad.writeGltf(dir_, "quad");
    ProcessResult r = run({"bake-curvature", scene.string(), "--skin", "all", "--size", "32", "--dilation", "0",
                           "--out", (dir_ / "maps").string()});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const json map = json::parse(readFile(dir_ / "maps" / "face_curvature.json"));
    EXPECT_EQ(map["coveredFraction"].get<double>(), 1.0);

    // The same quad 74 times over in UV (74 primitives of their own accessors): stacked beyond any layout.
    GltfBuilder stacked;
    stacked.doc["materials"] = quad.doc["materials"];
    json primitives = json::array();
    for (int i = 0; i < 74; ++i) {
        const int z = stacked.addFloats(
            {0, 0, 0.01f * float(i), 1, 0, 0.01f * float(i), 1, 1, 0.01f * float(i), 0, 1, 0.01f * float(i)}, "VEC3");
        primitives.push_back({{"attributes",
                               {{"POSITION", z},
                                {"NORMAL", stacked.addFloats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3")},
                                {"TEXCOORD_0", stacked.addFloats({0, 1, 1, 1, 1, 0, 0, 0}, "VEC2")}}},
                              {"indices", stacked.addIndices(std::vector<uint16_t>{0, 1, 2, 0, 2, 3})},
                              {"material", 0}});
    }
    stacked.addMeshNode(primitives[0]);
    stacked.doc["meshes"][0]["primitives"] = primitives;
    const fs::path stackedScene = stacked.writeGltf(dir_, "stacked");
    expectRefused(run({"bake-curvature", stackedScene.string(), "--skin", "all", "--out", (dir_ / "s").string()}),
                  "bake-curvature: materials[0] ('face'): its triangles cover the map 74 times over in UV (more "
                  "than 64: charts stacked beyond any real layout); nothing baked");
}

// KHR_materials_diffuse_transmission's colour as PRESKIN_materials_skin's transmissionColor: a
// negative component refused, above 1 clamped with a warning.
TEST_F(HostileInput, DiffuseTransmissionColourOutOfRange) {
    for (const double value : {-1.0, 5.0}) {
        GltfBuilder b = triangleScene();
        b.doc["extensionsUsed"] = {"KHR_materials_diffuse_transmission"};
        b.doc["materials"] = json::array(
            {{{"extensions",
               {{"KHR_materials_diffuse_transmission",
                 {{"diffuseTransmissionFactor", 0.5}, {"diffuseTransmissionColorFactor", {value, 0.5, 0.5}}}}}}}});
        b.doc["meshes"][0]["primitives"][0]["material"] = 0;
        const fs::path scene = b.writeGltf(dir_, "transmission");
        const std::string field = scene.string() +
            ": materials[0].extensions.KHR_materials_diffuse_transmission.diffuseTransmissionColorFactor";
        const ProcessResult r = run(render(scene, {"--skin", "all"}), kRenderMemory);
        if (value < 0.0) {
            expectRefused(r, field + ": negative component");
        } else {
            EXPECT_EQ(r.exitCode, 0) << r.err;
            EXPECT_NE(r.err.find("preskin: warning: " + field + ": (5, 0.5, 0.5) has components above 1; clamped"),
                      std::string::npos)
                << r.err;
        }
    }
}

// Messages that name what is wrong: a non-finite LUT texel by texel and channel, a scene with no
// skin by its field, a bench's animated scene before anything is measured.
TEST_F(HostileInput, MessagesNameTheFieldOfTheProblem) {
    // A raw LUT folder whose diffuse texel (3, 2) holds NaN in red, its checksum made to match.
    const fs::path luts = dir_ / "luts";
    ASSERT_EQ(run({"bake", "--raw", "--out", luts.string()}).exitCode, 0);
    std::vector<uint8_t> table = readBytes(luts / "diffuse.f16");
    const size_t at = (size_t(2) * 256 + 3) * 3 * 2;
    table[at] = 0x00;
    table[at + 1] = 0x7e;  // a quiet NaN, little-endian
    writeBytes(luts / "diffuse.f16", table);
    json manifest = json::parse(readFile(luts / "manifest.json"));
    manifest["tables"]["diffuse"]["crc32"] = fmt::format("{:08x}", crc32_z(0, table.data(), table.size()));
    writeText(luts / "manifest.json", manifest.dump(2));
    expectRefused(run(render(kTriangle, {"--luts", luts.string()})),
                  (luts / "diffuse.f16").string() + ": texel (3, 2) R: NaN is not finite");

    const fs::path noSkin = dir_ / "maps";
    expectRefused(run({"bake-curvature", kTriangle.string(), "--out", noSkin.string()}),
                  kTriangle.string() +
                      ": materials: no skin material is drawn (make materials skin with --skin NAME "
                      "or all)");
    const ProcessResult bench = run(
        {"bench", "--animated-scene", kTriangle.string(), "--width", "16", "--height", "16", "--device", testDevice()},
        kRenderMemory, 30.0);
    EXPECT_EQ(bench.exitCode, 1) << bench.err;
    EXPECT_EQ(bench.err.find("preskin bench: "), std::string::npos) << "measured before refusing:\n" << bench.err;
    EXPECT_NE(
        bench.err.find("preskin: error: --animated-scene " + kTriangle.string() + ": animations: the scene has none"),
        std::string::npos)
        << bench.err;
}

}  // namespace
}  // namespace preskin::test
