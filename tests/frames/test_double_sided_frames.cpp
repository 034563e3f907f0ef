// Double-sided surfaces in frames (issue 7, item 5): a double-sided sheet seen from behind
// keeps the tone of its front and shows its rim; the bake names a bad --double-sided value.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "tests/common/fixtures.h"

namespace {

using namespace stipple;

// SimpleSkin is one open sheet (glTF default material: single-sided). Baked with
// --double-sided on, its back (yaw 180) draws with the tone of its front; without, nothing.
class DoubleSidedFrames : public ::testing::Test {
  protected:
    static std::string dir;
    static void SetUpTestSuite() {
        dir = test::scratch_path("double_sided");
        test::run("rm -rf " + dir + " && mkdir -p " + dir);
        const std::string on = test::baked_asset("assets/SimpleSkin/SimpleSkin.gltf",
                                                 "--points 20000 --double-sided on");
        const std::string single =
            test::baked_asset("assets/SimpleSkin/SimpleSkin.gltf", "--points 20000");
        ASSERT_FALSE(on.empty() || single.empty());
        ASSERT_EQ(test::run("ln -s " + on + " " + dir + "/on.stip"), 0);
        ASSERT_EQ(test::run("ln -s " + single + " " + dir + "/auto.stip"), 0);
    }
    static void TearDownTestSuite() { test::run("rm -rf " + dir); }

    static test::Image frame(const std::string& asset, const std::string& name,
                             const std::string& args) {
        const std::string out = dir + "/" + name;
        std::string log;
        EXPECT_EQ(test::run(test::play_checked() + " " + dir + "/" + asset + " --out " + out +
                                " --frames 1 --no-apng --size 320x320 --time 1 " + args,
                            &log),
                  0)
            << log;
        test::Image img;
        EXPECT_TRUE(test::load_png(out + "/frame_0000.png", &img)) << out;
        return img;
    }
    // Mean darkness of the dots inside the sheet's mask (silhouette lines off; the mask is
    // the frame's --mask-out: where the mesh has depth). The mask comes from `mask_asset` if
    // given: a single-sided sheet seen from behind draws no body (its back faces are culled),
    // so its back view is measured inside the double-sided sheet's mask.
    static double tone(const std::string& asset, const std::string& name, std::string args,
                       const std::string& mask_asset = "") {
        args += " --no-silhouettes --mask-out";
        std::string masked = name;
        if (!mask_asset.empty()) frame(mask_asset, masked = name + "_mask", args);
        test::Image dots = frame(asset, name, args);
        test::Image mask;
        EXPECT_TRUE(test::load_png(dir + "/" + masked + "/mask_0000.png", &mask)) << masked;
        size_t pixels = 0;
        const double d = test::mean_darkness(dots, test::silhouette(mask), &pixels);
        EXPECT_GT(pixels, 2000u) << name;
        return d;
    }
};
std::string DoubleSidedFrames::dir;

TEST_F(DoubleSidedFrames, BackViewKeepsTheToneOfTheFrontView) {
    for (const char* lighting : {"", "--tone 0.3"}) {
        const std::string l = lighting;
        const double front = tone("on.stip", "front", "--yaw 0 " + l);
        const double back = tone("on.stip", "back", "--yaw 180 " + l);
        const double single = tone("auto.stip", "single_back", "--yaw 180 " + l, "on.stip");
        std::printf(
            "SimpleSkin darkness (%s): front %.4f, back %.4f (%+.1f%%), single-sided "
            "back %.4f\n",
            l.empty() ? "lit" : lighting, front, back, 100 * (back / front - 1), single);
        EXPECT_GT(front, 0.05);
        EXPECT_LE(std::fabs(back - front), 0.15 * front);
        EXPECT_LT(single, 0.1 * front);  // single-sided: its back draws (almost) nothing
    }
}

TEST_F(DoubleSidedFrames, RimIsOutlinedFromBehind) {
    // With dots off (--tone 0) only silhouette lines are ink: the rim shows from behind.
    auto ink = [](const test::Image& img) {
        size_t dark = 0;
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) dark += img.luminance(x, y) < 0.5f;
        return dark;
    };
    const size_t on = ink(frame("on.stip", "rim_on", "--yaw 180 --tone 0"));
    const size_t single = ink(frame("auto.stip", "rim_single", "--yaw 180 --tone 0"));
    std::printf("rim pixels seen from behind: double-sided %zu, single-sided %zu\n", on, single);
    EXPECT_GT(on, 400u);  // the sheet's outline: ~2 x (height + width) of its picture
    EXPECT_EQ(single, 0u);
}

TEST_F(DoubleSidedFrames, BadOptionIsNamed) {
    std::string log;
    EXPECT_EQ(test::run(test::bin("stipple-bake") + " " +
                            test::source("assets/SimpleSkin/SimpleSkin.gltf") + " -o " + dir +
                            "/x.stip --double-sided both",
                        &log),
              1);
    EXPECT_NE(log.find("--double-sided must be auto, on or off, got 'both'"), std::string::npos)
        << log;
}

}  // namespace
