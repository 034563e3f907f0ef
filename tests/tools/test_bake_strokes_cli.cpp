// stipple-bake's paintstroke options (--fur, --fur-length, --fur-radius, --fur-comb,
// --fur-curl, --strokes): bad values end with one line naming the option; the sketch's torus
// and water bake, stipple-inspect lists their STRK section, and the summary counts them.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/common/fixtures.h"

namespace {

using namespace stipple::test;

std::string bake_cmd(const ScratchDir& dir, const std::string& options) {
    return bin("stipple-bake") + " " + source("assets/torus.obj") + " -o " + dir.file("t.stip") +
           " --points 2000 " + options;
}

void expect_one_line_error(int rc, const std::string& log, const std::string& words) {
    EXPECT_EQ(rc, 1) << log;
    EXPECT_EQ(log.rfind("stipple-bake: ", 0), 0u) << log;
    EXPECT_EQ(log.find('\n'), log.size() - 1) << log;
    EXPECT_NE(log.find(words), std::string::npos) << log;
}

TEST(BakeStrokesCli, BadFurValuesAreOneLineErrors) {
    ScratchDir dir;
    const std::pair<const char*, const char*> cases[] = {
        {"--fur -1", "--fur"},
        {"--fur abc", "--fur"},
        {"--fur 4194305", "--fur"},
        {"--fur 10 --fur-length 0", "--fur-length must be a number in (0, 250000]"},
        {"--fur 10 --fur-length -1", "--fur-length"},
        {"--fur 10 --fur-length nan", "--fur-length"},
        {"--fur 10 --fur-length 1e9", "--fur-length"},
        {"--fur 10 --fur-radius 0", "--fur-radius"},
        {"--fur 10 --fur-radius inf", "--fur-radius"},
        {"--fur 10 --fur-comb 1,2", "--fur-comb"},
        {"--fur 10 --fur-comb 1,2,3,4", "--fur-comb"},
        {"--fur 10 --fur-comb a,b,c", "--fur-comb"},
        {"--fur 10 --fur-comb 1,,3", "--fur-comb"},
        {"--fur 10 --fur-curl x", "--fur-curl"},
        {"--fur-length 0.1", "need --fur N"},
        {"--fur 0 --fur-curl 1", "need --fur N"},
    };
    for (const auto& c : cases) {
        std::string log;
        const int rc = run(bake_cmd(dir, c.first), &log);
        expect_one_line_error(rc, log, c.second);
        EXPECT_FALSE(std::ifstream(dir.file("t.stip")).good()) << c.first;
    }
}

TEST(BakeStrokesCli, BadStrokeFilesAreOneLineErrors) {
    ScratchDir dir;
    std::string log;
    int rc = run(bake_cmd(dir, "--strokes " + dir.file("missing.json")), &log);
    expect_one_line_error(rc, log, "missing.json: cannot open");
    std::ofstream(dir.file("bad.json")) << R"({"strokes": [{"points": [[0,0,0,1],[0,0,0,-1]]}]})";
    rc = run(bake_cmd(dir, "--strokes " + dir.file("bad.json")), &log);
    expect_one_line_error(rc, log, "strokes[0].points[1]: radius");
    std::ofstream(dir.file("joint.json"))
        << R"({"strokes": [{"anchor": "joint", "joint": "hip", "points": [[0,0,0,1],[0,1,0,1]]}]})";
    rc = run(bake_cmd(dir, "--strokes " + dir.file("joint.json")), &log);
    expect_one_line_error(rc, log, "the scene has no skin");
    EXPECT_FALSE(std::ifstream(dir.file("t.stip")).good());
}

nlohmann::json last_json_line(const std::string& log) {
    const size_t start = log.rfind('{');
    return nlohmann::json::parse(log.substr(start), nullptr, false);
}

TEST(BakeStrokesCli, SketchTorusAndWaterBakeAndInspect) {
    ScratchDir dir;
    std::string log;
    // The sketch's torus: 1,250 strokes.
    ASSERT_EQ(run(bake_cmd(dir, "--fur 1250 --fur-curl 2 --fur-comb 0,-1,0.5"), &log), 0) << log;
    nlohmann::json summary = last_json_line(log);
    EXPECT_EQ(summary.value("strokes", 0), 1250) << log;
    EXPECT_EQ(summary.value("stroke_points", 0), 1250 * 5) << log;
    EXPECT_GT(summary.value("stroke_bytes", 0), 1250 * 32 + 6250 * 28) << log;
    ASSERT_EQ(run(bin("stipple-inspect") + " " + dir.file("t.stip"), &log), 0) << log;
    nlohmann::json inspect = nlohmann::json::parse(log, nullptr, false);
    EXPECT_EQ(inspect["strokes"]["strokes"], 1250) << log;
    EXPECT_EQ(inspect["strokes"]["rooted"], 1250) << log;
    EXPECT_GT(inspect["sections"]["STRK"].get<int>(), 0) << log;
    // Fur and the water's four strokes together.
    ASSERT_EQ(
        run(bake_cmd(dir, "--fur 100 --strokes " + source("assets/strokes/water.json")), &log), 0)
        << log;
    EXPECT_EQ(last_json_line(log).value("strokes", 0), 104) << log;
    ASSERT_EQ(run(bin("stipple-inspect") + " " + dir.file("t.stip"), &log), 0) << log;
    inspect = nlohmann::json::parse(log, nullptr, false);
    EXPECT_EQ(inspect["strokes"]["object"], 4) << log;
    EXPECT_EQ(inspect["strokes"]["surface"], 100) << log;
    // No strokes: no STRK section and no stroke keys in the summary.
    ASSERT_EQ(run(bake_cmd(dir, ""), &log), 0) << log;
    EXPECT_FALSE(last_json_line(log).contains("strokes")) << log;
}

TEST(BakeStrokesCli, HelpNamesTheStrokeOptions) {
    std::string log;
    EXPECT_EQ(run(bin("stipple-bake") + " --help", &log), 0);
    for (const char* option :
         {"--fur N", "--fur-length", "--fur-radius", "--fur-comb", "--fur-curl", "--strokes"})
        EXPECT_NE(log.find(option), std::string::npos) << option;
    EXPECT_NE(log.find("3% of the"), std::string::npos);
}

}  // namespace
