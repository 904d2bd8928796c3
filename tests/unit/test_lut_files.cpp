// Tests of LutSet files (half-float EXR + manifest.json): round trip, previews, the committed
// luts/ folder equals a fresh bake (so it cannot go stale), and every kind of damage
// (corrupt or swapped EXR, missing or mismatching manifest fields, bad profile) is refused
// with a message naming the file and field; a failed save leaves nothing behind.
#include <preskin/Error.h>
#include <preskin/LutSet.h>

#include "skin/Half.h"

#include <OpenImageIO/imageio.h>
#include <fmt/core.h>
#include "support/ErrorText.h"

#include <gtest/gtest.h>
#include <zlib.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

namespace preskin::test {
namespace {

namespace fs = std::filesystem;

class TempDir {
public:
    TempDir() {
        std::random_device entropy;
        path_ = fs::temp_directory_path() / ("preskin_test_lut_" + std::to_string(entropy()));
        fs::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(path_, ec);
    }
    const fs::path& path() const { return path_; }

private:
    fs::path path_;
};

std::vector<std::string> listing(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

const LutSet& smallSet() {
    static const LutSet set = LutSet::bake(DiffusionProfile::deonLuebke(), LutBakeSettings::withSize(16));
    return set;
}

void expectSameTables(const LutSet& a, const LutSet& b) {
    for (auto get : {&LutSet::diffuse, &LutSet::penumbra, &LutSet::shTransfer, &LutSet::transmittance}) {
        const LutTable& ta = (a.*get)();
        const LutTable& tb = (b.*get)();
        EXPECT_EQ(ta.name, tb.name);
        EXPECT_EQ(ta.width(), tb.width());
        EXPECT_EQ(ta.height(), tb.height());
        EXPECT_EQ(ta.rgb, tb.rgb) << ta.name;
    }
}

nlohmann::json readJson(const fs::path& p) {
    std::ifstream in(p);
    return nlohmann::json::parse(in);
}

void writeJson(const fs::path& p, const nlohmann::json& j) {
    std::ofstream out(p);
    out << j.dump(2);
}

TEST(LutFiles, SaveLoadRoundTrip) {
    TempDir tmp;
    const fs::path dir = tmp.path() / "nested" / "set";
    smallSet().save(dir);
    EXPECT_EQ(listing(dir),
              (std::vector<std::string>{"diffuse.exr", "manifest.json", "penumbra.exr", "sh_transfer.exr",
                                        "transmittance.exr"}));
    const LutSet loaded = LutSet::load(dir);
    expectSameTables(smallSet(), loaded);
    EXPECT_EQ(loaded.profile().toJson(), smallSet().profile().toJson());
    EXPECT_EQ(loaded.settings(), smallSet().settings());
    EXPECT_EQ(loaded.lookupDiffuse(0.1f, 0.3f), smallSet().lookupDiffuse(0.1f, 0.3f));

    const nlohmann::json manifest = readJson(dir / "manifest.json");
    EXPECT_EQ(manifest["format"], "preskin-lut-set");
    EXPECT_EQ(manifest["tables"]["diffuse"]["x"]["quantity"], "NoL");
    EXPECT_EQ(manifest["tables"]["diffuse"]["y"]["unit"], "1/mm");
    EXPECT_EQ(manifest["tables"]["diffuse"]["y"]["mapping"], "splitSqrt");
    EXPECT_EQ(manifest["tables"]["penumbra"]["y"]["max"], "infinity");
    EXPECT_EQ(manifest["tables"]["diffuse"]["hash"], smallSet().diffuse().contentHash());
    EXPECT_TRUE(manifest["conventions"].contains("varianceScale"));

    // Saving again over an existing set replaces it cleanly.
    smallSet().save(dir);
    EXPECT_EQ(listing(dir).size(), 5u);
}

TEST(LutFiles, PreviewsAreWritten) {
    TempDir tmp;
    smallSet().save(tmp.path(), {.previewPngs = true});
    for (const char* name :
         {"preview_diffuse.png", "preview_penumbra.png", "preview_sh_transfer.png", "preview_transmittance.png"}) {
        auto in = OIIO::ImageInput::open((tmp.path() / name).string());
        ASSERT_TRUE(in) << name;
        EXPECT_EQ(in->spec().nchannels, 3) << name;
        EXPECT_EQ(in->spec().width, 16) << name;
    }
}

TEST(LutFiles, CommittedDefaultSetEqualsAFreshBake) {
    const fs::path dir = fs::path(PRESKIN_SOURCE_DIR) / "luts";
    const LutSet committed = LutSet::load(dir);
    const LutSet& fresh = LutSet::loadDefault();
    EXPECT_EQ(committed.profile().toJson(), fresh.profile().toJson());
    EXPECT_EQ(committed.settings(), fresh.settings());
    for (auto get : {&LutSet::diffuse, &LutSet::penumbra, &LutSet::shTransfer, &LutSet::transmittance}) {
        const LutTable& a = (committed.*get)();
        const LutTable& b = (fresh.*get)();
        ASSERT_EQ(a.rgb.size(), b.rgb.size()) << a.name;
        size_t differing = 0;
        for (size_t i = 0; i < a.rgb.size(); ++i) {
            // Within one half-float step (libm differences across machines may flip a rounding).
            const float tolerance = std::max(std::abs(a.rgb[i]), std::abs(b.rgb[i])) * (1.0f / 1024.0f) + 6e-8f;
            ASSERT_NEAR(a.rgb[i], b.rgb[i], tolerance)
                << a.name << " value " << i << ": regenerate with `preskin bake --out luts`";
            differing += a.rgb[i] != b.rgb[i];
        }
        EXPECT_LE(differing, a.rgb.size() / 100) << a.name;
    }
}

// Raw half-float tables (what the profile cache writes): the same set back, each file checked by
// its CRC-32 (zlib's crc32 of the bytes written, computed here from the tables), and a flipped
// byte or a short file refused with the file's name.
TEST(LutFiles, RawTablesRoundTripAndDamageIsRefused) {
    TempDir tmp;
    const fs::path dir = tmp.path() / "raw";
    smallSet().save(dir, {.rawTables = true});
    EXPECT_EQ(listing(dir),
              (std::vector<std::string>{"diffuse.f16", "manifest.json", "penumbra.f16", "sh_transfer.f16",
                                        "transmittance.f16"}));
    EXPECT_EQ(fs::file_size(dir / "diffuse.f16"), smallSet().diffuse().rgb.size() * 2);
    const LutSet loaded = LutSet::load(dir);
    expectSameTables(smallSet(), loaded);
    const nlohmann::json manifest = readJson(dir / "manifest.json");
    EXPECT_EQ(manifest["tables"]["diffuse"]["file"], "diffuse.f16");
    EXPECT_EQ(manifest["tables"]["diffuse"]["hash"], smallSet().diffuse().contentHash());
    {
        std::vector<uint8_t> bytes;
        for (float v : smallSet().penumbra().rgb) {
            const uint16_t h = skin::floatToHalfBits(v);
            bytes.push_back(uint8_t(h & 0xff));
            bytes.push_back(uint8_t(h >> 8));
        }
        EXPECT_EQ(manifest["tables"]["penumbra"]["crc32"],
                  fmt::format("{:08x}", crc32_z(0, bytes.data(), bytes.size())));
    }
    const fs::path table = dir / "sh_transfer.f16";
    {
        std::fstream f(table, std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(3);
        f.put('\x5a');
    }
    std::string message = errorOf([&] { LutSet::load(dir); });
    EXPECT_EQ(message.rfind(table.string() + ": CRC-32", 0), 0u) << message;
    smallSet().save(dir, {.rawTables = true});
    fs::resize_file(table, fs::file_size(table) - 2);
    message = errorOf([&] { LutSet::load(dir); });
    EXPECT_EQ(message.rfind(table.string() + ": holds", 0), 0u) << message;
}

TEST(LutFiles, CorruptExrIsRefused) {
    TempDir tmp;
    smallSet().save(tmp.path());
    const fs::path exr = tmp.path() / "diffuse.exr";
    std::fstream f(exr, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(fs::file_size(exr) / 2));
    f.write("garbage!garbage!", 16);
    f.close();
    const std::string message = errorOf([&] { LutSet::load(tmp.path()); });
    EXPECT_EQ(message.rfind(exr.string() + ": ", 0), 0u) << message;
}

TEST(LutFiles, TruncatedExrIsRefused) {
    TempDir tmp;
    smallSet().save(tmp.path());
    const fs::path exr = tmp.path() / "penumbra.exr";
    fs::resize_file(exr, 40);
    const std::string message = errorOf([&] { LutSet::load(tmp.path()); });
    EXPECT_EQ(message.rfind(exr.string() + ": ", 0), 0u) << message;
}

TEST(LutFiles, ExrFromAnotherBakeIsRefused) {
    TempDir tmp;
    const fs::path a = tmp.path() / "a";
    const fs::path b = tmp.path() / "b";
    smallSet().save(a);
    LutSet::bake(DiffusionProfile::burley({0.8, 0.5, 0.3}, {2.0, 0.9, 0.4}), LutBakeSettings::withSize(16)).save(b);
    fs::copy_file(b / "diffuse.exr", a / "diffuse.exr", fs::copy_options::overwrite_existing);
    const std::string message = errorOf([&] { LutSet::load(a); });
    EXPECT_NE(message.find((a / "diffuse.exr").string() + ": content hash"), std::string::npos) << message;
    EXPECT_NE(message.find("tables.diffuse.hash"), std::string::npos) << message;
}

TEST(LutFiles, ManifestProblemsNameTheField) {
    TempDir tmp;
    smallSet().save(tmp.path());
    const fs::path manifestPath = tmp.path() / "manifest.json";
    const nlohmann::json good = readJson(manifestPath);
    const std::string prefix = manifestPath.string() + ": ";

    struct Case {
        std::function<void(nlohmann::json&)> damage;
        std::string expected;
    };
    const std::vector<Case> cases{
        {[](nlohmann::json& j) { j["tables"]["diffuse"].erase("hash"); }, "tables.diffuse.hash: missing"},
        {[](nlohmann::json& j) { j["tables"]["penumbra"]["width"] = 32; },
         "tables.penumbra.width: 32x16 does not match"},
        {[](nlohmann::json& j) { j["settings"]["diffuseNoLSize"] = 0; },
         "settings.diffuseNoLSize: must be an integer in [16, 4096], got 0"},
        {[](nlohmann::json& j) { j["settings"]["diffuseNoLSize"] = 32; },
         "tables.diffuse.width: 16x16 does not match the settings (32x16)"},
        {[](nlohmann::json& j) { j["settings"]["curvatureMaxPerMm"] = 2.0; },
         "tables.diffuse.y.min: -1 does not match"},
        {[](nlohmann::json& j) { j["profile"]["gaussians"][0]["varianceMm2"] = -1; },
         "profile.gaussians[0].varianceMm2: must be >= 1e-06 mm^2 (a Gaussian 1 um wide), got -1"},
        {[](nlohmann::json& j) { j["profile"]["gaussians"][5]["varianceMm2"] = 9.0; }, "does not match"},
        {[](nlohmann::json& j) { j["tables"]["diffuse"]["y"]["mapping"] = "linear"; },
         "tables.diffuse.y.mapping: expected \"splitSqrt\", got \"linear\""},
        {[](nlohmann::json& j) { j["tables"]["diffuse"]["file"] = "../x.exr"; },
         "tables.diffuse.file: expected \"diffuse.exr\""},
        {[](nlohmann::json& j) { j["version"] = 7; }, "version: unsupported version 7"},
        {[](nlohmann::json& j) { j.erase("tables"); }, "tables: missing"},
        {[](nlohmann::json& j) { j["format"] = "something"; }, "format: expected \"preskin-lut-set\""},
    };
    for (const Case& c : cases) {
        nlohmann::json damaged = good;
        c.damage(damaged);
        writeJson(manifestPath, damaged);
        const std::string message = errorOf([&] { LutSet::load(tmp.path()); });
        EXPECT_EQ(message.rfind(prefix, 0), 0u) << message;
        EXPECT_NE(message.find(c.expected), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
    std::ofstream(manifestPath) << "{ not json";
    EXPECT_NE(errorOf([&] { LutSet::load(tmp.path()); }).find(prefix + "JSON: parse error"), std::string::npos);
    fs::remove(manifestPath);
    EXPECT_NE(errorOf([&] { LutSet::load(tmp.path()); }).find(prefix + "file: not found"), std::string::npos);
}

TEST(LutFiles, FailedSaveLeavesNothing) {
    TempDir tmp;
    // The output folder cannot be created (its parent is a file).
    const fs::path file = tmp.path() / "file.txt";
    std::ofstream(file) << "x";
    EXPECT_NE(errorOf([&] { smallSet().save(file / "sub" / "set"); }).find((file / "sub" / "set").string()),
              std::string::npos);
    EXPECT_EQ(listing(tmp.path()), std::vector<std::string>{"file.txt"});
    // The folder is a file.
    EXPECT_NE(errorOf([&] { smallSet().save(file); }).find(file.string()), std::string::npos);
    // A target name is taken by a folder: refused before anything is replaced.
    const fs::path dir = tmp.path() / "set";
    fs::create_directories(dir / "penumbra.exr");
    const std::string message = errorOf([&] { smallSet().save(dir); });
    EXPECT_NE(message.find((dir / "penumbra.exr").string()), std::string::npos) << message;
    EXPECT_EQ(listing(dir), std::vector<std::string>{"penumbra.exr"});
    EXPECT_TRUE(fs::is_empty(dir / "penumbra.exr"));
}

}  // namespace
}  // namespace preskin::test
