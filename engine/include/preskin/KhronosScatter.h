// A diffusion profile from the scattering parameters that Khronos glTF material extensions carry,
// for assets made for other viewers:
//  - KHR_materials_volume: attenuationDistance d (world metres) and attenuationColor c, the
//    colour white light turns into after d; the extinction coefficient sigma_t = -ln(c) / d;
//  - KHR_materials_volume_scatter (draft) or its successor KHR_materials_scatter (draft):
//    multiscatterColor A, the multiple-scattering albedo (the colour a thick slab of the medium
//    shows), and scatterAnisotropy g, the Henyey-Greenstein phase function's mean cosine;
//    KHR_materials_scatter's scatterFactor scales A.
// Convention (the drafts', and OpenPBR's subsurface): the attenuation is the medium's
// extinction (absorption plus scattering), and A is split into single-scattering albedo alpha by
// the inversion of Chiang, Kutz & Burley, "Practical and Controllable Subsurface Scattering for
// Production Path Tracing" (SIGGRAPH 2016 talk),
//   s = 4.09712 + 4.20863 A - sqrt(9.59217 + 41.6808 A + 17.7126 A^2),  alpha_0 = 1 - s^2,
// which holds for isotropic scattering; with anisotropy the similarity relation
// ((1 - g) sigma_s is the reduced scattering coefficient that diffusion sees) keeps the reduced
// albedo alpha_0, so alpha = (1 - s^2) / (1 - g s^2).
// The profile is Christensen & Burley's normalized diffusion (DiffusionProfile::burley), which
// is written in what diffusion depends on: the surface albedo A and the mean free path, here the
// reduced one, l = 1 / sigma_t' with sigma_t' = sigma_a + (1 - g) sigma_s = sigma_t (1 - g alpha),
// in millimetres. Other viewers differ: some read attenuation as absorption alone (sigma_a =
// -ln(c) / d, sigma_t = sigma_a / (1 - alpha)), which gives longer paths for bright media; and
// an anisotropy that ignores the similarity relation gives the unreduced path (g = 0 here).
// The profile's millimetres are world millimetres (glTF's metres times 1000); the material's
// scatterScale applies on top as for any profile. The surface colour stays the material's base
// colour: A shapes the profile (Burley's searchlight fit of its width), it does not tint it.
#pragma once

#include <preskin/DiffusionProfile.h>
#include <preskin/Export.h>
#include <preskin/Glm.h>

#include <limits>
#include <string>

namespace preskin {

struct KhronosScatter {
    double attenuationDistanceM = std::numeric_limits<double>::infinity();  // KHR_materials_volume
    glm::dvec3 attenuationColor{1.0};                                       // KHR_materials_volume
    glm::dvec3 multiscatterColor{0.0};  // after KHR_materials_scatter's scatterFactor
    double scatterAnisotropy = 0.0;     // (-1, 1)
};

// The single-scattering albedo of multiple-scattering albedo A (each channel in [0, 1]) with
// phase anisotropy g in (-1, 1), by the inversion above.
PRESKIN_API glm::dvec3 singleScatteringAlbedo(const glm::dvec3& multiscatterAlbedo, double anisotropy);

// The mean free path (mm) a profile takes from the parameters: 1000 / (sigma_t (1 - g alpha)).
// Infinite in a channel whose attenuationColor is 1 or whose attenuationDistance is infinite.
PRESKIN_API glm::dvec3 khronosMeanFreePathMm(const KhronosScatter& scatter);

// The normalized-diffusion profile of the parameters, named `name`. Throws preskin::Error naming
// the field when they define none: a channel without extinction (attenuationColor 1, or no
// attenuationDistance), a multiscatterColor channel of 0, values out of range.
PRESKIN_API DiffusionProfile profileFromKhronosScatter(const KhronosScatter& scatter, std::string name);

}  // namespace preskin
