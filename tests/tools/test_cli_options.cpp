// The tools' option layer (tools/cli_options.h) and JSON output (tools/json_line.h): values
// are parsed whole and range-checked, every bad command line of every tool ends with one
// line naming the option and exit status 1, --help lists every option, JSON stays valid for
// any path, and the bake's stderr is clean when redirected or --quiet.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/common/fixtures.h"
#include "tools/cli_options.h"
#include "tools/image_write.h"
#include "tools/json_line.h"

namespace {

using namespace stipple::test;
namespace cli = stipple::cli;

std::string quoted(const std::string& s) {
    return "'" + s + "'";
}

TEST(CliOptions, IntegersAreParsedWholeAndInRange) {
    long long v = 7;
    EXPECT_TRUE(cli::parse_integer("42", 1, 100, &v));
    EXPECT_EQ(v, 42);
    EXPECT_TRUE(cli::parse_integer("-5", -10, 10, &v));
    EXPECT_EQ(v, -5);
    for (const char* bad :
         {"10x", "", " 5", "5 ", "1.5", "1e3", "x", "101", "0", "99999999999999999999"})
        EXPECT_FALSE(cli::parse_integer(bad, 1, 100, &v)) << bad;
    EXPECT_EQ(v, -5);  // untouched by failures
}

TEST(CliOptions, SeedsRejectSignsAndOverflow) {
    uint64_t v = 0;
    EXPECT_TRUE(cli::parse_unsigned("18446744073709551615", &v));
    EXPECT_EQ(v, UINT64_MAX);
    EXPECT_TRUE(cli::parse_unsigned("0", &v));
    EXPECT_EQ(v, 0u);
    for (const char* bad : {"-1", "+1", "18446744073709551616", "1x", "", " 1"})
        EXPECT_FALSE(cli::parse_unsigned(bad, &v)) << bad;
}

TEST(CliOptions, NumbersAreFiniteWholeAndInRange) {
    double v = 0;
    EXPECT_TRUE(cli::parse_number("0.75", 0, 0.75, &v));
    EXPECT_DOUBLE_EQ(v, 0.75);
    EXPECT_TRUE(cli::parse_number("-3.5e2", -1000, 0, &v));
    EXPECT_DOUBLE_EQ(v, -350);
    for (const char* bad : {"1.01", "nan", "inf", "-inf", "1.5x", "", " 1", "-0.1", "0x1p-2"})
        EXPECT_FALSE(cli::parse_number(bad, 0, 1, &v)) << bad;
}

TEST(CliOptions, SizesAreTwoIntegers) {
    int w = 0, h = 0;
    EXPECT_TRUE(cli::parse_size("640x480", 16, 8192, &w, &h));
    EXPECT_EQ(w, 640);
    EXPECT_EQ(h, 480);
    for (const char* bad : {"640", "640x", "x480", "10x480", "640x480x2", "640.5x480", "640x99999"})
        EXPECT_FALSE(cli::parse_size(bad, 16, 8192, &w, &h)) << bad;
}

TEST(CliOptions, JsonLineKeepsTheToolsLayoutAndEscapes) {
    cli::Json j;
    j["path"] = "a \"b\" \\ c";
    j["passed"] = false;
    j["list"] = {1, 2};
    j["x"] = cli::fixed(2.0 / 3.0, 2);
    j["whole"] = -2.0;
    EXPECT_EQ(cli::json_line(j),
              "{\"path\": \"a \\\"b\\\" \\\\ c\", \"passed\": false, \"list\": [1, 2], \"x\": "
              "0.67, \"whole\": -2}");
    EXPECT_EQ(nlohmann::json::parse(cli::json_line(j))["path"], "a \"b\" \\ c");
}

// ---------------------------------------------------------------------------------------
// Every tool, run as a process

struct BadLine {
    const char* tool;
    const char* args;
    const char* words;  // the error names this (the option, usually)
    int status = 1;
};

TEST(CliOptions, EveryToolRejectsBadValuesWithOneLineAndStatus1) {
    const BadLine cases[] = {
        {"stipple-bake", "x.glb -o y.stip --seed -1", "--seed"},
        {"stipple-bake", "x.glb -o y.stip --points 10x", "--points"},
        {"stipple-bake", "x.glb -o y.stip --points 0", "--points"},
        {"stipple-bake", "x.glb -o y.stip --jitter 0.8", "--jitter"},
        {"stipple-bake", "x.glb -o y.stip --crease 40.5", "--crease"},
        {"stipple-bake", "x.glb -o y.stip --method best", "--method"},
        {"stipple-bake", "x.glb -o y.stip --up x", "--up"},
        {"stipple-bake", "x.glb -o", "-o"},
        {"stipple-bake", "x.glb -o y.stip --quiet=1", "--quiet"},
        {"stipple-play", "a.stip --out d --frames 1.5", "--frames"},
        {"stipple-play", "a.stip --out d --fps 0", "--fps"},
        {"stipple-play", "a.stip --out d --size 640x480x", "--size"},
        {"stipple-play", "a.stip --out d --background 12345g", "--background"},
        {"stipple-play", "a.stip --out d --blend walk:1.5", "--blend"},
        {"stipple-play", "a.stip --out d --refinement-budget -1", "--refinement-budget"},
        {"stipple-play", "a.stip --out d --skinning xyz", "--skinning"},
        {"stipple-play", "a.stip --out d --backend vulkan", "--backend"},
        {"stipple-inspect", "a.stip --prefixes 1000,x", "--prefixes"},
        {"stipple-inspect", "a.stip --bogus", "--bogus"},
        {"stipple-measure", "tone f.png --mask m.png --rows 4:2", "--rows"},
        {"stipple-measure", "tone f.png --mask m.png --rows 1:2x", "--rows"},
        {"stipple-measure", "evenness d.csv --mask m.png --block 0", "--block"},
        {"stipple-measure", "coherence dir --from -1", "--from"},
        {"stipple-measure", "coherence dir --wobble", "coherence: unknown option '--wobble'"},
        {"make-stretch-tube", "x.gltf --segments-around 2", "--segments-around"},
        {"make-stretch-tube", "x.gltf --segments-along=1x", "--segments-along"},
        // stipple-compare keeps its documented usage status 2 (1 means "images differ").
        {"stipple-compare", "a.png b.png --tolerance 3x", "--tolerance", 2},
        {"stipple-compare", "a.png b.png --max-fraction 1.5", "--max-fraction", 2},
        {"stipple-compare", "a.png b.png --shift 5", "--shift", 2},
    };
    for (const BadLine& c : cases) {
        std::string log;
        const int rc = run(bin(c.tool) + " " + c.args, &log);
        SCOPED_TRACE(std::string(c.tool) + " " + c.args + " -> " + log);
        EXPECT_EQ(rc, c.status);
        EXPECT_EQ(log.rfind(std::string(c.tool) + ": ", 0), 0u);
        EXPECT_EQ(log.find('\n'), log.size() - 1);  // exactly one line
        EXPECT_NE(log.find(c.words), std::string::npos);
    }
}

TEST(CliOptions, HelpListsEveryOptionWithItsDefault) {
    // The parser refuses --help (exit 1, "missing from --help") when a registered option is
    // not in the usage text, so exit 0 means every option is listed.
    for (const char* line :
         {"stipple-bake", "stipple-play", "stipple-inspect", "stipple-compare", "make-stretch-tube",
          "stipple-measure tone", "stipple-measure evenness", "stipple-measure coherence",
          "stipple-measure frames"}) {
        std::string log;
        EXPECT_EQ(run(bin(line) + " --help", &log), 0) << line << ": " << log;
        EXPECT_EQ(log.rfind("usage: ", 0), 0u) << line << ": " << log;
    }
    std::string log;
    ASSERT_EQ(run(bin("stipple-bake") + " --help", &log), 0);
    for (const char* shown : {"--points N", "default 20000", "--seed S", "default 1",
                              "default 0.35", "default auto", "default 40", "--quiet"})
        EXPECT_NE(log.find(shown), std::string::npos) << shown;
}

// A scratch directory whose name has a double quote and a backslash in it.
class AwkwardPath : public ::testing::Test {
  protected:
    ScratchDir scratch_;
    std::string dir_ = scratch_.file("we\"ird\\dir");
    void SetUp() override { std::filesystem::create_directories(dir_); }
};

TEST_F(AwkwardPath, BakeAndInspectPrintValidJson) {
    const std::string obj = dir_ + "/tet.obj", asset = dir_ + "/tet \"1\".stip";
    std::ofstream(obj)
        << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    std::string log;
    // (run() captures stdout and stderr; the subshell sends stderr elsewhere.)
    ASSERT_EQ(run("(" + bin("stipple-bake") + " " + quoted(obj) + " -o " + quoted(asset) +
                      " --points 300 2>/dev/null)",
                  &log),
              0)
        << log;
    const nlohmann::json bake = nlohmann::json::parse(log, nullptr, false);
    ASSERT_FALSE(bake.is_discarded()) << log;
    EXPECT_EQ(bake["output"], asset);
    EXPECT_EQ(bake["input"], obj);
    EXPECT_EQ(bake["points"], 300);

    ASSERT_EQ(
        run(bin("stipple-inspect") + " " + quoted(asset) + " --quality --prefixes 100,200", &log),
        0)
        << log;
    const nlohmann::json inspect = nlohmann::json::parse(log, nullptr, false);
    ASSERT_FALSE(inspect.is_discarded()) << log;
    EXPECT_EQ(inspect["asset"], asset);
    EXPECT_EQ(inspect["points"], 300);
    ASSERT_EQ(inspect["quality"].size(), 2u);
    EXPECT_GT(inspect["quality"][0]["nn_mean"].get<double>(), 0.0);
}

TEST_F(AwkwardPath, MeasureAndCompareToolsPrintValidJson) {
    const std::string frame = dir_ + "/frame \"a\".png", mask = dir_ + "/mask.png";
    std::vector<uint8_t> grey(32 * 32 * 4, 128), white(32 * 32 * 4, 255);
    std::string error;
    ASSERT_TRUE(stipple::image::write_png(frame.c_str(), 32, 32, grey.data(), false, &error))
        << error;
    ASSERT_TRUE(stipple::image::write_png(mask.c_str(), 32, 32, white.data(), false, &error))
        << error;
    std::string log;
    ASSERT_EQ(
        run(bin("stipple-measure") + " tone " + quoted(frame) + " --mask " + quoted(mask), &log), 0)
        << log;
    const nlohmann::json tone = nlohmann::json::parse(log, nullptr, false);
    ASSERT_FALSE(tone.is_discarded()) << log;
    EXPECT_EQ(tone["frame"], frame);
    EXPECT_NEAR(tone["tone"].get<double>(), 1 - 128 / 255.0, 0.01);

    EXPECT_EQ(run(bin("stipple-compare") + " " + quoted(frame) + " " + quoted(mask), &log), 1);
    const nlohmann::json verdict = nlohmann::json::parse(log, nullptr, false);
    ASSERT_FALSE(verdict.is_discarded()) << log;
    EXPECT_EQ(verdict["passed"], false);
    EXPECT_EQ(verdict["failing_pixels"], 32 * 32);
}

// ---------------------------------------------------------------------------------------
// stipple-bake's stderr

// The Utah teapot has faces OpenMesh refuses ("PolyMeshT::add_face: complex vertex") when
// the simplify method builds its mesh.
const std::string kTeapot = "assets/UtahTeapot/teapot.obj";

TEST(BakeStderr, QuietIsSilentAndLibraryLinesBecomeOneSummary) {
    ScratchDir scratch;
    const std::string out = scratch.file("t.stip");
    const std::string bake = bin("stipple-bake") + " " + source(kTeapot) + " -o " + out +
                             " --method simplify --points 4000";
    std::string log;
    ASSERT_EQ(run(bake + " --quiet", &log), 0) << log;
    EXPECT_EQ(log, "");
    std::string text;  // stderr only
    ASSERT_EQ(run("(" + bake + " >/dev/null)", &text), 0);
    EXPECT_EQ(text.find("PolyMeshT"), std::string::npos) << text;
    const size_t at = text.find("complex vertex");
    ASSERT_NE(at, std::string::npos) << text;
    EXPECT_EQ(text.find("complex vertex", at + 1), std::string::npos) << text;  // one line
    EXPECT_EQ(text.rfind("warning: ", 0), 0u) << text;
}

TEST(BakeStderr, NoProgressFramesInARedirectedLog) {
    // STIPPLE_PROGRESS_DELAY=0 would show the bar at once on a terminal; a redirected log
    // still gets no '\r' frames.
    ScratchDir scratch;
    std::string log;
    ASSERT_EQ(run("(STIPPLE_PROGRESS_DELAY=0 " + bin("stipple-bake") + " " +
                      source("assets/RiggedSimple/RiggedSimple.glb") + " -o " +
                      scratch.file("c.stip") + " --points 2000 >/dev/null)",
                  &log),
              0)
        << log;
    EXPECT_EQ(log.find('\r'), std::string::npos) << log;
    EXPECT_EQ(log.find("] "), std::string::npos) << log;
}

TEST(BakeStderr, ProgressFramesOnATerminal) {
    // The same bake with stderr on a pseudo-terminal (util-linux `script`, in every Debian
    // install) does show them.
    ASSERT_EQ(run("command -v script >/dev/null"), 0) << "util-linux `script` is missing";
    ScratchDir scratch;
    std::string log;
    ASSERT_EQ(
        run("STIPPLE_PROGRESS_DELAY=0 script -qec " +
                quoted(bin("stipple-bake") + " " + source("assets/RiggedSimple/RiggedSimple.glb") +
                       " -o " + scratch.file("c.stip") + " --points 2000") +
                " /dev/null",
            &log),
        0)
        << log;
    EXPECT_NE(log.find('\r'), std::string::npos) << log;
    EXPECT_NE(log.find("] 100%"), std::string::npos) << log;
}

}  // namespace
