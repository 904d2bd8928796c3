// The skin's per-channel prefiltered normals (<preskin/NormalBasis.h>) against independent
// computations: on a plane every basis normal is the plane's normal; on a sphere it is the vertex
// normal times 1 plus the 1D integral of the Gaussian times (cos psi - 1) over the sphere's near
// hemisphere (Simpson's rule here, in the chord distance 2 a sin(psi / 2));
// the profile weights recover a profile made of the basis Gaussians themselves, narrow terms going
// to the vertex normal, at any scatter scale. The GPU deformation of the basis is tested with the
// deformation (test_deformation.cpp).
#include <preskin/DiffusionProfile.h>
#include <preskin/Error.h>
#include <preskin/NormalBasis.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace preskin::test {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kReachMm = 3.0 * preskin::kNormalBasisSigmaMm.back();

struct TestMesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<uint32_t> indices;
};

// A square grid in the xz plane (metres), normals +y, `cells` cells of `stepM` per side.
TestMesh plane(int cells, float stepM) {
    TestMesh m;
    const float half = 0.5f * float(cells) * stepM;
    for (int j = 0; j <= cells; ++j)
        for (int i = 0; i <= cells; ++i) {
            m.positions.emplace_back(float(i) * stepM - half, 0.0f, float(j) * stepM - half);
            m.normals.emplace_back(0.0f, 1.0f, 0.0f);
        }
    const auto row = uint32_t(cells + 1);
    for (uint32_t j = 0; j < uint32_t(cells); ++j)
        for (uint32_t i = 0; i < uint32_t(cells); ++i) {
            const uint32_t a = j * row + i, b = a + 1, c = a + row, d = c + 1;
            m.indices.insert(m.indices.end(), {a, c, b, b, c, d});
        }
    return m;
}

// UV sphere (metres) with a seam column and pole rings, analytic normals.
TestMesh sphere(float radiusM, int segments, int rings) {
    TestMesh m;
    for (int r = 0; r <= rings; ++r) {
        const double theta = kPi * r / rings;
        for (int s = 0; s <= segments; ++s) {
            const double phi = 2.0 * kPi * (s % segments) / segments;
            const glm::vec3 n(float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)),
                              float(std::sin(theta) * std::sin(phi)));
            m.positions.push_back(radiusM * n);
            m.normals.push_back(n);
        }
    }
    const auto row = uint32_t(segments + 1);
    for (uint32_t r = 0; r < uint32_t(rings); ++r)
        for (uint32_t s = 0; s < uint32_t(segments); ++s) {
            const uint32_t a = r * row + s, b = a + 1, c = a + row, d = c + 1;
            m.indices.insert(m.indices.end(), {a, b, c, b, d, c});
        }
    return m;
}

double gaussian2d(double sigmaMm, double rMm) {
    return std::exp(-rMm * rMm / (2.0 * sigmaMm * sigmaMm)) / (2.0 * kPi * sigmaMm * sigmaMm);
}

// int over psi in [from, from + pi / 2] of f(psi) G(chord) 2 pi a^2 sin psi on a sphere of radius a
// (mm), f a function of the polar angle psi from x: composite Simpson, the chord 2 a sin(psi / 2)
// (the Gaussian cut at the basis's reach), dA = 2 pi a^2 sin psi dpsi.
template <typename Weight>
double sphereQuarterIntegral(double sigmaMm, double radiusMm, double from, Weight f) {
    const int n = 4000;
    const double h = 0.5 * kPi / n;
    double sum = 0.0;
    for (int i = 0; i <= n; ++i) {
        const double psi = from + i * h;
        const double chord = 2.0 * radiusMm * std::sin(0.5 * psi);
        const double value = chord <= kReachMm
            ? f(psi) * gaussian2d(sigmaMm, chord) * 2.0 * kPi * radiusMm * radiusMm * std::sin(psi)
            : 0.0;
        sum += value * (i == 0 || i == n ? 1.0 : (i % 2 ? 4.0 : 2.0));
    }
    return sum * h / 3.0;
}

// 1 + int over the near hemisphere of G(chord) (n_y . n_x - 1) dA.
double sphereIntegral(double sigmaMm, double radiusMm) {
    return 1.0 + sphereQuarterIntegral(sigmaMm, radiusMm, 0.0, [](double psi) { return std::cos(psi) - 1.0; });
}

// The opposing neighbours' integral along n_x on the same sphere: over the far hemisphere,
// int c G(chord) (n_y . n_x) dA with c = min(-10 n_y . n_x, 1) (<preskin/NormalBasis.h>).
double sphereOpposingIntegral(double sigmaMm, double radiusMm) {
    return sphereQuarterIntegral(sigmaMm, radiusMm, 0.5 * kPi,
                                 [](double psi) { return std::min(-10.0 * std::cos(psi), 1.0) * std::cos(psi); });
}

}  // namespace

TEST(NormalBasis, PlaneGivesItsNormal) {
    const TestMesh m = plane(60, 0.001f);  // 60 mm, 1 mm cells
    const std::vector<preskin::NormalBasis> basis =
        preskin::computeNormalBasis(m.positions, m.normals, m.indices, 1000.0);
    ASSERT_EQ(basis.size(), m.positions.size());
    for (size_t v = 0; v < m.positions.size(); ++v)
        for (int b = 0; b < preskin::kNormalBasisCount; ++b)
            EXPECT_LT(glm::length(basis[v].averaged[size_t(b)] - glm::vec3(0.0f, 1.0f, 0.0f)), 1e-5f) << "vertex " << v;
}

TEST(NormalBasis, SphereGivesTheNormalTimesTheHemisphereIntegral) {
    for (float radiusMm : {3.0f, 8.0f}) {
        const TestMesh m = sphere(radiusMm * 1e-3f, 96, 48);
        const std::vector<preskin::NormalBasis> basis =
            preskin::computeNormalBasis(m.positions, m.normals, m.indices, 1000.0);
        for (int b = 0; b < preskin::kNormalBasisCount; ++b) {
            const double expected = sphereIntegral(preskin::kNormalBasisSigmaMm[size_t(b)], radiusMm);
            double worst = 0.0, worstAngle = 0.0;
            for (size_t v = 0; v < m.positions.size(); ++v) {
                if (std::abs(m.normals[v].y) > 0.8f) continue;  // away from the poles' thin triangles
                const glm::dvec3 got(basis[v].averaged[size_t(b)]);
                worst = std::max(worst, std::abs(glm::length(got) - expected));
                worstAngle = std::max(
                    worstAngle, std::acos(std::min(1.0, glm::dot(glm::normalize(got), glm::dvec3(m.normals[v])))));
            }
            // (2.5 %: the cut at 90 degrees is taken sample by sample on the 96 x 48 mesh.)
            EXPECT_LT(worst, 0.025 * expected + 1e-3)
                << "radius " << radiusMm << " mm, basis " << b << ", expected " << expected;
            EXPECT_LT(worstAngle, 0.02) << "radius " << radiusMm << " mm, basis " << b;
        }
    }
}

// The far hemisphere within reach: the opposing integral lies along -n_x with the length of the
// 1D integral, and the centroid lies behind the vertex, inside the sphere.
TEST(NormalBasis, SpheresFarSideIsItsOpposingNeighbourhood) {
    const float radiusMm = 3.0f;
    const TestMesh m = sphere(radiusMm * 1e-3f, 96, 48);
    const std::vector<preskin::NormalBasis> basis =
        preskin::computeNormalBasis(m.positions, m.normals, m.indices, 1000.0);
    for (int b = 0; b < preskin::kNormalBasisCount; ++b) {
        const double expected = sphereOpposingIntegral(preskin::kNormalBasisSigmaMm[size_t(b)], radiusMm);
        double worstAlong = 0.0, worst = 0.0;
        for (size_t v = 0; v < m.positions.size(); ++v) {
            if (std::abs(m.normals[v].y) > 0.8f) continue;
            const glm::dvec3 got(basis[v].opposing[size_t(b)]);
            worstAlong = std::max(worstAlong, std::abs(glm::dot(got, glm::dvec3(m.normals[v])) - expected));
            worst = std::max(worst, glm::length(got - expected * glm::dvec3(m.normals[v])));
            if (b == 0) {
                const double depthMm = -1e3 * glm::dot(glm::dvec3(basis[v].opposingCentroid), glm::dvec3(m.normals[v]));
                EXPECT_GT(depthMm, double(radiusMm)) << "vertex " << v;  // past the centre, towards the far side
                EXPECT_LT(depthMm, 2.0 * double(radiusMm)) << "vertex " << v;
            }
        }
        // The tree code samples far nodes at their centroids, a little inside the sphere: 4 %
        // along the normal, and a few degrees across it, on a sphere smaller than the widest basis.
        EXPECT_LT(worstAlong, 0.05 * std::abs(expected) + 1e-4) << "basis " << b << ", expected " << expected;
        EXPECT_LT(worst, 0.12 * std::abs(expected) + 1e-4) << "basis " << b << ", expected " << expected;
    }
}

// Two parallel plates facing each other d apart: at the middle of one, the other is its opposing
// neighbourhood, O_b = n_other exp(-d^2 / (2 sigma_b^2)) (the basis Gaussian's plane integral, less
// its part beyond the reach),
// its centroid straight across; the averaged normals are the plate's own.
TEST(NormalBasis, FacingPlatesSeeEachOtherAcrossTheGap) {
    const float gapMm = 1.5f;
    TestMesh m = plane(60, 0.001f);  // 60 mm, normals +y
    const TestMesh upper = plane(60, 0.001f);
    const auto base = uint32_t(m.positions.size());
    for (size_t i = 0; i < upper.positions.size(); ++i) {
        m.positions.push_back(upper.positions[i] + glm::vec3(0.0f, gapMm * 1e-3f, 0.0f));
        m.normals.emplace_back(0.0f, -1.0f, 0.0f);
    }
    for (size_t t = 0; t < upper.indices.size(); t += 3)  // wound the other way: it faces down
        m.indices.insert(m.indices.end(),
                         {base + upper.indices[t], base + upper.indices[t + 2], base + upper.indices[t + 1]});
    const std::vector<preskin::NormalBasis> basis =
        preskin::computeNormalBasis(m.positions, m.normals, m.indices, 1000.0);
    const size_t middle = 30 * 61 + 30;
    for (size_t v : {middle, base + middle}) {
        const float side = v == middle ? 1.0f : -1.0f;
        for (int b = 0; b < preskin::kNormalBasisCount; ++b) {
            const double sigma = preskin::kNormalBasisSigmaMm[size_t(b)];
            // The plane integral of the Gaussian cut at its reach R = 3 sigma (<preskin/NormalBasis.h>'s
            // tree code): exp(-d^2 / (2 sigma^2)) - exp(-R^2 / (2 sigma^2)).
            const double expected = std::exp(-double(gapMm) * double(gapMm) / (2.0 * sigma * sigma)) - std::exp(-4.5);
            const glm::vec3 o = basis[v].opposing[size_t(b)];
            EXPECT_NEAR(double(o.y), -double(side) * expected, 0.01 * expected + 1e-4) << "basis " << b;
            EXPECT_NEAR(double(glm::length(glm::vec2(o.x, o.z))), 0.0, 1e-4) << "basis " << b;
            EXPECT_LT(glm::length(basis[v].averaged[size_t(b)] - glm::vec3(0.0f, side, 0.0f)), 1e-5f);
        }
        EXPECT_LT(glm::length(basis[v].opposingCentroid - glm::vec3(0.0f, side * gapMm * 1e-3f, 0.0f)), 1e-5f);
    }
    // A plate alone has none.
    const TestMesh single = plane(60, 0.001f);
    for (const preskin::NormalBasis& n :
         preskin::computeNormalBasis(single.positions, single.normals, single.indices, 1000.0))
        for (const glm::vec3& o : n.opposing) EXPECT_EQ(o, glm::vec3(0.0f));
}

TEST(NormalBasis, DenseMeshesMatchCoarseOnes) {
    // A 5 mm sphere of 32768 triangles (0.12 mm edges) lies wholly within every vertex's reach:
    // the tree code gives the values of a coarse one.
    const TestMesh dense = sphere(0.005f, 128, 64), coarse = sphere(0.005f, 48, 24);
    const std::vector<preskin::NormalBasis> d =
        preskin::computeNormalBasis(dense.positions, dense.normals, dense.indices, 1000.0);
    const std::vector<preskin::NormalBasis> c =
        preskin::computeNormalBasis(coarse.positions, coarse.normals, coarse.indices, 1000.0);
    for (int b = 0; b < preskin::kNormalBasisCount; ++b) {
        const double expected = sphereIntegral(preskin::kNormalBasisSigmaMm[size_t(b)], 5.0);
        for (const auto* basis : {&d, &c})
            for (size_t v = 0; v < basis->size(); v += 7) {
                const glm::vec3 n = basis == &d ? dense.normals[v] : coarse.normals[v];
                if (std::abs(n.y) > 0.8f) continue;
                EXPECT_NEAR(glm::length((*basis)[v].averaged[size_t(b)]), expected, 0.02 * expected + 1e-3)
                    << "basis " << b;
            }
    }
}

TEST(NormalBasis, WeightsRecoverAProfileMadeOfTheBasisAtAnyScatterScale) {
    // Red: the four basis Gaussians and a narrow term (0.05 mm) that belongs to the vertex normal.
    const std::array<double, 4> red = {0.1, 0.2, 0.3, 0.15};
    const double narrow = 0.25;
    for (double scale : {1.0, 2.5}) {
        std::vector<preskin::GaussianTerm> terms;
        for (int b = 0; b < preskin::kNormalBasisCount; ++b) {
            const double s = preskin::kNormalBasisSigmaMm[size_t(b)] * scale;  // profile mm
            terms.push_back({s * s, glm::dvec3(red[size_t(b)], b == 0 ? 0.5 : 0.0, 0.0)});
        }
        terms.push_back({0.05 * 0.05, glm::dvec3(narrow, 0.5, 1.0)});
        const auto profile = preskin::DiffusionProfile::sumOfGaussians(terms);
        const std::array<glm::vec4, 3> w = preskin::normalBasisWeights(profile, scale);
        for (int b = 0; b < preskin::kNormalBasisCount; ++b)
            EXPECT_NEAR(w[0][b], red[size_t(b)], 2e-3) << "scale " << scale << " red basis " << b;
        EXPECT_NEAR(w[1][0], 0.5, 2e-3) << "green: half the 0.5 mm basis";
        EXPECT_NEAR(w[1][1] + w[1][2] + w[1][3], 0.0, 2e-3);
        EXPECT_NEAR(w[2][0] + w[2][1] + w[2][2] + w[2][3], 0.0, 3e-3) << "blue: the narrow term alone";
    }
}

TEST(NormalBasis, WeightsOfMeasuredProfilesArePositiveAndRedIsWidest) {
    for (const auto& profile :
         {preskin::DiffusionProfile::deonLuebke(),
          preskin::DiffusionProfile::burley(glm::dvec3(0.8, 0.5, 0.4), glm::dvec3(1.0, 0.5, 0.3))}) {
        const std::array<glm::vec4, 3> w = preskin::normalBasisWeights(profile, 1.0);
        double previousVariance = 1e30;
        for (int c = 0; c < 3; ++c) {
            double sum = 0.0, variance = 0.0;
            for (int b = 0; b < preskin::kNormalBasisCount; ++b) {
                const double a = w[size_t(c)][b];
                EXPECT_GE(a, 0.0) << profile.name();
                sum += a;
                variance += a * 2.0 * preskin::kNormalBasisSigmaMm[size_t(b)] * preskin::kNormalBasisSigmaMm[size_t(b)];
            }
            EXPECT_LE(sum, 1.0 + 1e-6) << profile.name();
            // The basis holds the profile's second moment where the profile is resolved.
            const double profileVariance = profile.widthMm()[c] * profile.widthMm()[c];
            if (profileVariance > 0.5) {
                EXPECT_NEAR(variance, profileVariance, 0.1 * profileVariance) << profile.name() << " channel " << c;
            }
            EXPECT_LE(variance, previousVariance * 1.001) << profile.name() << ": red widest, blue narrowest";
            previousVariance = variance;
        }
    }
}

TEST(NormalBasis, BadInputIsRefused) {
    const TestMesh m = plane(2, 0.001f);
    const std::vector<glm::vec3> fewer(m.normals.begin(), m.normals.end() - 1);
    EXPECT_THROW(preskin::computeNormalBasis(m.positions, fewer, m.indices, 1000.0), preskin::Error);
    std::vector<uint32_t> bad = m.indices;
    bad[4] = 99;
    EXPECT_THROW(preskin::computeNormalBasis(m.positions, m.normals, bad, 1000.0), preskin::Error);
    for (double scale : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()})
        EXPECT_THROW(preskin::computeNormalBasis(m.positions, m.normals, m.indices, scale), preskin::Error);
}

}  // namespace preskin::test
