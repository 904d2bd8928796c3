// DiffusionProfile: sum-of-Gaussians (d'Eon & Luebke 2007) and normalized-diffusion
// (Christensen & Burley 2015) radial profiles, their line integrals, edge responses and slab
// transmittance, plus JSON reading with field-level validation. Formulas: DiffusionProfile.h.
// Limits: see DiffusionProfile.h and ProfileJson.h.
#include <preskin/DiffusionProfile.h>

#include "skin/ProfileJson.h"
#include "skin/Quadrature.h"
#include "skin/SpecialFunctions.h"

#include <preskin/Error.h>
#include <preskin/Limits.h>

#include "io/InputFile.h"
#include "io/JsonDocument.h"
#include "io/MessageText.h"
#include "io/NumberRule.h"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace preskin {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr std::array<const char*, 3> kChannelNames{"R", "G", "B"};

[[noreturn]] void fail(std::string_view source, std::string_view field, std::string_view problem) {
    throw Error(fmt::format("{}: {}: {}", source, field, io::messageText(problem, 4 * io::kMessageExcerptChars)));
}

// Burley's searchlight fit of d = l / s(A) (Christensen & Burley 2015, eq. for the
// searchlight configuration with the mean free path).
double searchlightScale(double albedo) {
    const double x = std::abs(albedo - 0.8);
    return 1.85 - albedo + 7.0 * x * x * x;
}

void checkGaussians(const std::vector<GaussianTerm>& terms, std::string_view source, std::string_view prefix) {
    const std::string field = std::string(prefix) + "gaussians";
    if (terms.empty()) fail(source, field, "must hold at least one term");
    if (terms.size() > static_cast<size_t>(skin::kMaxGaussianTerms))
        fail(source, field, fmt::format("at most {} terms, got {}", skin::kMaxGaussianTerms, terms.size()));
    glm::dvec3 sum{0.0};
    for (size_t i = 0; i < terms.size(); ++i) {
        const double v = terms[i].varianceMm2;
        const std::string at = fmt::format("{}[{}]", field, i);
        if (!std::isfinite(v)) fail(source, at + ".varianceMm2", fmt::format("must be finite, got {}", v));
        if (!(v >= skin::kMinVarianceMm2))
            fail(source, at + ".varianceMm2",
                 fmt::format("must be >= {} mm^2 (a Gaussian 1 um wide), got {}", skin::kMinVarianceMm2, v));
        if (v > skin::kMaxVarianceMm2)
            fail(source, at + ".varianceMm2", fmt::format("must be <= {} mm^2, got {}", skin::kMaxVarianceMm2, v));
        for (int c = 0; c < 3; ++c) {
            const double w = terms[i].weight[c];
            const std::string wf = fmt::format("{}.weights[{}]", at, c);
            if (!std::isfinite(w)) fail(source, wf, fmt::format("must be finite, got {}", w));
            if (w < 0.0) fail(source, wf, fmt::format("must be >= 0, got {}", w));
            sum[c] += w;
        }
    }
    for (int c = 0; c < 3; ++c) {
        if (!(sum[c] > 0.0))
            fail(source, fmt::format("{}[*].weights[{}]", field, c),
                 fmt::format("channel {} has zero albedo (the weights sum to 0)", kChannelNames[c]));
        if (sum[c] > 1.0 + 1e-9)
            fail(source, fmt::format("{}[*].weights[{}]", field, c),
                 fmt::format("channel {} has albedo {:.6g} > 1 (the weights must sum to at most 1)", kChannelNames[c],
                             sum[c]));
    }
}

void checkBurley(glm::dvec3 albedo, glm::dvec3 meanFreePathMm, std::string_view source, std::string_view prefix) {
    for (int c = 0; c < 3; ++c) {
        const std::string af = fmt::format("{}albedo[{}]", prefix, c);
        if (!std::isfinite(albedo[c])) fail(source, af, fmt::format("must be finite, got {}", albedo[c]));
        if (!(albedo[c] > 0.0 && albedo[c] <= 1.0))
            fail(source, af, fmt::format("must be in (0, 1], got {}", albedo[c]));
        const std::string lf = fmt::format("{}meanFreePathMm[{}]", prefix, c);
        const double l = meanFreePathMm[c];
        if (!std::isfinite(l)) fail(source, lf, fmt::format("must be finite, got {}", l));
        if (!(l >= skin::kMinMeanFreePathMm))
            fail(source, lf, fmt::format("must be >= {} mm (1 um), got {}", skin::kMinMeanFreePathMm, l));
        if (l > skin::kMaxMeanFreePathMm)
            fail(source, lf, fmt::format("must be <= {} mm, got {}", skin::kMaxMeanFreePathMm, l));
    }
}

std::string jsonTypeName(const nlohmann::json& j) { return j.type_name(); }

const nlohmann::json& requireField(const nlohmann::json& object, const char* key, std::string_view source,
                                   const std::string& field) {
    const auto it = object.find(key);
    if (it == object.end()) fail(source, field, "missing");
    return *it;
}

double requireNumber(const nlohmann::json& value, std::string_view source, const std::string& field) {
    if (!value.is_number()) fail(source, field, "must be a number, got " + jsonTypeName(value));
    const double number = value.get<double>();
    if (auto problem = io::numberProblem(number)) fail(source, field, *problem);
    return number;
}

glm::dvec3 requireRgb(const nlohmann::json& value, std::string_view source, const std::string& field) {
    if (!value.is_array() || value.size() != 3)
        fail(source, field, "must be an array of three numbers [r, g, b], got " + io::jsonExcerpt(value));
    glm::dvec3 result;
    for (int c = 0; c < 3; ++c)
        result[c] = requireNumber(value[static_cast<size_t>(c)], source, fmt::format("{}[{}]", field, c));
    return result;
}

void rejectUnknownKeys(const nlohmann::json& object, std::initializer_list<std::string_view> known,
                       std::string_view source, const std::string& prefix) {
    for (const auto& item : object.items()) {
        if (std::find(known.begin(), known.end(), item.key()) == known.end())
            fail(source, prefix + io::messageText(item.key()), "unknown field");
    }
}

}  // namespace

DiffusionProfile DiffusionProfile::deonLuebke() {
    // GPU Gems 3, ch. 14, table 14-1 / figure 14-13: variances (mm^2) and RGB weights.
    std::vector<GaussianTerm> terms{
        {0.0064, {0.233, 0.455, 0.649}}, {0.0484, {0.100, 0.336, 0.344}}, {0.187, {0.118, 0.198, 0.000}},
        {0.567, {0.113, 0.007, 0.007}},  {1.99, {0.358, 0.004, 0.000}},   {7.41, {0.078, 0.000, 0.000}},
    };
    return sumOfGaussians(std::move(terms), "d'Eon & Luebke 2007 skin (six Gaussians)", "deonLuebke");
}

DiffusionProfile DiffusionProfile::sumOfGaussians(std::vector<GaussianTerm> terms, std::string name,
                                                  std::string_view source) {
    checkGaussians(terms, source, "");
    DiffusionProfile profile;
    profile.kind_ = Kind::SumOfGaussians;
    profile.name_ = std::move(name);
    profile.gaussians_ = std::move(terms);
    profile.finish();
    return profile;
}

DiffusionProfile DiffusionProfile::burley(glm::dvec3 albedo, glm::dvec3 meanFreePathMm, std::string name) {
    checkBurley(albedo, meanFreePathMm, "burley", "");
    DiffusionProfile profile;
    profile.kind_ = Kind::NormalizedDiffusion;
    profile.name_ = std::move(name);
    profile.albedo_ = albedo;
    profile.meanFreePathMm_ = meanFreePathMm;
    profile.finish();
    return profile;
}

void DiffusionProfile::finish() {
    if (kind_ == Kind::SumOfGaussians) {
        albedo_ = glm::dvec3(0.0);
        glm::dvec3 secondMoment(0.0);
        constants_.clear();
        for (const GaussianTerm& term : gaussians_) {
            const double v = term.varianceMm2;
            albedo_ += term.weight;
            secondMoment += term.weight * (2.0 * v);  // E[r^2] of a 2D Gaussian is 2v
            constants_.push_back(
                {0.5 / v, 1.0 / (2.0 * kPi * v), 1.0 / std::sqrt(2.0 * kPi * v), 1.0 / std::sqrt(2.0 * v)});
        }
        widthMm_ = glm::sqrt(secondMoment / albedo_);
    } else {
        for (int c = 0; c < 3; ++c) distanceMm_[c] = meanFreePathMm_[c] / searchlightScale(albedo_[c]);
        widthMm_ = std::sqrt(14.0) * distanceMm_;  // E[r^2] = (2 d^3 + 2 (3d)^3) / (4 d) = 14 d^2
    }
}

glm::dvec3 DiffusionProfile::R(double rMm) const {
    const double r = std::abs(rMm);
    if (kind_ == Kind::SumOfGaussians) {
        glm::dvec3 sum(0.0);
        for (size_t i = 0; i < gaussians_.size(); ++i)
            sum += gaussians_[i].weight * (constants_[i].radialNorm * std::exp(-r * r * constants_[i].halfInvVariance));
        return sum;
    }
    glm::dvec3 result;
    for (int c = 0; c < 3; ++c) {
        const double d = distanceMm_[c];
        result[c] = r > 0.0 ? albedo_[c] * (std::exp(-r / d) + std::exp(-r / (3.0 * d))) / (8.0 * kPi * d * r)
                            : std::numeric_limits<double>::infinity();
    }
    return result;
}

glm::dvec3 DiffusionProfile::lineProfile(double uMm) const {
    const double u = std::abs(uMm);
    if (kind_ == Kind::SumOfGaussians) {
        glm::dvec3 sum(0.0);
        for (size_t i = 0; i < gaussians_.size(); ++i)
            sum += gaussians_[i].weight * (constants_[i].lineNorm * std::exp(-u * u * constants_[i].halfInvVariance));
        return sum;
    }
    glm::dvec3 result;
    for (int c = 0; c < 3; ++c) {
        const double d = distanceMm_[c];
        // int exp(-sqrt(u^2+y^2)/d) / sqrt(u^2+y^2) dy over the line = 2 K0(u/d).
        result[c] = u > 0.0 ? albedo_[c] * (skin::besselK0(u / d) + skin::besselK0(u / (3.0 * d))) / (4.0 * kPi * d)
                            : std::numeric_limits<double>::infinity();
    }
    return result;
}

glm::dvec3 DiffusionProfile::transmittance(double thicknessMm) const {
    const double t = std::abs(thicknessMm);
    if (kind_ == Kind::SumOfGaussians) {
        glm::dvec3 sum(0.0);
        for (size_t i = 0; i < gaussians_.size(); ++i)
            sum += gaussians_[i].weight * std::exp(-t * t * constants_[i].halfInvVariance);
        return sum / albedo_;
    }
    glm::dvec3 result;
    for (int c = 0; c < 3; ++c) {
        const double d = distanceMm_[c];
        result[c] = 0.25 * (std::exp(-t / d) + 3.0 * std::exp(-t / (3.0 * d)));
    }
    return result;
}

glm::dvec3 DiffusionProfile::edgeResponse(double xMm) const {
    if (kind_ == Kind::SumOfGaussians) {
        glm::dvec3 sum(0.0);
        for (size_t i = 0; i < gaussians_.size(); ++i)
            sum += gaussians_[i].weight * (0.5 * std::erfc(-xMm * constants_[i].invSigmaSqrt2));
        return sum / albedo_;
    }
    // The light reaching a point at distance a from a lit half-plane is
    // (1/pi) int_0^{pi/2} T(a / sin(psi)) dpsi (integrate the radial profile over the
    // half-plane in polar coordinates and by parts; for a Gaussian this is Craig's formula).
    // Composite Gauss-Legendre on a mesh graded geometrically towards psi = 0.
    const double a = std::abs(xMm);
    glm::dvec3 beyond(0.5);
    if (a > 0.0) {
        const skin::GaussLegendreRule& rule = skin::gaussLegendre(8);
        for (int c = 0; c < 3; ++c) {
            const double d = distanceMm_[c];
            auto integrand = [&](double psi) {
                const double rho = a / std::sin(psi);
                return 0.25 * (std::exp(-rho / d) + 3.0 * std::exp(-rho / (3.0 * d)));
            };
            // Below psiMin the integrand is below exp(-60): a / sin(psi) > 180 d.
            const double psiMin = std::min(a / (180.0 * d), 0.5 * kPi);
            double sum = 0.0;
            double hi = 0.5 * kPi;
            while (hi > psiMin) {
                const double lo = std::max(0.5 * hi, psiMin);
                sum += skin::integrateGaussLegendre<double>(rule, lo, hi, integrand);
                hi = lo;
            }
            beyond[c] = sum / kPi;
        }
    }
    return xMm >= 0.0 ? glm::dvec3(1.0) - beyond : beyond;
}

double DiffusionProfile::reachMm(double tailFraction) const {
    auto largest = [&](double d) {
        const glm::dvec3 t = transmittance(d);
        return std::max({t.x, t.y, t.z});
    };
    double lo = 0.0;
    double hi = maxWidthMm();
    while (largest(hi) > tailFraction) {
        lo = hi;
        hi *= 2.0;
    }
    for (int i = 0; i < 200 && hi - lo > 1e-9 * hi; ++i) {
        const double mid = 0.5 * (lo + hi);
        (largest(mid) > tailFraction ? lo : hi) = mid;
    }
    return hi;
}

double DiffusionProfile::maxWidthMm() const { return std::max({widthMm_.x, widthMm_.y, widthMm_.z}); }

double DiffusionProfile::narrowestScaleMm() const {
    if (kind_ == Kind::NormalizedDiffusion) return std::min({distanceMm_.x, distanceMm_.y, distanceMm_.z});
    double narrowest = std::numeric_limits<double>::infinity();
    for (const GaussianTerm& term : gaussians_) {
        if (term.weight.x > 0.0 || term.weight.y > 0.0 || term.weight.z > 0.0)
            narrowest = std::min(narrowest, std::sqrt(term.varianceMm2));
    }
    return narrowest;
}

std::string DiffusionProfile::toJson() const { return skin::profileToJson(*this).dump(2); }

DiffusionProfile DiffusionProfile::fromJsonText(std::string_view text, std::string_view sourceName) {
    const std::string source(sourceName);
    if (text.size() > limits::kMaxProfileBytes)
        throw Error(fmt::format("{}: file: {} bytes exceeds the limit of {} bytes", source, text.size(),
                                limits::kMaxProfileBytes));
    return skin::parseProfileJson(io::parseJson(text, source), sourceName, "");
}

DiffusionProfile DiffusionProfile::fromJsonFile(const std::filesystem::path& path) {
    const std::vector<uint8_t> bytes = io::readInputFile(path, path.string(), limits::kMaxProfileBytes);
    return fromJsonText(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), path.string());
}

namespace skin {

DiffusionProfile parseProfileJson(const nlohmann::json& json, std::string_view source, std::string_view fieldPrefix) {
    const std::string prefix(fieldPrefix);
    const std::string rootName = prefix.empty() ? std::string("(root)") : prefix.substr(0, prefix.size() - 1);
    if (!json.is_object()) fail(source, rootName, "must be a JSON object, got " + jsonTypeName(json));
    const nlohmann::json& type = requireField(json, "type", source, prefix + "type");
    if (!type.is_string())
        fail(source, prefix + "type",
             "must be \"deonLuebke\", \"sumOfGaussians\" or \"normalizedDiffusion\", got " + io::jsonExcerpt(type));
    std::string name;
    if (const auto it = json.find("name"); it != json.end()) {
        if (!it->is_string()) fail(source, prefix + "name", "must be a string, got " + jsonTypeName(*it));
        name = it->get<std::string>();
    }

    if (type == "deonLuebke") {
        rejectUnknownKeys(json, {"type", "name"}, source, prefix);
        return name.empty()
            ? DiffusionProfile::deonLuebke()
            : DiffusionProfile::sumOfGaussians(DiffusionProfile::deonLuebke().gaussians(), name, source);
    }
    if (type == "lutFolder")
        fail(
            source, prefix + "type",
            "\"lutFolder\" names LUTs already baked: load the folder (--luts, LutSet::load), there is no profile to bake");
    if (type == "sumOfGaussians") {
        rejectUnknownKeys(json, {"type", "name", "gaussians"}, source, prefix);
        const nlohmann::json& list = requireField(json, "gaussians", source, prefix + "gaussians");
        if (!list.is_array()) fail(source, prefix + "gaussians", "must be an array, got " + jsonTypeName(list));
        std::vector<GaussianTerm> terms;
        for (size_t i = 0; i < list.size(); ++i) {
            const std::string at = fmt::format("{}gaussians[{}]", prefix, i);
            const nlohmann::json& item = list[i];
            if (!item.is_object()) fail(source, at, "must be an object, got " + jsonTypeName(item));
            rejectUnknownKeys(item, {"varianceMm2", "weights"}, source, at + ".");
            GaussianTerm term;
            term.varianceMm2 = requireNumber(requireField(item, "varianceMm2", source, at + ".varianceMm2"), source,
                                             at + ".varianceMm2");
            term.weight = requireRgb(requireField(item, "weights", source, at + ".weights"), source, at + ".weights");
            terms.push_back(term);
        }
        checkGaussians(terms, source, prefix);
        return DiffusionProfile::sumOfGaussians(std::move(terms), name.empty() ? "sum of Gaussians" : name, source);
    }
    if (type == "normalizedDiffusion") {
        rejectUnknownKeys(json, {"type", "name", "albedo", "meanFreePathMm"}, source, prefix);
        const glm::dvec3 albedo =
            requireRgb(requireField(json, "albedo", source, prefix + "albedo"), source, prefix + "albedo");
        const glm::dvec3 mfp = requireRgb(requireField(json, "meanFreePathMm", source, prefix + "meanFreePathMm"),
                                          source, prefix + "meanFreePathMm");
        checkBurley(albedo, mfp, source, prefix);
        return name.empty() ? DiffusionProfile::burley(albedo, mfp)
                            : DiffusionProfile::burley(albedo, mfp, std::move(name));
    }
    fail(source, prefix + "type",
         "must be \"deonLuebke\", \"sumOfGaussians\" or \"normalizedDiffusion\", got " + io::jsonExcerpt(type));
}

nlohmann::ordered_json profileToJson(const DiffusionProfile& profile) {
    nlohmann::ordered_json json;
    auto rgb = [](glm::dvec3 v) { return nlohmann::ordered_json::array({v.x, v.y, v.z}); };
    if (profile.kind() == DiffusionProfile::Kind::SumOfGaussians) {
        json["type"] = "sumOfGaussians";
        json["name"] = profile.name();
        nlohmann::ordered_json list = nlohmann::ordered_json::array();
        for (const GaussianTerm& term : profile.gaussians())
            list.push_back(nlohmann::ordered_json{{"varianceMm2", term.varianceMm2}, {"weights", rgb(term.weight)}});
        json["gaussians"] = std::move(list);
    } else {
        json["type"] = "normalizedDiffusion";
        json["name"] = profile.name();
        json["albedo"] = rgb(profile.albedo());
        json["meanFreePathMm"] = rgb(profile.meanFreePathMm());
    }
    return json;
}

}  // namespace skin
}  // namespace preskin
