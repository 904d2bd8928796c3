// The core's own image codecs against an independent decoder (OpenImageIO, which the tests link):
// JPEG (libjpeg-turbo) and Radiance HDR (stb_image) give the same values on the bundled images,
// PNG written by the core reads back through OpenImageIO at 8 and 16 bits and 1 to 4 channels.
// Then the plug-in points: without the image component an EXR environment, an EXR LUT folder,
// EXR output and an EXR texture are refused, naming the file, the field and the component; a
// codec a host registers decodes a format the core does not know; SceneLoadOptions::decodeImage
// hands the loader the host's own pixels.
#include "GltfTestFiles.h"
#include "support/ErrorText.h"

#include "image/ImageCodecs.h"
#include "image/ImageFormat.h"

#include <preskin/Environment.h>
#include <preskin/ImageCodec.h>
#include <preskin/LutSet.h>
#include <preskin/Renderer.h>
#include <preskin/imageio/ImageIo.h>

#include <OpenImageIO/imageio.h>
#include <fmt/core.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace preskin::test {
namespace {

const fs::path kAssets = fs::path(PRESKIN_SOURCE_DIR) / "samples" / "assets";
const DecodeLimits kLimits{1ull << 26, 16384};

// OpenImageIO's reading of a file, as floats (8-bit values scaled by 1/255).
std::vector<float> oiioPixels(const fs::path& path, int channels, int& width, int& height) {
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);  // alpha as stored, not multiplied in
    auto in = OIIO::ImageInput::open(path.string(), &config);
    if (!in) {
        ADD_FAILURE() << OIIO::geterror();
        return {};
    }
    width = in->spec().width;
    height = in->spec().height;
    std::vector<float> pixels(size_t(width) * size_t(height) * size_t(channels));
    EXPECT_TRUE(in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, pixels.data())) << in->geterror();
    in->close();
    return pixels;
}

TEST(ImageCodecs, JpegDecodesAsOpenImageIoDoes) {
    for (const char* name : {"head/Map-COL.jpg", "head/Map-SPEC.jpg", "head/Infinite-Level_02_Tangent_SmoothUV.jpg"}) {
        const std::vector<uint8_t> bytes = readBytes(kAssets / name);
        const PixelImage image = decodeImage(bytes, kLimits, name);
        int width = 0, height = 0;
        const std::vector<float> expected = oiioPixels(kAssets / name, int(image.channels), width, height);
        ASSERT_EQ(image.width, uint32_t(width)) << name;
        ASSERT_EQ(image.height, uint32_t(height)) << name;
        const auto& texels = std::get<std::vector<uint8_t>>(image.texels);
        ASSERT_EQ(texels.size(), expected.size());
        size_t differing = 0;
        for (size_t i = 0; i < texels.size(); ++i) differing += texels[i] != uint8_t(std::lround(expected[i] * 255.0f));
        EXPECT_EQ(differing, 0u) << name << ": " << differing << " of " << texels.size() << " values differ";
    }
}

TEST(ImageCodecs, RadianceDecodesAsOpenImageIoDoes) {
    for (const char* name : {"head/studio_small_05_1k.hdr", "sky/sunny_sky_1k.hdr"}) {
        const std::vector<uint8_t> bytes = readBytes(kAssets / name);
        const PixelImage image = decodeImage(bytes, kLimits, name);
        int width = 0, height = 0;
        const std::vector<float> expected = oiioPixels(kAssets / name, 3, width, height);
        ASSERT_EQ(image.width, uint32_t(width)) << name;
        ASSERT_EQ(image.channels, 3u);
        const auto& texels = std::get<std::vector<float>>(image.texels);
        ASSERT_EQ(texels.size(), expected.size());
        size_t differing = 0;
        for (size_t i = 0; i < texels.size(); ++i) differing += texels[i] != expected[i];
        EXPECT_EQ(differing, 0u) << name;
    }
}

// The test sky in every encoding tests/data/environments holds (make_environment_files.py: flat and
// run-length RGBE, XYZE with EXPOSURE, scanline and tiled half EXR): the same radiance, within the
// encodings' precision (RGBE's 8-bit mantissas, XYZE's also turned by a matrix with negative terms).
TEST(ImageCodecs, EveryEncodingOfTheTestSkyGivesTheSameRadiance) {
    const fs::path dir = fs::path(PRESKIN_SOURCE_DIR) / "tests" / "data" / "environments";
    const Environment reference = Environment::load(dir / "sky.exr");
    for (const auto& [name, tolerance] : {std::pair{"sky.hdr", 0.02f}, std::pair{"sky_rle.hdr", 0.02f},
                                          std::pair{"sky_xyze.hdr", 0.03f}, std::pair{"sky_tiled.exr", 1e-6f}}) {
        const Environment env = Environment::load(dir / name);
        ASSERT_EQ(env.image().width, reference.image().width) << name;
        float worst = 0.0f;
        for (size_t i = 0; i < env.image().rgb.size(); ++i)
            worst = std::max(
                worst,
                std::abs(env.image().rgb[i] - reference.image().rgb[i]) / std::max(reference.image().rgb[i], 0.05f));
        EXPECT_LT(worst, tolerance) << name;
    }
    // The run-length scanlines hold exactly the flat ones' texels.
    EXPECT_EQ(Environment::load(dir / "sky_rle.hdr").image().rgb, Environment::load(dir / "sky.hdr").image().rgb);
}

TEST(ImageCodecs, RadianceCutShortIsRefusedBeforeDecoding) {
    std::vector<uint8_t> bytes = readBytes(kAssets / "head/studio_small_05_1k.hdr");
    bytes.resize(bytes.size() / 4);
    try {
        decodeImage(bytes, kLimits, "cut.hdr");
        ADD_FAILURE() << "a Radiance file cut to a quarter decoded";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("cut.hdr: cannot decode the Radiance HDR data: truncated"),
                  std::string::npos)
            << e.what();
    }
}

TEST(ImageCodecs, PngWrittenByTheCoreReadsBackThroughOpenImageIo) {
    TempDir dir;
    for (uint32_t channels = 1; channels <= 4; ++channels)
        for (bool sixteen : {false, true}) {
            PixelImage image;
            image.width = 5;
            image.height = 3;
            image.channels = channels;
            std::vector<float> values(image.valueCount());
            for (size_t i = 0; i < values.size(); ++i) values[i] = float((i * 37) % 101) / 100.0f;
            if (sixteen) {
                std::vector<uint16_t> t;
                for (float v : values) t.push_back(uint16_t(std::lround(v * 65535.0f)));
                image.texels = t;
            } else {
                std::vector<uint8_t> t;
                for (float v : values) t.push_back(uint8_t(std::lround(v * 255.0f)));
                image.texels = t;
            }
            const fs::path path = dir / fmt::format("p{}_{}.png", channels, sixteen ? 16 : 8);
            encodeImage(path, image);
            int width = 0, height = 0;
            const std::vector<float> back = oiioPixels(path, int(channels), width, height);
            ASSERT_EQ(width, 5);
            ASSERT_EQ(height, 3);
            const float step = sixteen ? 1.0f / 65535.0f : 1.0f / 255.0f;
            for (size_t i = 0; i < values.size(); ++i)
                ASSERT_NEAR(back[i], values[i], 0.51f * step) << path << " value " << i;
            // And the core reads it back the same (as RGBA).
            const PixelImage decoded = decodeImage(readBytes(path), kLimits, path.string());
            EXPECT_EQ(decoded.channels, 4u);
            EXPECT_EQ(std::holds_alternative<std::vector<uint16_t>>(decoded.texels), sixteen);
        }
}

// An EXR written by the test (OpenImageIO directly), 8x4 RGB.
fs::path writeExr(const fs::path& path, float value) {
    auto out = OIIO::ImageOutput::create("openexr");
    OIIO::ImageSpec spec(8, 4, 3, OIIO::TypeDesc::HALF);
    std::vector<float> pixels(8 * 4 * 3, value);
    EXPECT_TRUE(out->open(path.string(), spec) && out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) &&
                out->close());
    return path;
}

TEST(ImageCodecs, WithoutTheImageComponentExrIsRefusedNamingIt) {
    TempDir dir;
    const fs::path exr = writeExr(dir / "sky.exr", 0.5f);
    // With the component (what the test program registers, as the tools do) it loads.
    EXPECT_NEAR(Environment::load(exr).image().rgb[0], 0.5f, 1e-6f);
    const image::ScopedCodecs coreAlone({});
    const std::string component = "link preskin::imageio and call preskin::imageio::registerCodecs()";

    const std::string env = errorOf([&] { Environment::load(exr); });
    EXPECT_EQ(env.rfind(exr.string() + ": cannot decode environment image: OpenEXR data: no decoder", 0), 0u) << env;
    EXPECT_NE(env.find(component), std::string::npos) << env;

    RenderedImage rendered;
    rendered.width = rendered.height = 1;
    rendered.encoding = OutputEncoding::LinearFloat;
    rendered.rgba32f = {1, 1, 1, 1};
    const std::string out = errorOf([&] { writeImage(dir / "out.exr", rendered); });
    EXPECT_EQ(out.rfind((dir / "out.exr").string() + ": output: no writer for '.exr' files", 0), 0u) << out;
    EXPECT_NE(out.find(component), std::string::npos) << out;
    EXPECT_FALSE(fs::exists(dir / "out.exr"));

    const std::string luts = errorOf([&] { LutSet::load(fs::path(PRESKIN_SOURCE_DIR) / "luts"); });
    EXPECT_NE(luts.find("diffuse.exr: OpenEXR data: no decoder"), std::string::npos) << luts;
    EXPECT_NE(luts.find(component), std::string::npos) << luts;
    const std::string save = errorOf([&] { LutSet::loadDefault().save(dir / "set"); });
    EXPECT_NE(save.find(component), std::string::npos) << save;
    EXPECT_FALSE(fs::exists(dir / "set"));
    // Raw tables need no component.
    LutSet::loadDefault().save(dir / "raw", {.rawTables = true});
    EXPECT_EQ(LutSet::load(dir / "raw").diffuse().rgb, LutSet::loadDefault().diffuse().rgb);

    // A scene: its EXR texture, and its EXR environment.
    GltfBuilder b = triangleScene();
    writeExr(dir / "t.exr", 0.25f);
    b.doc["images"] = nlohmann::json::array({{{"uri", "t.exr"}}});
    b.doc["textures"] = nlohmann::json::array({{{"source", 0}}});
    b.doc["materials"] = nlohmann::json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
    b.doc["meshes"][0]["primitives"][0]["material"] = 0;
    const fs::path scene = b.writeGltf(dir.path(), "textured");
    const std::string texture = errorOf([&] { Scene::load(scene); });
    EXPECT_EQ(texture.rfind(scene.string() + ": images[0] ('t.exr'): OpenEXR data: no decoder", 0), 0u) << texture;
    EXPECT_NE(texture.find(component), std::string::npos) << texture;

    GltfBuilder e = triangleScene();
    e.doc["extensions"] = {{"PRESKIN_environment", {{"uri", "sky.exr"}}}};
    e.doc["extensionsUsed"] = {"PRESKIN_environment"};
    const fs::path envScene = e.writeGltf(dir.path(), "lit");
    const std::string sceneEnv = errorOf([&] { Scene::load(envScene); });
    EXPECT_EQ(sceneEnv.rfind(envScene.string() + ": extensions.PRESKIN_environment.uri: 'sky.exr' is OpenEXR", 0), 0u)
        << sceneEnv;
    EXPECT_NE(sceneEnv.find(component), std::string::npos) << sceneEnv;
}

TEST(ImageCodecs, ExrTextureDecodesWithTheImageComponent) {
    TempDir dir;
    GltfBuilder b = triangleScene();
    writeExr(dir / "t.exr", 0.25f);
    b.doc["images"] = nlohmann::json::array({{{"uri", "t.exr"}}});
    const Scene scene = Scene::load(b.writeGltf(dir.path(), "textured"));
    ASSERT_EQ(scene.images.size(), 1u);
    ASSERT_EQ(scene.images[0].rgba16.size(), 8u * 4u * 4u);
    EXPECT_EQ(scene.images[0].rgba16[0], 16384);  // 0.25 of 65535, rounded
    EXPECT_EQ(scene.images[0].rgba8[0], 64);
    EXPECT_EQ(scene.images[0].rgba8[3], 255);
}

// A host's codec for a format of its own ("XIMG" + width, height bytes + grey texels).
class TinyGreyCodec final : public ImageCodec {
public:
    std::string name() const override { return "host test codec"; }
    std::string decodes(std::span<const uint8_t> head) const override {
        return head.size() >= 4 && std::equal(head.begin(), head.begin() + 4, "XIMG") ? "XIMG" : "";
    }
    PixelImage decode(std::span<const uint8_t> bytes, const DecodeLimits&) const override {
        if (bytes.size() < 6) throw std::runtime_error("no size");
        PixelImage image;
        image.width = bytes[4];
        image.height = bytes[5];
        image.channels = 1;
        image.texels = std::vector<uint8_t>(bytes.begin() + 6, bytes.end());
        return image;
    }
};

TEST(ImageCodecs, HostCodecsAndHostDecodedImagesReachTheScene) {
    TempDir dir;
    writeBytes(dir / "t.ximg", {'X', 'I', 'M', 'G', 2, 1, 10, 200});
    GltfBuilder b = triangleScene();
    b.doc["images"] = nlohmann::json::array({{{"uri", "t.ximg"}}});
    const fs::path path = b.writeGltf(dir.path(), "host");
    // Unknown to preskin: a warning, no pixels.
    const Scene unknown = Scene::load(path);
    EXPECT_TRUE(unknown.images[0].rgba8.empty());
    {
        const image::ScopedCodecs codecs({std::make_shared<TinyGreyCodec>()});
        const Scene scene = Scene::load(path);
        EXPECT_EQ(scene.images[0].rgba8, (std::vector<uint8_t>{10, 10, 10, 255, 200, 200, 200, 255}));
    }
    // The host's own pixels for an image (whatever its file holds), through the load options.
    SceneLoadOptions options;
    std::string seenUri;
    options.decodeImage = [&](std::span<const uint8_t> bytes, const std::string& uri,
                              const std::string&) -> std::optional<PixelImage> {
        seenUri = uri;
        EXPECT_EQ(bytes.size(), 8u);
        PixelImage image;
        image.width = image.height = 1;
        image.channels = 4;
        image.texels = std::vector<uint16_t>{65535, 0, 32768, 65535};
        return image;
    };
    const Scene hosted = Scene::load(path, options);
    EXPECT_EQ(seenUri, "t.ximg");
    EXPECT_EQ(hosted.images[0].rgba16, (std::vector<uint16_t>{65535, 0, 32768, 65535}));
    EXPECT_EQ(hosted.images[0].rgba8, (std::vector<uint8_t>{255, 0, 128, 255}));
    // A host decoder whose image does not match its size refuses the scene, naming the image.
    options.decodeImage = [](std::span<const uint8_t>, const std::string&, const std::string&) {
        PixelImage image;
        image.width = image.height = 2;
        image.channels = 4;
        image.texels = std::vector<uint8_t>(3);
        return std::optional<PixelImage>(image);
    };
    const std::string bad = errorOf([&] { Scene::load(path, options); });
    EXPECT_NE(bad.find("images[0] ('t.ximg'): the host's decoder returned 2x2 texels"), std::string::npos) << bad;
}

}  // namespace
}  // namespace preskin::test
