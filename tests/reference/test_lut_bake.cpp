// Bake benchmark and determinism: the default d'Eon set at default sizes (the goal is <= 1 s on
// 2 cores in a Release build; the assertion only catches gross regressions), and parallel
// bakes give bit-identical tables.
#include <preskin/LutSet.h>

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

namespace preskin::test {
namespace {

TEST(LutBake, DefaultSetBakeTime) {
    const DiffusionProfile profile = DiffusionProfile::deonLuebke();
    double bestMs = 1e30;
    for (int run = 0; run < 2; ++run) {
        const auto start = std::chrono::steady_clock::now();
        const LutSet luts = LutSet::bake(profile);
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        bestMs = std::min(bestMs, ms);
        ASSERT_EQ(luts.diffuse().width(), 256);
    }
    std::printf("default LUT set bake: %.1f ms (best of 2, %u hardware threads)\n", bestMs,
                std::thread::hardware_concurrency());
    RecordProperty("defaultBakeMs", std::to_string(bestMs));
    EXPECT_LT(bestMs, 10000.0);
}

TEST(LutBake, ParallelBakesAreDeterministic) {
    const DiffusionProfile profile = DiffusionProfile::burley({0.8, 0.5, 0.3}, {2.0, 0.9, 0.4});
    const LutSet a = LutSet::bake(profile, LutBakeSettings::withSize(32));
    const LutSet b = LutSet::bake(profile, LutBakeSettings::withSize(32));
    EXPECT_EQ(a.diffuse().rgb, b.diffuse().rgb);
    EXPECT_EQ(a.penumbra().rgb, b.penumbra().rgb);
    EXPECT_EQ(a.shTransfer().rgb, b.shTransfer().rgb);
    EXPECT_EQ(a.transmittance().rgb, b.transmittance().rgb);
    EXPECT_EQ(a.diffuse().contentHash(), b.diffuse().contentHash());
}

}  // namespace
}  // namespace preskin::test
