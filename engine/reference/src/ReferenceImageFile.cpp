// Reference images as files (writeReferenceImage, readReferenceImage): a 32-bit float OpenEXR
// with the radiance, the masks `preskin compare` measures by, and the key of what made it, so an
// expensive reference is computed once and measured against many renders.
#include <preskin/DiffusionReference.h>
#include <preskin/Error.h>
#include <preskin/Limits.h>
#include <preskin/OutputFile.h>

#include "io/InputFile.h"
#include "io/MessageText.h"

#include <OpenImageIO/imageio.h>
#include <fmt/core.h>
#include <unistd.h>

#include <array>
#include <cmath>

namespace preskin {

namespace {

constexpr std::array<const char*, 8> kChannels = {
    "R", "G", "B", "A", "skin", "curvaturePerMm", "nearShadowEdge", "terminatorBand"};
constexpr std::string_view kKeyPrefix = "preskin:";

}  // namespace

void writeReferenceImage(const std::filesystem::path& path, const ReferenceImage& image, const ReferenceKey& key) {
    const size_t count = size_t(image.width) * image.height;
    if (count == 0 || image.rgba32f.size() != count * 4 || image.skin.size() != count ||
        image.curvaturePerMm.size() != count || image.nearShadowEdge.size() != count ||
        image.terminatorBand.size() != count)
        throw Error(fmt::format("{}: reference: image data does not match its size {}x{}", path.string(), image.width,
                                image.height));
    std::vector<float> pixels(count * kChannels.size());
    for (size_t i = 0; i < count; ++i) {
        float* p = pixels.data() + i * kChannels.size();
        for (int c = 0; c < 4; ++c) p[c] = image.rgba32f[4 * i + size_t(c)];
        p[4] = float(image.skin[i]);
        p[5] = image.curvaturePerMm[i];
        p[6] = float(image.nearShadowEdge[i]);
        p[7] = float(image.terminatorBand[i]);
        for (size_t c = 0; c < kChannels.size(); ++c)
            if (!std::isfinite(p[c]))
                throw Error(fmt::format("{}: reference: channel {} is not finite at pixel {}; nothing written",
                                        path.string(), kChannels[c], i));
    }
    OIIO::ImageSpec spec(int(image.width), int(image.height), int(kChannels.size()), OIIO::TypeDesc::FLOAT);
    spec.channelnames.assign(kChannels.begin(), kChannels.end());
    spec.alpha_channel = 3;
    spec.attribute("oiio:ColorSpace", "Linear");
    spec.attribute("compression", "zip");
    for (const auto& [name, value] : key) spec.attribute(std::string(kKeyPrefix) + name, value);

    spec.attribute("DateTime", "");  // no time stamp: the same reference is the same bytes
    writeOutputFile(path, [&](const std::filesystem::path& temp) {
        auto out = OIIO::ImageOutput::create("openexr");
        if (!out) throw Error(fmt::format("{}: no OpenEXR writer: {}", path.string(), OIIO::geterror()));
        if (!out->open(temp.string(), spec))
            throw Error(fmt::format("{}: cannot create file: {}", path.string(), out->geterror()));
        if (!out->write_image(OIIO::TypeDesc::FLOAT, pixels.data())) {
            const std::string error = out->geterror();
            out->close();
            throw Error(fmt::format("{}: cannot write image: {}", path.string(), error));
        }
        if (!out->close()) throw Error(fmt::format("{}: cannot finish image: {}", path.string(), out->geterror()));
    });
}

ReferenceImage readReferenceImage(const std::filesystem::path& path, ReferenceKey& key) {
    const std::string name = path.string();
    io::checkInputFile(path, name, limits::kMaxImageFileBytes);
    auto input = OIIO::ImageInput::open(name);
    if (!input) throw Error(fmt::format("{}: reference: cannot read: {}", name, io::messageText(OIIO::geterror())));
    const OIIO::ImageSpec& spec = input->spec();
    if (spec.width < 1 || spec.height < 1 || spec.width > 16384 || spec.height > 16384)
        throw Error(fmt::format("{}: reference: size {}x{} is outside 1..16384 pixels per side", name, spec.width,
                                spec.height));
    std::array<int, kChannels.size()> index{};
    for (size_t c = 0; c < kChannels.size(); ++c) {
        index[c] = spec.channelindex(kChannels[c]);
        if (index[c] < 0)
            throw Error(
                fmt::format("{}: reference: channel {}: missing: not a reference this preskin writes (an older "
                            "one, or another file: remove it and let `preskin compare --reference` or `preskin "
                            "reference` write it again)",
                            name, kChannels[c]));
    }
    key.clear();
    for (const OIIO::ParamValue& p : spec.extra_attribs) {
        const std::string attribute = p.name().string();
        if (attribute.rfind(kKeyPrefix, 0) == 0 && p.type() == OIIO::TypeDesc::STRING)
            key.emplace_back(attribute.substr(kKeyPrefix.size()), p.get_string());
    }
    const size_t count = size_t(spec.width) * size_t(spec.height);
    const size_t channels = size_t(spec.nchannels);
    std::vector<float> pixels(count * channels);
    if (!input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data()))
        throw Error(fmt::format("{}: reference: cannot read pixels: {}", name, io::messageText(input->geterror())));
    input->close();

    ReferenceImage image;
    image.width = uint32_t(spec.width);
    image.height = uint32_t(spec.height);
    image.rgba32f.resize(count * 4);
    image.skin.resize(count);
    image.curvaturePerMm.resize(count);
    image.nearShadowEdge.resize(count);
    image.terminatorBand.resize(count);
    for (size_t i = 0; i < count; ++i) {
        const float* p = pixels.data() + i * channels;
        for (size_t c = 0; c < kChannels.size(); ++c)
            if (!std::isfinite(p[index[c]]))
                throw Error(fmt::format("{}: reference: channel {}: not finite at pixel {}", name, kChannels[c], i));
        for (int c = 0; c < 4; ++c) image.rgba32f[4 * i + size_t(c)] = p[index[size_t(c)]];
        image.skin[i] = p[index[4]] > 0.5f ? 1 : 0;
        image.curvaturePerMm[i] = p[index[5]];
        image.nearShadowEdge[i] = p[index[6]] > 0.5f ? 1 : 0;
        image.terminatorBand[i] = p[index[7]] > 0.5f ? 1 : 0;
    }
    return image;
}

}  // namespace preskin
