// The player's animation options end to end: crossfade and blend between clips, and
// dual-quaternion skinning, measured on rendered frames.
#include <gtest/gtest.h>

#include "tests/common/fixtures.h"

namespace {

using namespace stipple::test;

// Height in pixels of the object's silhouette (rows holding any non-background pixel).
int silhouette_height(const Image& img) {
    int top = -1, bottom = -1;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            if (img.luminance(x, y) > 0.9f) {  // the object is white paper on grey
                if (top < 0) top = y;
                bottom = y;
                break;
            }
    return top < 0 ? 0 : bottom - top + 1;
}

class PlayerAnimation : public ::testing::Test {
  protected:
    static std::string dir;
    static void SetUpTestSuite() {
        dir = scratch_path("player_anim");
        run("rm -rf " + dir + " && mkdir -p " + dir);
        const std::string tube =
            baked_asset("assets/stretch_tube/stretch_tube.gltf", "--points 5000");
        ASSERT_FALSE(tube.empty());
        ASSERT_EQ(run("ln -s " + tube + " " + dir + "/tube.stip"), 0);
    }
    static void TearDownTestSuite() { run("rm -rf " + dir); }
};
std::string PlayerAnimation::dir;

// The tube's upper bone (y 0.5..2) scales by s, so the tube is 0.5 + 1.5 s tall. A crossfade
// from "rest" to "stretch" over 1 s at 30 fps: frame 15 blends scale 1.5 (stretch at 0.5 s)
// half and half with 1 -> s = 1.25; frame 30 is all "stretch" at 1 s -> s = 2.
TEST_F(PlayerAnimation, CrossfadeRampsFromOneClipToTheOther) {
    std::string out = dir + "/crossfade";
    ASSERT_EQ(run(play_checked() + " " + dir + "/tube.stip --out " + out +
                  " --clip rest --crossfade stretch:1 --frames 31 --fps 30 --zoom 0.5"
                  " --size 200x400 --tone 0 --no-silhouettes --background 808080 --no-apng"),
              0);
    Image f0, f15, f30;
    ASSERT_TRUE(load_png(out + "/frame_0000.png", &f0));
    ASSERT_TRUE(load_png(out + "/frame_0015.png", &f15));
    ASSERT_TRUE(load_png(out + "/frame_0030.png", &f30));
    double h0 = silhouette_height(f0);
    ASSERT_GT(h0, 50);
    EXPECT_NEAR(silhouette_height(f15) / h0, 2.375 / 2.0, 0.05);
    EXPECT_NEAR(silhouette_height(f30) / h0, 3.5 / 2.0, 0.06);
}

TEST_F(PlayerAnimation, BlendLayersTwoClipsWithAWeight) {
    std::string out = dir + "/blend";
    ASSERT_EQ(run(play_checked() + " " + dir + "/tube.stip --out " + out +
                  " --clip rest --blend stretch:0.5 --time 1 --frames 1 --zoom 0.5"
                  " --size 200x400 --tone 0 --no-silhouettes --background 808080 --no-apng"),
              0);
    // The reference blends with weight 0: the rest pose, framed like the blend (both clips).
    std::string ref = dir + "/blend_ref";
    ASSERT_EQ(run(play_checked() + " " + dir + "/tube.stip --out " + ref +
                  " --clip rest --blend stretch:0 --frames 1 --zoom 0.5 --size 200x400 --tone 0"
                  " --no-silhouettes --background 808080 --no-apng"),
              0);
    Image blended, rest;
    ASSERT_TRUE(load_png(out + "/frame_0000.png", &blended));
    ASSERT_TRUE(load_png(ref + "/frame_0000.png", &rest));
    // Half of scale 2 and half of scale 1: s = 1.5, height 2.75 against 2.
    EXPECT_NEAR(double(silhouette_height(blended)) / silhouette_height(rest), 2.75 / 2.0, 0.05);
}

TEST_F(PlayerAnimation, DualQuaternionSkinningRendersAndDiffersOnlySlightlyFromLbs) {
    std::string log;
    for (const char* method : {"lbs", "dqs"})
        ASSERT_EQ(run(play_checked() + " " + dir + "/tube.stip --out " + dir + "/" + method +
                          " --clip stretch --time 1 --frames 1 --zoom 0.5 --size 200x400"
                          " --tone 0 --no-silhouettes --background 808080 --no-apng --skinning " +
                          method,
                      &log),
                  0)
            << log;
    Image lbs, dqs;
    ASSERT_TRUE(load_png(dir + "/lbs/frame_0000.png", &lbs));
    ASSERT_TRUE(load_png(dir + "/dqs/frame_0000.png", &dqs));
    // A pure scale along the bone: both methods give the same silhouette height.
    EXPECT_NEAR(silhouette_height(dqs), silhouette_height(lbs), 2);
}

TEST_F(PlayerAnimation, BadClipOptionsAreNamed) {
    std::string log;
    EXPECT_EQ(
        run(play_checked() + " " + dir + "/tube.stip --out " + dir + "/x --crossfade walk:1", &log),
        1);
    EXPECT_NE(log.find("no clip 'walk'"), std::string::npos) << log;
    EXPECT_EQ(
        run(play_checked() + " " + dir + "/tube.stip --out " + dir + "/x --blend stretch", &log),
        1);
    EXPECT_NE(log.find("--blend takes CLIP:WEIGHT"), std::string::npos) << log;
    EXPECT_EQ(run(play_checked() + " " + dir + "/tube.stip --out " + dir + "/x --skinning x", &log),
              1);
    EXPECT_NE(log.find("--skinning must be lbs or dqs"), std::string::npos) << log;
}

// --check-gl puts the GL error count in --stats; --rss-every writes the soak test's memory
// curve (scripts/soak.sh): a row per N frames, every RSS positive. A sweep there and back
// (--zoom-period) draws the close-up twice.
TEST_F(PlayerAnimation, CheckGlAndRssEveryReportWhatASoakNeeds) {
    const std::string out = dir + "/soak";
    std::string log;
    ASSERT_EQ(run(play_checked() + " " + dir + "/tube.stip --out " + out +
                      " --frames 40 --size 64x64 --zoom 0.5 --zoom-to 16 --zoom-period 20"
                      " --no-png --no-apng --stats --rss-every 10",
                  &log),
              0)
        << log;
    EXPECT_NE(log.find("\"gl_errors\": 0"), std::string::npos) << log;
    std::ifstream csv(out + "/rss.csv");
    std::string line;
    ASSERT_TRUE(std::getline(csv, line));
    EXPECT_EQ(line, "frame,rss_kb,ms_per_frame");
    int rows = 0;
    long frame = 0, rss = 0;
    while (std::getline(csv, line)) {
        ASSERT_EQ(std::sscanf(line.c_str(), "%ld,%ld,", &frame, &rss), 2) << line;
        EXPECT_EQ(frame, 10 * ++rows);
        EXPECT_GT(rss, 1000);
    }
    EXPECT_EQ(rows, 4);
}

}  // namespace
