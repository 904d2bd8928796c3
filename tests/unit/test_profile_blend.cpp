// How far a per-texel blend of two profiles' LUT lookups (what the shader does with a
// profile-weight texture) is from the LUT baked for the blended profile
// R_w = (1 - w) R_A + w R_B. Both profiles are sums of Gaussians with albedo 1 per channel, so
// R_w is one too and bakes exactly: A is d'Eon & Luebke's skin, B the same with every variance
// times `scale` (a profile `sqrt(scale)` times as wide). The tables are ratios (the diffuse ring
// integral is int cos R / int R), so the blend of ratios differs from the ratio of blends
// wherever A and B weigh a ring differently. Every table is compared on its own nodes (the
// texel centres), for w = 0.25, 0.5, 0.75; the largest and RMS differences are printed and held
// to the bounds docs/profiles.md quotes. At w = 0 and 1 the blend is exact.
#include <preskin/LutSet.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace preskin::test {
namespace {

DiffusionProfile widened(const DiffusionProfile& p, double varianceScale) {
    std::vector<GaussianTerm> terms = p.gaussians();
    for (GaussianTerm& t : terms) t.varianceMm2 *= varianceScale;
    return DiffusionProfile::sumOfGaussians(terms);
}

DiffusionProfile blended(const DiffusionProfile& a, const DiffusionProfile& b, double w) {
    std::vector<GaussianTerm> terms;
    for (GaussianTerm t : a.gaussians()) {
        t.weight *= 1.0 - w;
        terms.push_back(t);
    }
    for (GaussianTerm t : b.gaussians()) {
        t.weight *= w;
        terms.push_back(t);
    }
    return DiffusionProfile::sumOfGaussians(terms);
}

struct TableError {
    double max = 0.0;
    double rms = 0.0;
};

TableError compare(const LutTable& a, const LutTable& b, const LutTable& exact, double w) {
    TableError e;
    double sum = 0.0;
    for (size_t i = 0; i < exact.rgb.size(); ++i) {
        const double d = std::abs((1.0 - w) * double(a.rgb[i]) + w * double(b.rgb[i]) - double(exact.rgb[i]));
        e.max = std::max(e.max, d);
        sum += d * d;
    }
    e.rms = std::sqrt(sum / double(exact.rgb.size()));
    return e;
}

TEST(ProfileBlend, LookupBlendAgainstBlendedProfileBake) {
    const LutBakeSettings settings = LutBakeSettings::withSize(64);
    const DiffusionProfile a = DiffusionProfile::deonLuebke();
    // Bounds on the largest difference per table (values are fractions of the lit response).
    struct Case {
        double scale;
        double maxDiffuse, maxPenumbra, maxSh, maxTransmittance;
    };
    const Case cases[] = {{4.0, 0.005, 0.005, 0.01, 0.005}, {16.0, 0.02, 0.01, 0.03, 0.005}};
    for (const Case& c : cases) {
        const DiffusionProfile b = widened(a, c.scale);
        const LutSet la = LutSet::bake(a, settings);
        const LutSet lb = LutSet::bake(b, settings);
        for (double w : {0.0, 0.25, 0.5, 0.75, 1.0}) {
            const LutSet exact = LutSet::bake(blended(a, b, w), settings);
            const TableError diffuse = compare(la.diffuse(), lb.diffuse(), exact.diffuse(), w);
            const TableError sh = compare(la.shTransfer(), lb.shTransfer(), exact.shTransfer(), w);
            // Penumbra and transmittance axes scale with each profile's width, so node i of A, B
            // and the blend are different physical widths / thicknesses: compare through lookups.
            double penumbraMax = 0.0, transmittanceMax = 0.0;
            for (int i = 0; i <= 64; ++i) {
                const float widthMm = float(exact.penumbraReferenceWidthMm() * 4.0 * i / 64.0);
                for (int j = 0; j <= 32; ++j) {
                    const float s = float(j) / 32.0f;
                    const glm::dvec3 blend = (1.0 - w) * glm::dvec3(la.lookupPenumbra(s, widthMm)) +
                                             w * glm::dvec3(lb.lookupPenumbra(s, widthMm));
                    const glm::dvec3 d = glm::abs(blend - glm::dvec3(exact.lookupPenumbra(s, widthMm)));
                    penumbraMax = std::max({penumbraMax, d.r, d.g, d.b});
                }
                const float thicknessMm = float(exact.transmittanceMaxMm() * i / 64.0);
                const glm::dvec3 blend = (1.0 - w) * glm::dvec3(la.lookupTransmittance(thicknessMm)) +
                                         w * glm::dvec3(lb.lookupTransmittance(thicknessMm));
                const glm::dvec3 d = glm::abs(blend - glm::dvec3(exact.lookupTransmittance(thicknessMm)));
                transmittanceMax = std::max({transmittanceMax, d.r, d.g, d.b});
            }
            std::printf("[ blend    ] B = d'Eon x%.0f variance, w = %.2f: diffuse max %.4f rms %.4f; SH max %.4f rms %.4f; "
                        "penumbra max %.4f; transmittance max %.4f\n",
                        c.scale, w, diffuse.max, diffuse.rms, sh.max, sh.rms, penumbraMax, transmittanceMax);
            if (w == 0.0 || w == 1.0) {
                EXPECT_LT(diffuse.max, 1e-3);  // the blend of one profile is that profile (half rounding)
                EXPECT_LT(sh.max, 1e-3);
                continue;
            }
            EXPECT_GT(diffuse.max, 1e-3) << "the blend of lookups should differ from the blended bake";
            EXPECT_LT(diffuse.max, c.maxDiffuse);
            EXPECT_LT(sh.max, c.maxSh);
            EXPECT_LT(penumbraMax, c.maxPenumbra);
            EXPECT_LT(transmittanceMax, c.maxTransmittance);
        }
    }
}

}  // namespace
}  // namespace preskin::test
