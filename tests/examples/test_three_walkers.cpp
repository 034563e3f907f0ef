// examples/three_walkers, built against the installed package by the ctest step
// Examples.BuildThreeWalkers: its frame shows the application's ground and box and three
// stippled walkers, the box hiding the walker behind it and the walkers standing in front of
// the ground.
#include <gtest/gtest.h>

#include "tests/common/fixtures.h"

namespace {

using namespace stipple::test;

const uint8_t* px(const Image& img, int x, int y) {
    return &img.rgba[(size_t(y) * size_t(img.width) + size_t(x)) * 4];
}
bool is(const uint8_t* p, int r, int g, int b) {
    return std::abs(p[0] - r) <= 2 && std::abs(p[1] - g) <= 2 && std::abs(p[2] - b) <= 2;
}
bool ink(const uint8_t* p) {
    return p[0] < 80 && p[1] < 80 && p[2] < 80;
}
bool paper(const uint8_t* p) {
    return p[0] > 245 && p[1] > 245 && p[2] > 245;
}

void check_frame(const std::string& path) {
    Image img;
    ASSERT_TRUE(load_png(path, &img)) << path;  // stb reads PPM
    ASSERT_EQ(img.width, 640);
    ASSERT_EQ(img.height, 480);
    // The box (0.2, 0.35, 0.8): its bounding rectangle, and inside it nothing but box.
    int x0 = img.width, x1 = -1, y0 = img.height, y1 = -1;
    size_t ground = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const uint8_t* p = px(img, x, y);
            if (is(p, 51, 89, 204))
                x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y),
                y1 = std::max(y1, y);
            ground += is(p, 140, 140, 140);
        }
    ASSERT_GT(x1 - x0, 60) << "no box";
    EXPECT_GT(ground, 50000u) << "no ground";
    size_t not_box = 0;
    for (int y = y0 + 25; y <= y1 - 25; ++y)  // the front face, away from its slanted edges
        for (int x = x0 + 25; x <= x1 - 25; ++x) not_box += !is(px(img, x, y), 51, 89, 204);
    EXPECT_EQ(not_box, 0u) << "the walker behind the box shows through it";
    // Three walkers: ink and paper in each third of the picture, paper over the ground.
    size_t ink_in[3] = {}, paper_in[3] = {}, paper_over_ground = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const uint8_t* p = px(img, x, y);
            const int third = x * 3 / img.width;
            ink_in[third] += ink(p);
            paper_in[third] += paper(p);
            paper_over_ground += paper(p) && y > img.height * 55 / 100;  // below the horizon
        }
    for (int k = 0; k < 3; ++k) {
        EXPECT_GT(ink_in[k], 150u) << "walker " << k;
        EXPECT_GT(paper_in[k], 600u) << "walker " << k;
    }
    EXPECT_GT(paper_over_ground, 500u) << "the walkers' legs should stand in front of the ground";
}

TEST(ThreeWalkers, GroundBoxAndThreeOccludedWalkers) {
    check_frame(STIPPLE_EXAMPLE_FRAME);
}

// The same application showing its frames in an X11 window (under Xvfb): the frame it drew
// last (10 frames into the walk) holds the same.
TEST(ThreeWalkers, InAWindowToo) {
    if (run("command -v xvfb-run > /dev/null") != 0) GTEST_SKIP() << "no xvfb-run";
    check_frame(STIPPLE_EXAMPLE_WINDOW_FRAME);
}

}  // namespace
