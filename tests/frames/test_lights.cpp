// Lights in stipple-play (--light X,Y,Z[,I], --light-space, --ambient): the tone follows
// ambient + the sum of intensity * max(N.L, 0) over the lights (runtime/stipple_size.h).
#include <gtest/gtest.h>

#include <algorithm>

#include "tests/common/fixtures.h"

namespace {

using namespace stipple::test;

// Dark pixels of one 320x240 frame of the walk drawn with `args`.
size_t dark_pixels(const std::string& asset, const ScratchDir& dir, const std::string& name,
                   const std::string& args) {
    std::string log;
    EXPECT_EQ(run(play_checked() + " " + asset + " --out " + dir.file(name) +
                      " --frames 1 --size 320x240 --no-apng --no-silhouettes " + args,
                  &log),
              0)
        << log;
    Image img;
    EXPECT_TRUE(load_png(dir.file(name) + "/frame_0000.png", &img));
    size_t n = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) n += img.luminance(x, y) < 0.5f;
    return n;
}

TEST(Lights, TheToneFollowsTheLights) {
    const std::string asset = baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 20000");
    ScratchDir dir;
    const size_t key = dark_pixels(asset, dir, "key", "");
    // The camera looks down -Z from +Z: a world light toward -Z lights the back only.
    const size_t behind = dark_pixels(asset, dir, "behind", "--light 0,0,-1 --light-space world");
    const size_t front = dark_pixels(asset, dir, "front", "--light 0,0,1 --light-space world");
    const size_t two = dark_pixels(asset, dir, "two", "--light 1,0,0,0.7 --light -1,0,0,0.7");
    const size_t bright = dark_pixels(asset, dir, "bright", "--light 0,0,1 --ambient 1");
    EXPECT_GT(behind, front * 3 / 2) << "lit from behind, the visible side is darker";
    EXPECT_GT(behind, key);
    EXPECT_LT(bright, front / 2) << "ambient 1: every point fully lit";
    EXPECT_NE(two, key);
    // Camera space: the same light follows the camera round the character.
    const size_t cam0 = dark_pixels(asset, dir, "cam0", "--light 0,0,1 --yaw 0");
    const size_t cam90 = dark_pixels(asset, dir, "cam90", "--light 0,0,1 --yaw 90");
    const size_t world90 =
        dark_pixels(asset, dir, "world90", "--light 0,0,1 --light-space world --yaw 90");
    EXPECT_LT(cam90, world90) << "a headlight keeps the seen side lit; a world light does not";
    EXPECT_GT(cam0, 0u);
}

TEST(Lights, BadLightsAreOneLineErrors) {
    const std::string asset = baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 20000");
    ScratchDir dir;
    for (const char* bad :
         {"--light 0,0,0", "--light 1,2", "--light 1,2,3,99", "--light 1,2,3,4,5",
          "--light-space moon", "--ambient 2",
          "--light 1,0,0 --light 1,0,0 --light 1,0,0 --light 1,0,0 --light 1,0,0"}) {
        std::string log;
        EXPECT_EQ(
            run(bin("stipple-play") + " " + asset + " --out " + dir.file("x") + " " + bad, &log), 1)
            << bad << ": " << log;
        EXPECT_EQ(std::count(log.begin(), log.end(), '\n'), 1) << bad << ": " << log;
    }
}

}  // namespace
