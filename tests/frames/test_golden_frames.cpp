// Golden-image frame checks: the frames of tests/golden/cases.txt, rendered headless, must
// match the blessed PNGs within the stated tolerance (per channel 8/255, 1-pixel shift
// forgiven, at most 0.5% of pixels failing). A failure writes the actual frame and a diff
// image next to the test's temporary files. Re-bless with scripts/bless-goldens.sh. The
// assets are baked once per ctest run (bake_test_assets.golden_<name>).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/common/fixtures.h"

namespace {

using namespace stipple::test;

std::string trim(const std::string& s) {
    size_t a = s.find_first_not_of(" \t"), b = s.find_last_not_of(" \t");
    return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

TEST(GoldenFrames, MatchBlessedImages) {
    std::ifstream cases(source("tests/golden/cases.txt"));
    ASSERT_TRUE(cases.good());
    std::string line, work = ::testing::TempDir() + "golden_" + std::to_string(getpid());
    run("rm -rf " + work + " && mkdir -p " +
        work);  // kept after a failure: actual frames and diffs
    int checked = 0;
    while (std::getline(cases, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::stringstream fields(line);
        std::string name, input, bake, play;
        std::getline(fields, name, '|');
        std::getline(fields, input, '|');
        std::getline(fields, bake, '|');
        std::getline(fields, play, '|');
        name = trim(name);
        const std::string asset = baked_asset(trim(input), bake), out = work + "/" + name;
        ASSERT_FALSE(asset.empty()) << name;
        ASSERT_EQ(
            run(play_checked() + " " + asset + " --out " + out + " --frames 1 --no-apng " + play),
            0);
        std::string log;
        int rc =
            run(bin("stipple-compare") + " " + out + "/frame_0000.png " +
                    source(("tests/golden/" + name + ".png").c_str()) +
                    " --tolerance 8 --shift 1 --max-fraction 0.005 --diff " + out + "/diff.png",
                &log);
        EXPECT_EQ(rc, 0) << name << ": " << log << " (actual and diff in " << out << ")";
        ++checked;
    }
    // Every blessed image has its case (and the file was read at all).
    int blessed = 0;
    for (const auto& entry : std::filesystem::directory_iterator(source("tests/golden")))
        blessed += entry.path().extension() == ".png";
    EXPECT_GT(checked, 0);
    EXPECT_EQ(checked, blessed);
}

TEST(GoldenFrames, CompareToolRejectsADifferentFrame) {
    // The comparison is not vacuous: two different goldens do not match each other.
    std::string log;
    int rc = run(bin("stipple-compare") + " " + source("tests/golden/cesium_walk_t066.png") + " " +
                     source("tests/golden/cesium_tone03_zoom2.png"),
                 &log);
    EXPECT_EQ(rc, 1) << log;
    EXPECT_NE(log.find("\"passed\": false"), std::string::npos) << log;
}

}  // namespace
