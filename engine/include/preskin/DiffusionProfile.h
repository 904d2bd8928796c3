// DiffusionProfile: the radial diffusion profile R(r) of skin, per RGB channel, in millimetres.
// It is the single physical input of every skin LUT (diffuse ring integral, penumbra,
// SH transfer, transmittance).
//
// Two families:
//  - Sum of Gaussians (d'Eon & Luebke, "Advanced Techniques for Realistic Real-Time Skin
//    Rendering", GPU Gems 3 ch. 14, 2007): R(r) = sum_i w_i G(v_i, r),
//    G(v, r) = exp(-r^2 / 2v) / (2 pi v). `deonLuebke()` is their six-Gaussian skin fit;
//    `fromJsonFile` reads any sum of Gaussians.
//  - Normalized diffusion (Christensen & Burley, "Approximate Reflectance Profiles for Efficient
//    Subsurface Scattering", 2015): R(r) = A (exp(-r/d) + exp(-r/3d)) / (8 pi d r), with
//    d = l / s(A) from the mean free path l and the searchlight fit s(A) = 1.85 - A + 7|A - 0.8|^3.
//
// Every profile integrates (int 2 pi r R(r) dr over [0, inf)) to its albedo, per channel.
//
// Deliberate choice, the "1.414" variance scale: some published pre-integration code multiplies
// d'Eon's variances by 1.414 (and evaluates 1D-normalised Gaussians). preskin uses the published
// variances unscaled: they were fitted for G(v, r) above, and the 1D normalisation appears by
// itself where it belongs (lineProfile below). A JSON profile with scaled variances reproduces
// the other convention if wanted.
//
// Limits: profiles are isotropic and radially symmetric, per channel; no wavelength dependence
// beyond RGB; no layered or anisotropic media.
#pragma once

#include <preskin/Export.h>

#include <preskin/Glm.h>

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace preskin {

// One term of a sum of Gaussians: R_i(r) = weight * exp(-r^2 / 2 varianceMm2) / (2 pi varianceMm2).
struct GaussianTerm {
    double varianceMm2 = 0.0;
    glm::dvec3 weight{0.0};
};

class PRESKIN_API DiffusionProfile {
public:
    enum class Kind { SumOfGaussians, NormalizedDiffusion };

    // d'Eon & Luebke's six-Gaussian skin profile (variances in mm^2, RGB weights; albedo 1).
    static DiffusionProfile deonLuebke();
    // Any sum of Gaussians; validates (throws preskin::Error naming `source` and the field).
    static DiffusionProfile sumOfGaussians(std::vector<GaussianTerm> terms, std::string name = "sum of Gaussians",
                                           std::string_view source = "sumOfGaussians");
    // Christensen-Burley normalized diffusion from per-channel surface albedo in (0, 1] and
    // mean free path in mm (> 0). Validates.
    static DiffusionProfile burley(glm::dvec3 albedo, glm::dvec3 meanFreePathMm,
                                   std::string name = "Christensen & Burley 2015 normalized diffusion");
    // Reads a profile from JSON (format: see toJson). Throws preskin::Error of the form
    // "<path>: gaussians[2].varianceMm2: must be > 0, got -1".
    static DiffusionProfile fromJsonFile(const std::filesystem::path& path);
    // Same, from text; `sourceName` prefixes every error message.
    static DiffusionProfile fromJsonText(std::string_view text, std::string_view sourceName);

    // JSON text that fromJsonText reads back to an identical profile:
    //   {"type": "sumOfGaussians", "name": ..., "gaussians": [{"varianceMm2": v, "weights": [r, g, b]}, ...]}
    //   {"type": "normalizedDiffusion", "name": ..., "albedo": [r, g, b], "meanFreePathMm": [r, g, b]}
    std::string toJson() const;

    Kind kind() const { return kind_; }
    const std::string& name() const { return name_; }
    const std::vector<GaussianTerm>& gaussians() const { return gaussians_; }  // empty unless SumOfGaussians
    glm::dvec3 meanFreePathMm() const { return meanFreePathMm_; }              // NormalizedDiffusion only
    glm::dvec3 scatteringDistanceMm() const { return distanceMm_; }            // Burley's d; NormalizedDiffusion only

    // Radial profile R(r), 1/mm^2, per channel. For normalized diffusion R(0) is infinite.
    glm::dvec3 R(double rMm) const;
    // Integral of 2 pi r R(r) over [0, inf), per channel.
    glm::dvec3 albedo() const { return albedo_; }
    // The profile integrated along a straight line at distance u from the centre,
    // P(u) = int R(sqrt(u^2 + y^2)) dy over the whole line, 1/mm. It is what a straight shadow
    // edge, or a cylinder lit across its axis, sees; it integrates over u to the albedo.
    // Gaussians: sum_i w_i exp(-u^2 / 2 v_i) / sqrt(2 pi v_i). Burley: A (K0(u/d) + K0(u/3d)) / (4 pi d),
    // infinite at u = 0.
    glm::dvec3 lineProfile(double uMm) const;
    // Response to a straight edge between dark (x < 0) and uniformly lit (x > 0) half-planes, at
    // signed distance x from the edge, divided by the albedo: int P(t) dt over (-inf, x] / albedo.
    // 0 at -inf, 1/2 at 0, 1 at +inf.
    glm::dvec3 edgeResponse(double xMm) const;
    // Transmittance through a slab of thickness d lit uniformly from behind, divided by the
    // albedo: int 2 pi r R(sqrt(r^2 + d^2)) dr over [0, inf) / albedo = fraction of the profile's
    // energy beyond radius d. T(0) = 1. Gaussians: sum_i w_i exp(-d^2 / 2 v_i) / albedo;
    // Burley: (exp(-d/D) + 3 exp(-d/3D)) / 4 with D = scatteringDistanceMm.
    glm::dvec3 transmittance(double thicknessMm) const;
    // The smallest radius beyond which at most `tailFraction` (in (0, 1)) of every channel's energy
    // lies: the d where the largest channel's transmittance(d) falls to tailFraction (bisection
    // to 1e-9 relative). Integrals of the profile over a surface can stop at this radius.
    double reachMm(double tailFraction) const;

    // Per-channel scattering width: the RMS radius sqrt(int r^2 2 pi r R dr / albedo), mm.
    // Gaussians: sqrt(2 sum_i w_i v_i / albedo); Burley: sqrt(14) d.
    glm::dvec3 widthMm() const { return widthMm_; }
    // The widest channel's width; penumbra widths are measured relative to it.
    double maxWidthMm() const;
    // The shortest length over which R changes noticeably (the smallest Gaussian standard
    // deviation carrying weight, or Burley's smallest d); numerical integration grades to it.
    double narrowestScaleMm() const;

private:
    DiffusionProfile() = default;
    void finish();  // computes albedo, widths and evaluation constants

    Kind kind_ = Kind::SumOfGaussians;
    std::string name_;
    std::vector<GaussianTerm> gaussians_;
    glm::dvec3 meanFreePathMm_{0.0};
    glm::dvec3 distanceMm_{0.0};
    glm::dvec3 albedo_{0.0};
    glm::dvec3 widthMm_{0.0};
    // Gaussians: per term 1 / (2 v), 1 / (2 pi v), 1 / sqrt(2 pi v), 1 / sqrt(2 v).
    struct TermConstants {
        double halfInvVariance;
        double radialNorm;
        double lineNorm;
        double invSigmaSqrt2;
    };
    std::vector<TermConstants> constants_;
};

}  // namespace preskin
