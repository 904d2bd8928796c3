// LutSet files: four half-float RGB EXR tables (through a registered codec: preskin::imageio) and manifest.json describing the
// profile, settings, axes (range, unit, mapping, formula), sizes, sample counts, conventions and
// an FNV-1a content hash per table; optional 8-bit sRGB PNG previews. Saving writes temporary
// files and renames them into place (manifest last); loading validates everything and names the
// file and field of the first problem.
// Limits: one set per folder; files are replaced one by one (a reader racing a writer can see
// a manifest whose hashes do not match, and then reports it).
#include <preskin/LutSet.h>

#include "skin/Half.h"
#include "skin/LutLayout.h"
#include "skin/ProfileJson.h"

#include <preskin/Error.h>
#include <preskin/ImageCodec.h>
#include <preskin/Limits.h>

#include "env/EnvironmentHeader.h"
#include "image/ImageCodecs.h"
#include "image/PngFile.h"
#include "io/InputFile.h"
#include "io/JsonDocument.h"
#include "io/MessageText.h"
#include "io/NumberRule.h"

#include <fmt/core.h>
#include <zlib.h>
#include <nlohmann/json.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <numbers>
#include <random>
#include <sstream>
#include <system_error>

namespace preskin {
namespace {

namespace fs = std::filesystem;
using ordered_json = nlohmann::ordered_json;

constexpr const char* kFormat = "preskin-lut-set";
constexpr int kVersion = 2;  // 2: diffuse over the sphere of the signed curvature (concave half)
constexpr const char* kManifestName = "manifest.json";

struct TableFile {
    const char* key;       // manifest key
    const char* fileName;  // EXR name
    const char* rawName;   // raw half-float name (LutSaveOptions::rawTables)
    const char* preview;   // PNG name
    const char* name(bool raw) const { return raw ? rawName : fileName; }
};
constexpr TableFile kDiffuseFile{"diffuse", "diffuse.exr", "diffuse.f16", "preview_diffuse.png"};
constexpr TableFile kPenumbraFile{"penumbra", "penumbra.exr", "penumbra.f16", "preview_penumbra.png"};
constexpr TableFile kShFile{"shTransfer", "sh_transfer.exr", "sh_transfer.f16", "preview_sh_transfer.png"};
constexpr TableFile kTransmittanceFile{"transmittance", "transmittance.exr", "transmittance.f16",
                                       "preview_transmittance.png"};
static_assert(std::endian::native == std::endian::little, "raw LUT tables are little-endian half floats");

std::string shown(const fs::path& p) { return p.string(); }

// ---- raw tables ----------------------------------------------------------------------------

std::vector<uint16_t> rawHalf(const LutTable& table) {
    std::vector<uint16_t> half(table.rgb.size());
    for (size_t i = 0; i < half.size(); ++i) half[i] = skin::floatToHalfBits(table.rgb[i]);
    return half;
}

uint32_t rawCrc32(const std::vector<uint16_t>& half) {
    return static_cast<uint32_t>(
        crc32_z(0, reinterpret_cast<const Bytef*>(half.data()), half.size() * sizeof(uint16_t)));
}

// ---- manifest writing ----------------------------------------------------------------------

ordered_json axisJson(const LutAxis& axis) {
    ordered_json j;
    j["quantity"] = axis.quantity;
    j["unit"] = axis.unit;
    j["min"] = axis.min;
    if (std::isinf(axis.max))
        j["max"] = "infinity";
    else
        j["max"] = axis.max;
    if (axis.mapping == AxisMapping::Log1p) j["scale"] = axis.scale;
    j["size"] = axis.size;
    j["mapping"] = axisMappingName(axis.mapping);
    j["formula"] = axis.formula();
    j["textureCoordinate"] = "(t + 0.5) / size";
    return j;
}

ordered_json tableJson(const LutTable& table, const TableFile& file, bool raw) {
    ordered_json j;
    j["file"] = file.name(raw);
    j["width"] = table.width();
    j["height"] = table.height();
    j["channels"] = ordered_json::array({"R", "G", "B"});
    j["pixelType"] = "half";
    j["x"] = axisJson(table.x);
    j["y"] = axisJson(table.y);
    j["hash"] = table.contentHash();
    // Raw tables also carry the CRC-32 (zlib) of their file, what a load checks: the content hash
    // is a byte-at-a-time FNV and would be most of the time a cache hit takes.
    if (raw) j["crc32"] = fmt::format("{:08x}", rawCrc32(rawHalf(table)));
    return j;
}

ordered_json rgbJson(glm::dvec3 v) { return ordered_json::array({v.x, v.y, v.z}); }

std::string manifestText(const LutSet& set, bool raw) {
    const DiffusionProfile& profile = set.profile();
    const LutBakeSettings& s = set.settings();
    ordered_json j;
    j["format"] = kFormat;
    j["version"] = kVersion;
    j["profile"] = skin::profileToJson(profile);
    j["profileProperties"] = {
        {"albedo", rgbJson(profile.albedo())},
        {"widthMm", rgbJson(profile.widthMm())},
        {"widthDefinition", "RMS radius sqrt(int r^2 2 pi r R(r) dr / albedo) per channel"},
        {"narrowestScaleMm", profile.narrowestScaleMm()},
    };
    j["settings"] = {
        {"diffuseNoLSize", s.diffuseNoLSize},         {"diffuseCurvatureSize", s.diffuseCurvatureSize},
        {"penumbraShadowSize", s.penumbraShadowSize}, {"penumbraWidthSize", s.penumbraWidthSize},
        {"shCurvatureSize", s.shCurvatureSize},       {"transmittanceSize", s.transmittanceSize},
        {"curvatureMaxPerMm", s.curvatureMaxPerMm},
    };
    j["conventions"] = {
        {"layout",
         "row-major RGB; scanline y (v = (y + 0.5) / height) holds y-axis node y; column x holds x-axis node x"},
        {"texelCentres",
         "axis node i sits at texel centre (i + 0.5) / size; node 0 = range start, node size-1 = range "
         "end; sample with LINEAR filtering and CLAMP_TO_EDGE"},
        {"values", "rounded to half precision at bake time; the EXR files hold exactly the baked numbers"},
        {"normalisation",
         "every table carries the profile's shape only (per channel, albedo divided out); multiply "
         "by the material's albedo"},
        {"varianceScale", "none: Gaussian variances are used as published (no 1.414 factor)"},
        {"curvature",
         "signed mean curvature 1/r in 1/mm of the profile's units, > 0 convex, < 0 concave; diffuse: "
         "range [-curvatureMaxPerMm, curvatureMaxPerMm] (default 1: radii from 1 mm to flat) with the "
         "flat row exactly in the middle, SH transfer: |curvature| in [0, curvatureMaxPerMm]; sqrt "
         "mappings, so half the rows of each side lie below a quarter of its range, where faces are "
         "(radii ~2..100 mm); values beyond the range clamp to the last row"},
        {"penumbraWidth",
         "filterSigmaRelative = sigma_f / referenceWidthMm; sigma_f is the shadow filter's Gaussian "
         "standard deviation on the receiver across the edge (mm), referenceWidthMm the widest "
         "channel's RMS width"},
        {"sphereKernel",
         "diffuse: the profile integrated over a sphere of radius 1/|curvature| (Penner & Borshukov 2011's "
         "pre-integration on a sphere instead of a ring): D = int R(|x-y|) max(n_y.L, 0) V dA / int R dA, "
         "convex: the whole sphere, V = 1; concave: the inside, limited to the cap of arc radius "
         "localPatchMm around x, V = 0 where the light towards y leaves through the cap"},
        {"localPatchMm", set.localPatchMm()},
        {"penumbraModel",
         "a point light's hard shadow edge, located by the shadow filter (Gaussian, standard "
         "deviation sigma_f): x = sigma_f Phi^-1(shadow); value = the profile's edge response at x "
         "renormalised to |x| <= 3 sigma_f"},
        {"shTransfer",
         "stored as A_l / (pi, 2 pi / 3, pi / 4)_l, A_l = 2 pi int D(theta) P_l(cos theta) sin theta "
         "dtheta over the convex sphere of |curvature| (= Lambert_l g_l / g_0, g_l the profile's Legendre "
         "coefficients on the sphere, Funk-Hecke); flat skin stores 1"},
        {"transmittance",
         "T(d) = int 2 pi r R(sqrt(r^2 + d^2)) dr / albedo; Gaussians: sum_i w_i exp(-d^2 / 2 v_i) / "
         "albedo (Jimenez et al. 2010's form with variances doubled, no 1.414 factor)"},
        {"previews", "preview_*.png: sRGB-encoded, first y node at the bottom; SH bands 0, 1, 2 bottom to top"},
    };

    ordered_json tables;
    ordered_json diffuse = tableJson(set.diffuse(), kDiffuseFile, raw);
    diffuse["method"] =
        "integral over the angle psi between x and y of a^2 R(2 a sin(psi/2)) sin(psi) times the "
        "closed-form azimuthal integral of max(n_y.L, 0) (with the concave cap's visibility threshold), "
        "up to the profile's 1e-4 reach, by 8-point Gauss-Legendre on a geometric mesh (ratio 1.5) "
        "from 1e-3 of the narrowest scale and 64 uniform intervals; the middle row (curvature 0) is "
        "exactly saturate(NoL)";
    diffuse["samples"] = {{"gaussLegendrePointsPerInterval", 8}, {"gradedMeshRatio", 1.5}, {"uniformIntervals", 64}};
    tables["diffuse"] = std::move(diffuse);

    ordered_json penumbra = tableJson(set.penumbra(), kPenumbraFile, raw);
    penumbra["referenceWidthMm"] = set.penumbraReferenceWidthMm();
    penumbra["windowSigmas"] = skin::kPenumbraWindowSigmas;
    penumbra["method"] =
        "closed form (erfc) for Gaussians; Craig-form integral (1/pi) int_0^{pi/2} T(a / sin psi) dpsi "
        "by 8-point Gauss-Legendre on a halving mesh for normalized diffusion";
    tables["penumbra"] = std::move(penumbra);

    ordered_json sh = tableJson(set.shTransfer(), kShFile, raw);
    sh["lambert"] = ordered_json::array({std::numbers::pi, 2.0 * std::numbers::pi / 3.0, std::numbers::pi / 4.0});
    sh["method"] =
        "16-point Gauss-Legendre in cos(theta) on [-1, 1] with breaks at 0, +-1/256, +-1/64, +-1/16, +-1/4 "
        "(160 ring integrals per curvature)";
    sh["samples"] = {{"cosThetaNodes", 160}};
    tables["shTransfer"] = std::move(sh);

    ordered_json transmittance = tableJson(set.transmittance(), kTransmittanceFile, raw);
    transmittance["floor"] = skin::kTransmittanceFloor;
    transmittance["method"] = "closed form";
    tables["transmittance"] = std::move(transmittance);
    j["tables"] = std::move(tables);
    return j.dump(2) + "\n";
}

// ---- image writing -------------------------------------------------------------------------

void writeExr(const fs::path& path, const fs::path& shownPath, const LutTable& table) {
    PixelImage image;
    image.width = uint32_t(table.width());
    image.height = uint32_t(table.height());
    image.channels = 3;
    image.texels = table.rgb;  // the table's values are halves already: written as half, exactly
    EncodeOptions options;
    options.halfFloat = true;
    options.attributes = {{"preskin:table", table.name}};
    try {
        image::encoderFor(shownPath)->encode(path, image, options);
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error(fmt::format("{}: cannot write: {}", shown(shownPath), io::messageText(e.what())));
    }
}

void writeRaw(const fs::path& path, const fs::path& shownPath, const LutTable& table) {
    const std::vector<uint16_t> half = rawHalf(table);
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(half.data()), std::streamsize(half.size() * sizeof(uint16_t)));
    out.close();
    if (!out) throw Error(fmt::format("{}: cannot write", shown(shownPath)));
}

float srgbEncode(float linear) {
    const float c = std::clamp(linear, 0.0f, 1.0f);
    return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

// Rows bottom-up (first y node at the bottom); each table row repeated `rowRepeat` times.
void writePreview(const fs::path& path, const fs::path& shownPath, const LutTable& table, int rowRepeat) {
    const int width = table.width();
    const int height = table.height() * rowRepeat;
    std::vector<uint8_t> pixels(static_cast<size_t>(width) * static_cast<size_t>(height) * 3);
    for (int py = 0; py < height; ++py) {
        const int iy = (height - 1 - py) / rowRepeat;
        for (int ix = 0; ix < width; ++ix) {
            const glm::vec3 v = table.texel(ix, iy);
            for (int c = 0; c < 3; ++c)
                pixels[(static_cast<size_t>(py) * static_cast<size_t>(width) + static_cast<size_t>(ix)) * 3 +
                       static_cast<size_t>(c)] = static_cast<uint8_t>(std::lround(255.0f * srgbEncode(v[c])));
        }
    }
    PixelImage image;
    image.width = uint32_t(width);
    image.height = uint32_t(height);
    image.channels = 3;
    image.texels = std::move(pixels);
    try {
        image::encodePng(path, image);
    } catch (const std::exception& e) {
        throw Error(fmt::format("{}: cannot write: {}", shown(shownPath), io::messageText(e.what())));
    }
}

void writeText(const fs::path& path, const fs::path& shownPath, const std::string& text) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << text;
    out.close();
    if (!out) throw Error(fmt::format("{}: cannot write", shown(shownPath)));
}

// ---- manifest reading ----------------------------------------------------------------------

struct ManifestReader {
    std::string source;  // the manifest's path, for messages

    [[noreturn]] void fail(const std::string& field, const std::string& problem) const {
        throw Error(fmt::format("{}: {}: {}", source, io::messageText(field),
                                io::messageText(problem, 4 * io::kMessageExcerptChars)));
    }
    const nlohmann::json& field(const nlohmann::json& object, const std::string& path, const char* key) const {
        const std::string full = path.empty() ? key : path + "." + key;
        if (!object.is_object()) fail(path, std::string("must be an object, got ") + object.type_name());
        const auto it = object.find(key);
        if (it == object.end()) fail(full, "missing");
        return *it;
    }
    int integer(const nlohmann::json& object, const std::string& path, const char* key) const {
        const nlohmann::json& v = field(object, path, key);
        const std::string full = path.empty() ? key : path + "." + key;
        if (!v.is_number_integer()) fail(full, std::string("must be an integer, got ") + io::jsonExcerpt(v));
        const auto value = v.get<int64_t>();
        if (value < -1000000000 || value > 1000000000) fail(full, "out of range: " + io::jsonExcerpt(v));
        return static_cast<int>(value);
    }
    double number(const nlohmann::json& object, const std::string& path, const char* key) const {
        const nlohmann::json& v = field(object, path, key);
        const std::string full = path.empty() ? key : path + "." + key;
        if (v.is_string() && v.get<std::string>() == "infinity") return std::numeric_limits<double>::infinity();
        if (!v.is_number()) fail(full, std::string("must be a number, got ") + io::jsonExcerpt(v));
        const double number = v.get<double>();
        if (auto problem = io::numberProblem(number)) fail(full, *problem);
        return number;
    }
    std::string string(const nlohmann::json& object, const std::string& path, const char* key) const {
        const nlohmann::json& v = field(object, path, key);
        const std::string full = path.empty() ? key : path + "." + key;
        if (!v.is_string()) fail(full, std::string("must be a string, got ") + io::jsonExcerpt(v));
        return v.get<std::string>();
    }
};

bool sameNumber(double a, double b) {
    if (std::isinf(a) || std::isinf(b)) return a == b;
    return std::abs(a - b) <= 1e-9 * std::max({1.0, std::abs(a), std::abs(b)});
}

void checkAxis(const ManifestReader& reader, const nlohmann::json& tables, const std::string& path, const char* key,
               const LutAxis& expected) {
    const std::string at = path + "." + key;
    const nlohmann::json& a = reader.field(tables, path, key);
    auto expect = [&](const char* name, double got, double want) {
        if (!sameNumber(got, want))
            reader.fail(at + "." + name, fmt::format("{} does not match the profile and settings ({})", got, want));
    };
    const std::string quantity = reader.string(a, at, "quantity");
    if (quantity != expected.quantity)
        reader.fail(at + ".quantity", fmt::format("expected \"{}\", got \"{}\"", expected.quantity, quantity));
    const std::string mapping = reader.string(a, at, "mapping");
    if (mapping != axisMappingName(expected.mapping))
        reader.fail(at + ".mapping",
                    fmt::format("expected \"{}\", got \"{}\"", axisMappingName(expected.mapping), mapping));
    expect("size", reader.integer(a, at, "size"), expected.size);
    expect("min", reader.number(a, at, "min"), expected.min);
    expect("max", reader.number(a, at, "max"), expected.max);
    if (expected.mapping == AxisMapping::Log1p) expect("scale", reader.number(a, at, "scale"), expected.scale);
}

// Raw half floats: exactly `values` of them, nothing else.
std::vector<uint8_t> readRaw(const fs::path& rawPath, size_t values) {
    std::vector<uint8_t> bytes = io::readInputFile(rawPath, shown(rawPath), limits::kMaxImageFileBytes);
    if (bytes.size() != values * sizeof(uint16_t))
        throw Error(fmt::format("{}: holds {} bytes, but the table needs {}", shown(rawPath), bytes.size(),
                                values * sizeof(uint16_t)));
    return bytes;
}

void readExr(const fs::path& exrPath, const ManifestReader& reader, const std::string& path, int width, int height,
             std::vector<uint16_t>& half) {
    // The size from the file's own header, checked against the manifest before a decoder
    // allocates; then only the OpenEXR reader (opening by name would try every format).
    const std::vector<uint8_t> prefix =
        io::readInputFileStart(exrPath, shown(exrPath), limits::kMaxImageFileBytes, env::kEnvironmentHeaderBytes);
    try {
        const env::EnvironmentHeader header = env::readEnvironmentHeader(prefix);
        if (header.format != env::EnvironmentFormat::OpenExr) throw std::runtime_error("format: not an OpenEXR file");
        if (header.width != width || header.height != height)
            throw std::runtime_error(fmt::format("size: {}x{}, but {} {} says {}x{}", header.width, header.height,
                                                 reader.source, path, width, height));
    } catch (const std::runtime_error& e) {
        throw Error(fmt::format("{}: {}", shown(exrPath), e.what()));
    }
    const std::vector<uint8_t> bytes = io::readInputFile(exrPath, shown(exrPath), limits::kMaxImageFileBytes);
    const PixelImage image =
        decodeImage(bytes, DecodeLimits{limits::kMaxImagePixels, limits::kMaxImageSide}, shown(exrPath));
    if (image.width != uint32_t(width) || image.height != uint32_t(height) || image.channels != 3)
        throw Error(fmt::format("{}: image is {}x{} with {} channels, but {} {} says {}x{} RGB", shown(exrPath),
                                image.width, image.height, image.channels, reader.source, path, width, height));
    const std::vector<float> rgb = image::toRgbFloat(image);
    for (size_t i = 0; i < rgb.size(); ++i) half[i] = skin::floatToHalfBits(rgb[i]);
}

LutTable readTable(const fs::path& dir, const ManifestReader& reader, const nlohmann::json& tables,
                   const TableFile& file, LutTable expected) {
    const std::string path = std::string("tables.") + file.key;
    const nlohmann::json& t = reader.field(tables, "tables", file.key);
    const std::string name = reader.string(t, path, "file");
    if (name != file.fileName && name != file.rawName)
        reader.fail(path + ".file",
                    fmt::format("expected \"{}\" or \"{}\", got \"{}\"", file.fileName, file.rawName, name));
    const int width = reader.integer(t, path, "width");
    const int height = reader.integer(t, path, "height");
    if (width != expected.width() || height != expected.height())
        reader.fail(path + ".width",
                    fmt::format("{}x{} does not match the settings ({}x{})", width, height, expected.width(),
                                expected.height()));
    checkAxis(reader, t, path, "x", expected.x);
    checkAxis(reader, t, path, "y", expected.y);
    const std::string hash = reader.string(t, path, "hash");
    const size_t values = static_cast<size_t>(width) * static_cast<size_t>(height) * 3;
    const fs::path tablePath = dir / name;
    const bool raw = name == file.rawName;
    std::vector<uint8_t> bytes;  // raw: the file
    std::vector<uint16_t> half;  // EXR: the decoded values
    if (raw) {
        const std::string crc = reader.string(t, path, "crc32");
        bytes = readRaw(tablePath, values);
        const std::string actual = fmt::format("{:08x}", crc32_z(0, bytes.data(), bytes.size()));
        if (actual != crc)
            throw Error(fmt::format("{}: CRC-32 {} does not match {} {}.crc32 ({}); the file is corrupt",
                                    shown(tablePath), actual, reader.source, path, io::messageText(crc)));
    } else {
        half.resize(values);
        readExr(tablePath, reader, path, width, height, half);
    }
    auto halfAt = [&](size_t i) {
        if (!raw) return half[i];
        uint16_t h;
        std::memcpy(&h, bytes.data() + 2 * i, sizeof h);
        return h;
    };
    // Every half value as a float, once (a cache load converts millions of them).
    static const std::vector<float> kHalfToFloat = [] {
        std::vector<float> table(65536);
        for (uint32_t h = 0; h < 65536; ++h) table[h] = skin::halfBitsToFloat(static_cast<uint16_t>(h));
        return table;
    }();
    expected.rgb.resize(values);
    for (size_t i = 0; i < values; ++i) {
        const uint16_t h = halfAt(i);
        if ((h & 0x7c00u) == 0x7c00u)  // exponent all ones: infinity or NaN
            throw Error(fmt::format("{}: texel ({}, {}) {}: {} is not finite", shown(tablePath),
                                    (i / 3) % size_t(width), (i / 3) / size_t(width), "RGB"[i % 3],
                                    (h & 0x3ffu) ? "NaN" : "infinity"));
        expected.rgb[i] = kHalfToFloat[h];
    }
    const std::string actual = raw ? hash : skin::halfContentHash(half);  // raw: the CRC above
    if (actual != hash)
        throw Error(
            fmt::format("{}: content hash {} does not match {} {}.hash ({}); the file is corrupt or from another bake",
                        shown(tablePath), actual, reader.source, path, io::messageText(hash)));
    return expected;
}

}  // namespace

// Builds and validates sets for LutSet's save/load (needs its private members).
struct LutSetAccess {
    static LutSet load(const fs::path& dir);
};

void LutSet::save(const fs::path& dir, const LutSaveOptions& options) const {
    for (const LutTable* table : {&diffuse_, &penumbra_, &shTransfer_, &transmittance_}) {
        const size_t bad = skin::nonFiniteValues(*table);
        if (bad > 0)
            throw Error(
                fmt::format("{}: table {}: {} values are not finite; nothing written", shown(dir), table->name, bad));
    }
    if (!options.rawTables) image::encoderFor(dir / kDiffuseFile.fileName);  // an EXR writer is registered
    struct Pending {
        fs::path finalPath;
        std::function<void(const fs::path& temp)> write;
    };
    std::vector<Pending> files;
    auto addTable = [&](const LutTable& table, const TableFile& file) {
        const fs::path path = dir / file.name(options.rawTables);
        files.push_back({path, [&table, shownPath = path, raw = options.rawTables](const fs::path& temp) {
                             if (raw)
                                 writeRaw(temp, shownPath, table);
                             else
                                 writeExr(temp, shownPath, table);
                         }});
    };
    addTable(diffuse_, kDiffuseFile);
    addTable(penumbra_, kPenumbraFile);
    addTable(shTransfer_, kShFile);
    addTable(transmittance_, kTransmittanceFile);
    if (options.previewPngs) {
        auto addPreview = [&](const LutTable& table, const TableFile& file, int rowRepeat) {
            files.push_back(
                {dir / file.preview, [&table, rowRepeat, shownPath = dir / file.preview](const fs::path& temp) {
                     writePreview(temp, shownPath, table, rowRepeat);
                 }});
        };
        addPreview(diffuse_, kDiffuseFile, 1);
        addPreview(penumbra_, kPenumbraFile, 1);
        addPreview(shTransfer_, kShFile, 16);
        addPreview(transmittance_, kTransmittanceFile, 32);
    }
    const std::string manifest = manifestText(*this, options.rawTables);
    files.push_back({dir / kManifestName, [&manifest, shownPath = dir / kManifestName](const fs::path& temp) {
                         writeText(temp, shownPath, manifest);
                     }});

    // Create the folder, remembering what did not exist so a failure can remove it again.
    std::vector<fs::path> created;
    std::error_code ec;
    for (fs::path p = dir; !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
        created.push_back(p);
        if (p == p.parent_path()) break;
    }
    if (!fs::create_directories(dir, ec) && ec)
        throw Error(fmt::format("{}: cannot create the output folder: {}", shown(dir), ec.message()));
    if (!fs::is_directory(dir, ec)) throw Error(fmt::format("{}: exists and is not a folder", shown(dir)));

    std::random_device entropy;
    const std::string tag = fmt::format("{:08x}", entropy());
    std::vector<fs::path> temps;
    try {
        // Refuse before writing anything if a target cannot be replaced by a rename.
        for (const Pending& file : files) {
            struct stat st {};
            if (::stat(file.finalPath.c_str(), &st) != 0) continue;
            if (!S_ISREG(st.st_mode))
                throw Error(
                    fmt::format("{}: output: exists and is not a regular file; not replaced", shown(file.finalPath)));
            if ((st.st_mode & (S_IWUSR | S_IWGRP | S_IWOTH)) == 0 || ::access(file.finalPath.c_str(), W_OK) != 0)
                throw Error(fmt::format("{}: output: exists and is read-only; not replaced", shown(file.finalPath)));
        }
        for (const Pending& file : files) {
            const fs::path temp = dir /
                fmt::format(".{}.tmp-{}{}", file.finalPath.stem().string(), tag, file.finalPath.extension().string());
            temps.push_back(temp);
            file.write(temp);
        }
        for (size_t i = 0; i < files.size(); ++i) {
            fs::rename(temps[i], files[i].finalPath, ec);
            if (ec) throw Error(fmt::format("{}: cannot move into place: {}", shown(files[i].finalPath), ec.message()));
        }
    } catch (...) {
        for (const fs::path& temp : temps) fs::remove(temp, ec);
        for (const fs::path& p : created) fs::remove(p, ec);  // only removes empty folders
        throw;
    }
}

LutSet LutSetAccess::load(const fs::path& dir) {
    const fs::path manifestPath = dir / kManifestName;
    ManifestReader reader{shown(manifestPath)};
    const nlohmann::json j =
        io::parseJson(io::readInputFile(manifestPath, reader.source, limits::kMaxManifestBytes), reader.source);
    if (!j.is_object()) reader.fail("(root)", "must be a JSON object");
    if (reader.string(j, "", "format") != kFormat) reader.fail("format", fmt::format("expected \"{}\"", kFormat));
    const int version = reader.integer(j, "", "version");
    if (version != kVersion)
        reader.fail("version", fmt::format("unsupported version {} (this build reads {})", version, kVersion));

    DiffusionProfile profile = skin::parseProfileJson(reader.field(j, "", "profile"), reader.source, "profile.");
    const nlohmann::json& s = reader.field(j, "", "settings");
    LutBakeSettings settings;
    settings.diffuseNoLSize = reader.integer(s, "settings", "diffuseNoLSize");
    settings.diffuseCurvatureSize = reader.integer(s, "settings", "diffuseCurvatureSize");
    settings.penumbraShadowSize = reader.integer(s, "settings", "penumbraShadowSize");
    settings.penumbraWidthSize = reader.integer(s, "settings", "penumbraWidthSize");
    settings.shCurvatureSize = reader.integer(s, "settings", "shCurvatureSize");
    settings.transmittanceSize = reader.integer(s, "settings", "transmittanceSize");
    settings.curvatureMaxPerMm = reader.number(s, "settings", "curvatureMaxPerMm");
    skin::validateBakeSettings(settings, reader.source, "settings.");

    skin::LutLayout layout = skin::makeLutLayout(profile, settings);
    const nlohmann::json& tables = reader.field(j, "", "tables");
    const double referenceWidth =
        reader.number(reader.field(tables, "tables", "penumbra"), "tables.penumbra", "referenceWidthMm");
    if (!sameNumber(referenceWidth, layout.penumbraReferenceWidthMm))
        reader.fail("tables.penumbra.referenceWidthMm",
                    fmt::format("{} does not match the profile ({})", referenceWidth, layout.penumbraReferenceWidthMm));

    LutSet set(std::move(profile));
    set.settings_ = settings;
    set.penumbraReferenceWidthMm_ = layout.penumbraReferenceWidthMm;
    set.diffuse_ = readTable(dir, reader, tables, kDiffuseFile, std::move(layout.diffuse));
    set.penumbra_ = readTable(dir, reader, tables, kPenumbraFile, std::move(layout.penumbra));
    set.shTransfer_ = readTable(dir, reader, tables, kShFile, std::move(layout.shTransfer));
    set.transmittance_ = readTable(dir, reader, tables, kTransmittanceFile, std::move(layout.transmittance));
    return set;
}

LutSet LutSet::load(const fs::path& dir) { return LutSetAccess::load(dir); }

const LutSet& LutSet::loadDefault() {
    static const LutSet set = bake(DiffusionProfile::deonLuebke());
    return set;
}

}  // namespace preskin
