// Tests of DiffusionProfile's JSON files (format: DiffusionProfile::toJson): the good files in
// tests/data/profiles load, profiles round-trip, and every bad file is refused with a one-line
// preskin::Error naming the file and the field.
#include <preskin/DiffusionProfile.h>
#include <preskin/Error.h>

#include <gtest/gtest.h>

#include <string>

namespace preskin::test {
namespace {

std::string dataFile(const std::string& name) { return std::string(PRESKIN_SOURCE_DIR "/tests/data/profiles/") + name; }

TEST(ProfileJson, GoodGaussianFileLoads) {
    const DiffusionProfile p = DiffusionProfile::fromJsonFile(dataFile("good_three_gaussians.json"));
    EXPECT_EQ(p.kind(), DiffusionProfile::Kind::SumOfGaussians);
    EXPECT_EQ(p.name(), "three-term test profile");
    ASSERT_EQ(p.gaussians().size(), 3u);
    EXPECT_EQ(p.gaussians()[2].varianceMm2, 4.0);
    EXPECT_NEAR(p.albedo().r, 0.9, 1e-15);
    EXPECT_NEAR(p.albedo().g, 0.9, 1e-15);
    EXPECT_NEAR(p.albedo().b, 0.9, 1e-15);
}

TEST(ProfileJson, GoodBurleyFileLoads) {
    const DiffusionProfile p = DiffusionProfile::fromJsonFile(dataFile("good_burley.json"));
    EXPECT_EQ(p.kind(), DiffusionProfile::Kind::NormalizedDiffusion);
    EXPECT_EQ(p.albedo(), glm::dvec3(0.8, 0.5, 0.3));
    EXPECT_EQ(p.meanFreePathMm(), glm::dvec3(2.0, 0.9, 0.4));
}

TEST(ProfileJson, RoundTrips) {
    for (const DiffusionProfile& p :
         {DiffusionProfile::deonLuebke(), DiffusionProfile::burley({0.7, 0.4, 0.2}, {3.0, 1.0, 0.3})}) {
        const DiffusionProfile back = DiffusionProfile::fromJsonText(p.toJson(), "round trip");
        EXPECT_EQ(back.name(), p.name());
        EXPECT_EQ(back.kind(), p.kind());
        EXPECT_EQ(back.toJson(), p.toJson());
        for (double r : {0.01, 0.3, 2.0}) EXPECT_EQ(back.R(r), p.R(r));
    }
}

struct BadFile {
    const char* name;
    const char* expected;  // the message after "<path>: "
};

class ProfileJsonBad : public ::testing::TestWithParam<BadFile> {};

TEST_P(ProfileJsonBad, IsRefusedWithFileAndField) {
    const BadFile bad = GetParam();
    const std::string path = dataFile(bad.name);
    try {
        DiffusionProfile::fromJsonFile(path);
        FAIL() << bad.name << " was accepted";
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;  // starts with the file
        EXPECT_NE(message.find(bad.expected), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;  // one line
    }
}

INSTANTIATE_TEST_SUITE_P(
    Files, ProfileJsonBad,
    ::testing::Values(BadFile{"bad_negative_weight.json", "gaussians[1].weights[0]: must be >= 0, got -0.1"},
                      BadFile{"bad_nan_variance.json", "JSON: parse error at line 4"},
                      BadFile{"bad_infinite_variance.json", "JSON: number overflow parsing '1e999'"},
                      BadFile{"bad_negative_variance.json",
                              "gaussians[2].varianceMm2: must be >= 1e-06 mm^2 (a Gaussian 1 um wide), got -1"},
                      BadFile{"bad_zero_albedo.json", "gaussians[*].weights[2]: channel B has zero albedo"},
                      BadFile{
                          "bad_albedo_above_one.json",
                          "gaussians[*].weights[0]: channel R has albedo 1.3 > 1 (the weights must sum to at most 1)"},
                      BadFile{"bad_missing_variance.json", "gaussians[0].varianceMm2: missing"},
                      BadFile{"bad_missing_type.json", "type: missing"},
                      BadFile{"bad_unknown_field.json", "gaussians[0].variance: unknown field"},
                      BadFile{"bad_weights_not_rgb.json", "gaussians[0].weights: must be an array of three numbers"},
                      BadFile{"bad_empty_gaussians.json", "gaussians: must hold at least one term"},
                      BadFile{"bad_burley_zero_albedo.json", "albedo[1]: must be in (0, 1], got 0"},
                      BadFile{"bad_burley_missing_mfp.json", "meanFreePathMm: missing"},
                      BadFile{"bad_truncated.json", "JSON: parse error at line 5"},
                      BadFile{"does_not_exist.json", "file: not found"}),
    [](const ::testing::TestParamInfo<BadFile>& param) {
        std::string name = param.param.name;
        name = name.substr(0, name.find('.'));
        for (char& ch : name)
            if (ch == '-') ch = '_';
        return name;
    });

TEST(ProfileJson, NonObjectAndWrongTypesAreRefused) {
    EXPECT_THROW(DiffusionProfile::fromJsonText("[1, 2]", "x.json"), Error);
    EXPECT_THROW(DiffusionProfile::fromJsonText(R"({"type": 3})", "x.json"), Error);
    EXPECT_THROW(DiffusionProfile::fromJsonText(R"({"type": "dipole"})", "x.json"), Error);
    EXPECT_THROW(
        DiffusionProfile::fromJsonText(
            R"({"type": "sumOfGaussians", "gaussians": [{"varianceMm2": "1", "weights": [1, 1, 1]}]})", "x.json"),
        Error);
    try {
        DiffusionProfile::fromJsonText(
            R"({"type": "normalizedDiffusion", "albedo": [0.5, 0.5, 0.5], "meanFreePathMm": [1, 1, 5000]})", "p.json");
        FAIL();
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "p.json: meanFreePathMm[2]: must be <= 1000 mm, got 5000");
    }
}

}  // namespace
}  // namespace preskin::test
