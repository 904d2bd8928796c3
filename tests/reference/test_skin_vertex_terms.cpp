// The skin terms that depend on curvature alone (preskin/skin_vertex.glsl: the SH transfer, the
// shadow lookup's lift, the transmittance the diffuse LUT already holds), found per vertex and
// interpolated (the default) against the same terms found per fragment
// (`--skin-terms-per-fragment`, RenderSettings::skinTermsPerVertex off), on the bundled head as
// `preskin render` draws it with scattered lights (validation layers on), at rest and animated
// (its curvature recomputed on the GPU every frame). Interpolating a smooth function of curvature
// instead of evaluating it at the interpolated curvature changes the image by second-order terms:
// at least 99.9% of the pixels within 5/255 (the golden images' tolerance). The two paths must
// differ somewhere, or the per-vertex path is not in effect.
#include "support/CliTest.h"
#include "support/ImageCompare.h"

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace preskin::test {
namespace {

class SkinVertexTerms : public CliTest {};

TEST_F(SkinVertexTerms, PerVertexTermsMatchPerFragmentTermsOnTheHead) {
    const std::filesystem::path assets = std::filesystem::path(PRESKIN_SOURCE_DIR) / "samples" / "assets" / "head";
    struct Case {
        std::string name;
        std::vector<std::string> args;
    };
    const std::vector<Case> cases = {
        {"rest", {(assets / "head.gltf").string()}},
        {"animated", {(assets / "head_animated.gltf").string(), "--time", "0.7"}},
    };
    for (const Case& c : cases) {
        auto render = [&](const std::string& name, bool perFragment) {
            std::vector<std::string> args = {"render"};
            args.insert(args.end(), c.args.begin(), c.args.end());
            const std::filesystem::path out = dir_ / (c.name + "_" + name + ".png");
            for (const char* a : {"--width", "192", "--height", "192", "--lights", "24", "--validation", "--out"})
                args.emplace_back(a);
            args.push_back(out.string());
            if (perFragment) args.emplace_back("--skin-terms-per-fragment");
            const ProcessResult r = run(args);
            EXPECT_EQ(r.exitCode, 0) << r.out << r.err;
            std::string error;
            RenderedImage image = readPng(out, error);
            EXPECT_TRUE(error.empty()) << error;
            return image;
        };
        const RenderedImage perVertex = render("vertex", false);
        const RenderedImage perFragment = render("fragment", true);
        ASSERT_EQ(perVertex.rgba8.size(), perFragment.rgba8.size());
        ASSERT_FALSE(perVertex.rgba8.empty());
        int worst = 0;
        const size_t beyond = pixelsDifferingBy(perVertex, perFragment, 5, worst);
        const size_t pixels = perVertex.rgba8.size() / 4;
        std::printf(
            "[ skin     ] %s: per-vertex terms against per-fragment: %zu of %zu pixels beyond 5/255, worst %d/255\n",
            c.name.c_str(), beyond, pixels, worst);
        EXPECT_LE(double(beyond), 0.001 * double(pixels)) << c.name;
        EXPECT_GT(worst, 0) << c.name << ": the per-vertex and per-fragment images are identical";
    }
}

}  // namespace
}  // namespace preskin::test
