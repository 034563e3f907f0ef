// Golden-image frame checks: the frames of tests/golden/cases.txt, rendered headless, must
// match the blessed PNGs within the stated tolerance (per channel 8/255, 1-pixel shift
// forgiven, at most 0.5% of pixels failing). A failure writes the actual frame and a diff
// image into the process's scratch directory, which a failed run keeps
// (tests/common/scratch.h). Re-bless with scripts/bless-goldens.sh. The assets are baked
// once per ctest run (bake_test_assets.golden_<name>). One test per case
// (Cases/GoldenFrame.MatchesBlessedImage/<name>), so ctest -j spreads them over its jobs.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/common/fixtures.h"

namespace {

using namespace stipple::test;

struct GoldenCase {
    std::string name, input, bake, play;
};
// Named by gtest (and so by ctest) as the case's name, not as its bytes.
void PrintTo(const GoldenCase& c, std::ostream* os) {
    *os << c.name;
}

std::string trim(const std::string& s) {
    size_t a = s.find_first_not_of(" \t"), b = s.find_last_not_of(" \t");
    return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

// The cases of tests/golden/cases.txt (name | input | bake options | play options).
std::vector<GoldenCase> read_cases() {
    std::ifstream cases(source("tests/golden/cases.txt"));
    std::vector<GoldenCase> out;
    std::string line;
    while (std::getline(cases, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::stringstream fields(line);
        GoldenCase c;
        std::getline(fields, c.name, '|');
        std::getline(fields, c.input, '|');
        std::getline(fields, c.bake, '|');
        std::getline(fields, c.play, '|');
        c.name = trim(c.name);
        c.input = trim(c.input);
        out.push_back(c);
    }
    return out;
}

class GoldenFrame : public ::testing::TestWithParam<GoldenCase> {};

TEST_P(GoldenFrame, MatchesBlessedImage) {
    const GoldenCase& c = GetParam();
    const std::string asset = baked_asset(c.input, c.bake);
    ASSERT_FALSE(asset.empty()) << c.name;
    // Kept after a failure: the actual frame and the diff.
    const std::string out = scratch_path("golden/" + c.name);
    ASSERT_EQ(run("rm -rf " + out + " && mkdir -p " + out), 0);
    ASSERT_EQ(
        run(play_checked() + " " + asset + " --out " + out + " --frames 1 --no-apng " + c.play), 0);
    std::string log;
    const int rc =
        run(bin("stipple-compare") + " " + out + "/frame_0000.png " +
                source("tests/golden/" + c.name + ".png") +
                " --tolerance 8 --shift 1 --max-fraction 0.005 --diff " + out + "/diff.png",
            &log);
    EXPECT_EQ(rc, 0) << c.name << ": " << log << " (actual and diff in " << out << ")";
    if (rc == 0) run("rm -rf " + out);
}

INSTANTIATE_TEST_SUITE_P(Cases, GoldenFrame, ::testing::ValuesIn(read_cases()),
                         [](const ::testing::TestParamInfo<GoldenCase>& param) {
                             return param.param.name;
                         });

// Every blessed image has its case (and the file was read at all).
TEST(GoldenFrames, EveryBlessedImageHasItsCase) {
    const std::vector<GoldenCase> cases = read_cases();
    int blessed = 0;
    for (const auto& entry : std::filesystem::directory_iterator(source("tests/golden"))) {
        if (entry.path().extension() != ".png") continue;
        ++blessed;
        const std::string name = entry.path().stem().string();
        bool found = false;
        for (const GoldenCase& c : cases) found = found || c.name == name;
        EXPECT_TRUE(found) << name << ".png has no line in tests/golden/cases.txt";
    }
    EXPECT_GT(cases.size(), 0u);
    EXPECT_EQ(cases.size(), size_t(blessed));
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
