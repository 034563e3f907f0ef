// The stipple-measure CLI: valid JSON for every command (paths escaped), inner contours as
// outlines for pops, stipple-play --mask-out against the paper frame, one-line errors.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/common/fixtures.h"
#include "tools/frame_measure.h"
#include "tools/image_write.h"

namespace {

namespace m = stipple::measure;
using stipple::test::bin;
using stipple::test::run;

void write_text(const std::string& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

// A directory of two 64x48 frames with masks and dots; the directory name holds a quote and
// a backslash, which the JSON output must escape.
std::string make_frames_dir(const std::string& test) {
    const std::string dir = stipple::test::scratch_path("measure \"q\\ dir " + test);
    run("rm -rf '" + dir + "' && mkdir -p '" + dir + "'");
    const int w = 64, h = 48;
    std::vector<uint8_t> frame(size_t(w) * h * 4, 255), mask(size_t(w) * h * 4, 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            uint8_t* p = &frame[(size_t(y) * w + size_t(x)) * 4];
            uint8_t* q = &mask[(size_t(y) * w + size_t(x)) * 4];
            q[3] = 255;
            if (x >= 16 && x < 48) {
                q[0] = q[1] = q[2] = 255;
                if (x < 32) p[0] = p[1] = p[2] = 0;  // half the object black: tone 0.5
            }
        }
    std::string error;
    for (int f = 0; f < 2; ++f) {
        char name[64];
        std::snprintf(name, sizeof(name), "/frame_%04d.png", f);
        EXPECT_TRUE(
            stipple::image::write_png((dir + name).c_str(), w, h, frame.data(), false, &error));
        std::snprintf(name, sizeof(name), "/mask_%04d.png", f);
        EXPECT_TRUE(
            stipple::image::write_png((dir + name).c_str(), w, h, mask.data(), false, &error));
    }
    write_text(dir + "/dots_0000.csv",
               "id,x,y,size\n1,20.5,10.5,2\n2,30.5,30.5,2\n3,40.5,20.5,2\n");
    write_text(dir + "/dots_0001.csv",
               "id,x,y,size\n1,20.5,10.5,2\n2,30.5,30.5,2\n4,40.5,30.5,2\n");
    return dir;
}

nlohmann::json run_json(const std::string& args, int* rc = nullptr) {
    std::string log;
    const int status = run(bin("stipple-measure") + " " + args, &log);
    if (rc) *rc = status;
    EXPECT_EQ(status, 0) << log;
    nlohmann::json j = nlohmann::json::parse(log, nullptr, false);
    EXPECT_FALSE(j.is_discarded()) << log;
    return j;
}

TEST(MeasureCli, PrintsValidJsonForEveryCommand) {
    const std::string dir = make_frames_dir("json");
    const std::string q = "'" + dir + "'";
    nlohmann::json j = run_json("tone " + q + "/frame_0000.png --mask " + q + "/mask_0000.png");
    EXPECT_NEAR(j["tone"].get<double>(), 0.5, 1e-6);
    EXPECT_EQ(j["mask_pixels"].get<int>(), 32 * 48);
    EXPECT_EQ(j["frame"].get<std::string>(), dir + "/frame_0000.png");
    j = run_json("tone " + q + "/frame_0000.png --mask " + q + "/mask_0000.png --rows 0:24");
    EXPECT_EQ(j["mask_pixels"].get<int>(), 32 * 24);

    j = run_json("evenness " + q + "/dots_0000.csv --mask " + q + "/mask_0000.png --block 8");
    EXPECT_EQ(j["dots"].get<int>(), 3);
    EXPECT_EQ(j["blocks_inside"].get<int>(), 4 * 6);
    EXPECT_EQ(j["empty_blocks"].get<int>(), 4 * 6 - 3);

    j = run_json("coherence " + q);
    EXPECT_EQ(j["pairs"].size(), 1u);
    EXPECT_NEAR(j["pairs"][0]["persistence"].get<double>(), 2.0 / 3.0, 1e-6);
    EXPECT_EQ(j["pairs"][0]["pops"].get<int>(), 2);  // 3 vanished, 4 appeared, both deep inside
    EXPECT_NEAR(j["summary"]["worst_persistence"].get<double>(), 2.0 / 3.0, 1e-6);

    j = run_json("frames " + q);
    EXPECT_EQ(j["frames"].size(), 2u);
    EXPECT_NEAR(j["summary"]["mean_tone"].get<double>(), 0.5, 1e-6);
    EXPECT_EQ(j["frames"][1]["evenness"]["dots"].get<int>(), 3);
    EXPECT_EQ(j["summary"]["coherence"]["pairs"].get<int>(), 1);
    run("rm -rf " + q);
}

// --contours: silhouette lines drawn inside the object (a --tone 0 frame with silhouettes)
// count as outline, so a dot blinking next to an inner contour is no pop.
TEST(MeasureCli, InnerContoursAreOutlinesForPops) {
    const std::string dir = make_frames_dir("contours");
    const std::string lines = dir + "_lines";
    run("rm -rf '" + lines + "' && mkdir -p '" + lines + "'");
    const int w = 64, h = 48;
    std::vector<uint8_t> frame(size_t(w) * h * 4, 255);
    for (int y = 0; y < h; ++y) {  // a contour line at x = 40..41, under dots 3 and 4
        frame[(size_t(y) * w + 40) * 4] = frame[(size_t(y) * w + 40) * 4 + 1] =
            frame[(size_t(y) * w + 40) * 4 + 2] = 0;
        frame[(size_t(y) * w + 41) * 4] = frame[(size_t(y) * w + 41) * 4 + 1] =
            frame[(size_t(y) * w + 41) * 4 + 2] = 0;
    }
    std::string error;
    for (const char* name : {"/frame_0000.png", "/frame_0001.png"})
        ASSERT_TRUE(
            stipple::image::write_png((lines + name).c_str(), w, h, frame.data(), false, &error))
            << error;
    const std::string q = "'" + dir + "'";
    nlohmann::json j = run_json("coherence " + q + " --contours '" + lines + "'");
    EXPECT_NEAR(j["pairs"][0]["persistence"].get<double>(), 2.0 / 3.0, 1e-6);
    EXPECT_EQ(j["pairs"][0]["pops"].get<int>(), 0);
    run("rm -rf " + q + " '" + lines + "'");
}

// stipple-play --mask-out writes the mesh pass's coverage: the same pixels as the legacy paper
// frame (--tone 0 --background 808080), the right way up, and every listed dot lies on it.
TEST(MeasureCli, PlayerMaskOutMatchesThePaperFrame) {
    const stipple::test::ScratchDir scratch;
    const std::string dir = scratch.path();
    const std::string asset =
        stipple::test::baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 5000");
    ASSERT_FALSE(asset.empty());
    const std::string view = " --frames 2 --size 320x240 --yaw -60 --no-silhouettes --no-apng";
    std::string log;
    ASSERT_EQ(run(bin("stipple-play") + " " + asset + " --out " + dir + "/ink" + view +
                      " --tone 0.3 --mask-out --dots-out",
                  &log),
              0)
        << log;
    ASSERT_EQ(run(bin("stipple-play") + " " + asset + " --out " + dir + "/paper" + view +
                      " --tone 0 --background 808080",
                  &log),
              0)
        << log;
    for (const char* n : {"0000", "0001"}) {
        m::Mask mask, paper;
        std::string error;
        ASSERT_TRUE(m::load_mask_png(dir + "/ink/mask_" + n + ".png", &mask, &error)) << error;
        ASSERT_TRUE(m::load_mask_png(dir + "/paper/frame_" + n + ".png", &paper, &error)) << error;
        ASSERT_EQ(mask.width, 320);
        ASSERT_EQ(mask.height, 240);
        EXPECT_GT(m::mask_extent(mask).pixels, 2000u);
        size_t differ = 0;
        for (size_t i = 0; i < mask.inside.size(); ++i) differ += mask.inside[i] != paper.inside[i];
        EXPECT_LE(differ, mask.inside.size() / 1000) << n;
        std::vector<m::Dot> dots;
        ASSERT_TRUE(m::load_dots_csv(dir + "/ink/dots_" + std::string(n) + ".csv", &dots, &error));
        ASSERT_FALSE(dots.empty());
        // Every drawn dot has one of the 2x2 pixels around its centre on the mask (the dots
        // pass's test, runtime/renderer_shaders.h; 0.51: the CSV rounds to 1/100 px), and
        // nearly all have their centre pixel on it (those the measures count).
        size_t near_mask = 0;
        for (const m::Dot& d : dots) {
            bool on = false;
            for (float dy : {-0.51f, 0.51f})
                for (float dx : {-0.51f, 0.51f}) on = on || mask.at(int(d.x + dx), int(d.y + dy));
            near_mask += on;
        }
        EXPECT_EQ(near_mask, dots.size()) << n;
        EXPECT_GE(double(m::evenness(dots, mask).dots), 0.95 * double(dots.size())) << n;
    }
    nlohmann::json j = run_json("frames " + dir + "/ink");
    EXPECT_EQ(j["frames"].size(), 2u);
    EXPECT_NEAR(j["summary"]["mean_tone"].get<double>(), 0.3, 0.1);
}

void expect_error(const std::string& args, const char* words) {
    std::string log;
    const int rc = run(bin("stipple-measure") + " " + args, &log);
    EXPECT_EQ(rc, 1) << log;
    EXPECT_EQ(log.rfind("stipple-measure: ", 0), 0u) << log;
    EXPECT_EQ(log.find('\n'), log.size() - 1) << log;
    EXPECT_NE(log.find(words), std::string::npos) << log;
}

TEST(MeasureCli, BadInputIsAOneLineError) {
    const std::string dir = make_frames_dir("errors");
    const std::string q = "'" + dir + "'";
    expect_error("", "no command");
    expect_error("frobnicate", "unknown command");
    expect_error("tone " + q + "/frame_0000.png", "--mask");
    expect_error("tone " + q + "/missing.png --mask " + q + "/mask_0000.png", "missing.png");
    write_text(dir + "/not_a.png", "not a png");
    expect_error("tone " + q + "/not_a.png --mask " + q + "/mask_0000.png", "not_a.png");
    std::vector<uint8_t> small(16 * 16 * 4, 255);
    std::string error;
    stipple::image::write_png((dir + "/small.png").c_str(), 16, 16, small.data(), false, &error);
    expect_error("tone " + q + "/frame_0000.png --mask " + q + "/small.png", "size mismatch");
    expect_error("evenness " + q + "/dots_0000.csv --mask " + q + "/mask_0000.png --block x",
                 "--block");
    expect_error("evenness " + q + "/dots_0000.csv --mask " + q + "/mask_0000.png --block 0",
                 "--block");
    write_text(dir + "/bad.csv", "id,x,y,size\n1,2,oops,3\n");
    expect_error("evenness " + q + "/bad.csv --mask " + q + "/mask_0000.png", "line 2");
    expect_error("coherence " + q + " --from 0 --to 5", "dots_0002.csv");
    expect_error("coherence " + q + "/nowhere", "not a directory");
    expect_error("frames " + q + " --frob", "unknown option");
    run("rm -f " + q + "/mask_0001.png");
    expect_error("coherence " + q, "mask_0001.png");
    run("rm -rf " + q);

    std::string log;
    EXPECT_EQ(run(bin("stipple-measure") + " --help", &log), 0);
    EXPECT_NE(log.find("evenness"), std::string::npos);
    for (const char* c : {"tone", "evenness", "coherence", "frames"}) {
        EXPECT_EQ(run(bin("stipple-measure") + " " + c + " --help", &log), 0) << c;
        EXPECT_EQ(log.rfind(std::string("usage: stipple-measure ") + c, 0), 0u) << log;
    }
}

// --hidden: dots each frame sized but hid behind the mesh (stipple-play --hidden-out) tell
// occlusion apart: dot 3 vanished behind the mesh of frame 1, so it is neither lost nor a pop.
TEST(MeasureCli, HiddenDotsTellOcclusionApart) {
    const std::string dir = make_frames_dir("hidden");
    const std::string q = "'" + dir + "'";
    expect_error("coherence " + q + " --hidden", "hidden_0000.csv");
    write_text(dir + "/hidden_0000.csv", "id,x,y,size\n");
    write_text(dir + "/hidden_0001.csv", "id,x,y,size\n3,40.5,20.5,2\n");
    nlohmann::json j = run_json("coherence " + q + " --hidden");
    const nlohmann::json& p = j["pairs"][0];
    EXPECT_NEAR(p["persistence"].get<double>(), 2.0 / 3.0, 1e-6);
    EXPECT_EQ(p["pops"].get<int>(), 2);
    EXPECT_EQ(p["occluded"].get<int>(), 1);
    EXPECT_EQ(p["disoccluded"].get<int>(), 0);
    EXPECT_NEAR(p["persistence_unoccluded"].get<double>(), 1.0, 1e-6);
    EXPECT_EQ(p["pops_unoccluded"].get<int>(), 1);  // dot 4 appeared from nowhere
    EXPECT_NEAR(j["summary"]["worst_persistence_unoccluded"].get<double>(), 1.0, 1e-6);
    EXPECT_EQ(j["summary"]["pops_unoccluded"].get<int>(), 1);
    // Without --hidden the output has no occlusion fields.
    j = run_json("coherence " + q);
    EXPECT_FALSE(j["pairs"][0].contains("occluded"));
    EXPECT_FALSE(j["summary"].contains("pops_unoccluded"));
    run("rm -rf " + q);
}

}  // namespace
