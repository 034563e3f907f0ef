// stipple-bake end to end: two bakes with the same seed write the same bytes, and every
// hierarchy method spreads its points more evenly than random points (stipple-inspect
// --quality on assets of the fixture step, tests/test_assets.txt).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "tests/common/fixtures.h"

namespace {

using namespace stipple::test;

// Same input, options and seed: byte-identical asset files from two CLI bakes, per method.
TEST(BakeCli, TwoBakesWriteIdenticalBytes) {
    const ScratchDir scratch;
    const std::string dir = scratch.path();
    for (const char* m : {"eliminate", "simplify", "relax", "random"}) {
        std::string bake = bin("stipple-bake") + " " + source("assets/CesiumMan/CesiumMan.glb") +
                           " --points 5000 --seed 7 --quiet --method " + m + " -o " + dir + "/";
        ASSERT_EQ(run(bake + "a.stip"), 0) << m;
        ASSERT_EQ(run(bake + "b.stip"), 0) << m;
        EXPECT_EQ(run("cmp " + dir + "/a.stip " + dir + "/b.stip"), 0) << m;
    }
}

// Spacing quality from stipple-inspect --quality: the coefficient of variation of the
// nearest-neighbour distance is clearly lower than for random points at every level, for
// every method; token relaxation is more even than simplification at the finest level
// (thesis §5.7.3), and sample elimination than both at every level.
TEST(BakeCli, HierarchiesSpreadMoreEvenlyThanRandomPoints) {
    enum { kSimplify, kRandom, kRelax, kEliminate, kMethods };
    std::vector<double> cv[kMethods];
    const char* methods[kMethods] = {"simplify", "random", "relax", "eliminate"};
    for (int m = 0; m < kMethods; ++m) {
        // 20k points: the 16k prefix is a finished level, not the last, cut-short one.
        const std::string asset = baked_asset("assets/CesiumMan/CesiumMan.glb",
                                              std::string("--points 20000 --method ") + methods[m]);
        ASSERT_FALSE(asset.empty());
        std::string log;
        ASSERT_EQ(run(bin("stipple-inspect") + " " + asset + " --quality", &log), 0) << log;
        for (size_t at = log.find("\"nn_cv\": "); at != std::string::npos;
             at = log.find("\"nn_cv\": ", at + 1))
            cv[m].push_back(std::atof(log.c_str() + at + 9));
    }
    for (int m = 0; m < kMethods; ++m) ASSERT_EQ(cv[m].size(), 3u);  // 1k, 4k, 16k
    for (size_t level = 0; level < 3; ++level) {
        std::printf("level %zu: nn CV eliminate %.3f, simplify %.3f, relax %.3f, random %.3f\n",
                    level, cv[kEliminate][level], cv[kSimplify][level], cv[kRelax][level],
                    cv[kRandom][level]);
        for (int m : {kSimplify, kRelax, kEliminate})
            EXPECT_LT(cv[m][level], 0.7 * cv[kRandom][level]);
        EXPECT_LT(cv[kEliminate][level], cv[kSimplify][level]);
        EXPECT_LT(cv[kEliminate][level], 0.15);
    }
    EXPECT_LT(cv[kRelax][2], cv[kSimplify][2]);
}

}  // namespace
