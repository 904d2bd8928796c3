// Environment loading (the registered image codecs) and L2 SH projection; see <preskin/Environment.h>.
#include <preskin/Environment.h>
#include <preskin/Error.h>
#include <preskin/ImageCodec.h>
#include <preskin/Limits.h>

#include "env/EnvironmentHeader.h"
#include "image/ImageCodecs.h"
#include "io/InputFile.h"
#include "io/MessageText.h"
#include "io/NumberRule.h"

#include <fmt/core.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>

namespace preskin {

std::array<float, 9> shBasis(const glm::vec3& d) {
    using namespace gpu;  // the basis constants of shared/constants.h, as preskin/sh.glsl uses them
    return {kShY00,
            kShY1 * d.y,
            kShY1 * d.z,
            kShY1 * d.x,
            kShY2 * d.x * d.y,
            kShY2 * d.y * d.z,
            kShY20 * (3.0f * d.z * d.z - 1.0f),
            kShY2 * d.x * d.z,
            kShY22 * (d.x * d.x - d.y * d.y)};
}

glm::vec3 evaluateSh(const ShRgb& sh, const glm::vec3& direction, const glm::vec3& bandScale) {
    const auto y = shBasis(direction);
    glm::vec3 sum = sh.c[0] * y[0] * bandScale[0];
    for (int i = 1; i < 4; ++i) sum += sh.c[i] * y[i] * bandScale[1];
    for (int i = 4; i < 9; ++i) sum += sh.c[i] * y[i] * bandScale[2];
    return sum;
}

glm::vec3 EquirectImage::directionAt(float u, float v) {
    const float phi = 2.0f * kPi * (u - 0.5f);
    const float theta = kPi * v;
    return {std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)};
}

glm::vec3 rotateY(const glm::vec3& d, float rotationY) {
    const float c = std::cos(rotationY);
    const float s = std::sin(rotationY);
    return {c * d.x + s * d.z, d.y, -s * d.x + c * d.z};
}

EquirectImage boxFiltered(const EquirectImage& image, uint32_t maxWidth) {
    uint32_t factor = 1;
    while (image.width / factor > maxWidth && image.height / factor >= 2) factor *= 2;
    if (factor == 1) return image;
    EquirectImage out;
    out.width = std::max(image.width / factor, 1u);
    out.height = std::max(image.height / factor, 1u);
    out.rgb.resize(size_t(out.width) * out.height * 3);
    for (uint32_t y = 0; y < out.height; ++y) {
        const uint32_t sy0 = uint32_t(uint64_t(y) * image.height / out.height);
        const uint32_t sy1 = std::max(uint32_t(uint64_t(y + 1) * image.height / out.height), sy0 + 1);
        for (uint32_t x = 0; x < out.width; ++x) {
            const uint32_t sx0 = uint32_t(uint64_t(x) * image.width / out.width);
            const uint32_t sx1 = std::max(uint32_t(uint64_t(x + 1) * image.width / out.width), sx0 + 1);
            glm::dvec3 sum(0.0);
            for (uint32_t sy = sy0; sy < sy1; ++sy)
                for (uint32_t sx = sx0; sx < sx1; ++sx) sum += glm::dvec3(image.texel(sx, sy));
            const glm::vec3 mean(sum / double((sy1 - sy0) * (sx1 - sx0)));
            for (int c = 0; c < 3; ++c) out.rgb[(size_t(y) * out.width + x) * 3 + size_t(c)] = mean[c];
        }
    }
    return out;
}

Environment Environment::downsampled(uint32_t maxWidth) const {
    Environment out;
    out.radianceSh_ = radianceSh_;
    out.image_ = boxFiltered(image_, maxWidth);
    out.intensity_ = intensity_;
    out.rotationY_ = rotationY_;
    out.constant_ = constant_;
    out.warnings_ = warnings_;
    return out;
}

ShRgb projectEquirect(const EquirectImage& image, float rotationY) {
    // Row y spans theta in [pi y/H, pi (y+1)/H]; its exact solid angle per texel is
    // (2 pi / W) (cos(theta0) - cos(theta1)).
    using Acc = std::array<glm::dvec3, 9>;
    const Acc total = tbb::parallel_reduce(
        tbb::blocked_range<uint32_t>(0, image.height), Acc{},
        [&](const tbb::blocked_range<uint32_t>& rows, Acc acc) {
            for (uint32_t y = rows.begin(); y != rows.end(); ++y) {
                const double theta0 = M_PI * y / image.height;
                const double theta1 = M_PI * (y + 1) / image.height;
                const double solidAngle = (2.0 * M_PI / image.width) * (std::cos(theta0) - std::cos(theta1));
                const float v = (static_cast<float>(y) + 0.5f) / static_cast<float>(image.height);
                for (uint32_t x = 0; x < image.width; ++x) {
                    const float u = (static_cast<float>(x) + 0.5f) / static_cast<float>(image.width);
                    const auto basis = shBasis(rotateY(EquirectImage::directionAt(u, v), rotationY));
                    const glm::dvec3 radiance(image.texel(x, y));
                    for (int i = 0; i < 9; ++i) acc[i] += radiance * (double(basis[i]) * solidAngle);
                }
            }
            return acc;
        },
        [](Acc a, const Acc& b) {
            for (int i = 0; i < 9; ++i) a[i] += b[i];
            return a;
        });
    ShRgb sh;
    for (int i = 0; i < 9; ++i) sh.c[i] = glm::vec3(total[i]);
    return sh;
}

Environment Environment::load(const std::filesystem::path& path, float intensity, float rotationY) {
    const std::string name = path.string();
    if (auto problem = io::numberProblem(intensity)) throw Error(fmt::format("{}: intensity: {}", name, *problem));
    const std::vector<uint8_t> bytes = io::readInputFile(path, name, limits::kMaxImageFileBytes);
    return load(bytes, name, intensity, rotationY);
}

Environment Environment::load(std::span<const uint8_t> bytes, const std::string& name, float intensity,
                              float rotationY) {
    if (auto problem = io::numberProblem(intensity)) throw Error(fmt::format("{}: intensity: {}", name, *problem));
    if (intensity < 0.0f) throw Error(fmt::format("{}: intensity: {} is negative", name, intensity));
    if (auto problem = io::numberProblem(rotationY)) throw Error(fmt::format("{}: rotation: {}", name, *problem));

    // Format and size come from the file's own header, checked before any decoder allocates.
    env::EnvironmentHeader header;
    try {
        header =
            env::readEnvironmentHeader(std::span(bytes).first(std::min(bytes.size(), env::kEnvironmentHeaderBytes)));
    } catch (const std::exception& e) {
        throw Error(fmt::format("{}: {}", name, e.what()));
    }
    if (header.width <= 0 || header.height <= 0 || header.width > limits::kMaxEnvironmentWidth ||
        header.height > limits::kMaxEnvironmentHeight)
        throw Error(fmt::format("{}: size: {}x{} is not a supported environment size (at most {}x{})", name,
                                header.width, header.height, limits::kMaxEnvironmentWidth,
                                limits::kMaxEnvironmentHeight));
    if (header.width != 2 * header.height)
        throw Error(fmt::format("{}: size: {}x{} is not equirectangular (width must be twice the height)", name,
                                header.width, header.height));

    // Radiance files decode in the core; OpenEXR through a registered codec (preskin::imageio).
    const DecodeLimits decodeLimits{uint64_t(limits::kMaxEnvironmentWidth) * limits::kMaxEnvironmentHeight,
                                    uint32_t(limits::kMaxEnvironmentWidth)};
    PixelImage decoded;
    try {
        decoded = decodeImage(bytes, decodeLimits, "cannot decode environment image");
    } catch (const Error& e) {
        throw Error(fmt::format("{}: {}", name, e.what()));
    }
    if (int64_t(decoded.width) != header.width || int64_t(decoded.height) != header.height)
        throw Error(fmt::format("{}: size: the decoder reads {}x{}, the header says {}x{}", name, decoded.width,
                                decoded.height, header.width, header.height));
    Environment env;
    env.intensity_ = intensity;
    env.image_.width = decoded.width;
    env.image_.height = decoded.height;
    env.image_.rgb = image::toRgbFloat(decoded);
    decoded = {};
    // Every pixel passes the input-number rule. Negative radiance is taken as 0; beyond a lossy
    // encoding's undershoot (a millionth of the image's mean magnitude) the host is told.
    double magnitude = 0.0;
    for (size_t i = 0; i < env.image_.rgb.size(); ++i) {
        const float v = env.image_.rgb[i];
        if (auto problem = io::numberProblem(v))
            throw Error(fmt::format("{}: pixel ({}, {}): radiance {}", name, (i / 3) % env.image_.width,
                                    (i / 3) / env.image_.width, *problem));
        magnitude += std::abs(double(v));
    }
    const double undershoot = -1e-6 * magnitude / double(std::max<size_t>(env.image_.rgb.size(), 1));
    size_t negative = 0, first = 0;
    float lowest = 0.0f;
    for (size_t i = 0; i < env.image_.rgb.size(); ++i) {
        float& v = env.image_.rgb[i];
        if (double(v) < undershoot) {
            if (negative++ == 0) first = i;
            lowest = std::min(lowest, v);
        }
        v = std::max(v, 0.0f) * intensity;
    }
    if (negative > 0)
        env.warnings_.push_back(fmt::format(
            "{}: pixels: {} of {} values are negative radiance (the lowest {}, the first at pixel ({}, {})); taken as 0",
            name, negative, env.image_.rgb.size(), lowest, (first / 3) % env.image_.width,
            (first / 3) / env.image_.width));
    env.radianceSh_ = projectEquirect(env.image_, rotationY);
    env.rotationY_ = rotationY;
    return env;
}

glm::vec3 Environment::radiance(const glm::vec3& directionWs) const {
    if (image_.width == 0 || image_.height == 0) return constant_;
    const glm::vec3 d = rotateY(directionWs, -rotationY_);
    const float theta = std::acos(std::clamp(d.y, -1.0f, 1.0f));
    const float phi = std::atan2(d.z, d.x);
    float u = phi / (2.0f * kPi) + 0.5f;
    u -= std::floor(u);
    const auto x = std::min(uint32_t(u * float(image_.width)), image_.width - 1);
    const auto y = std::min(uint32_t(theta / kPi * float(image_.height)), image_.height - 1);
    return image_.texel(x, y);
}

Environment Environment::fromImage(EquirectImage image, float rotationY) {
    if (image.width == 0 || image.width != 2 * image.height || image.width > limits::kMaxEnvironmentWidth ||
        image.rgb.size() != size_t(image.width) * image.height * 3)
        throw Error(fmt::format(
            "environment image: size: {}x{} with {} values is not an equirectangular RGB image of "
            "at most {}x{}",
            image.width, image.height, image.rgb.size(), limits::kMaxEnvironmentWidth, limits::kMaxEnvironmentHeight));
    if (auto problem = io::numberProblem(rotationY))
        throw Error(fmt::format("environment image: rotation: {}", *problem));
    for (size_t i = 0; i < image.rgb.size(); ++i)
        if (auto problem = io::numberProblem(image.rgb[i]); problem || image.rgb[i] < 0.0f)
            throw Error(fmt::format("environment image: pixel ({}, {}): radiance {}", (i / 3) % image.width,
                                    (i / 3) / image.width, problem ? *problem : std::string("is negative")));
    Environment env;
    env.image_ = std::move(image);
    env.radianceSh_ = projectEquirect(env.image_, rotationY);
    env.rotationY_ = rotationY;
    return env;
}

Environment Environment::constant(const glm::vec3& radiance) {
    Environment env;
    // A constant function c has only c_00 = c * sqrt(4 pi).
    env.radianceSh_.c[0] = radiance * std::sqrt(4.0f * kPi);
    env.constant_ = radiance;
    return env;
}

}  // namespace preskin
