// The looks in stipple-play (--style, --toon-bands, --toon-ink, --fill, --tone-gamma,
// --tone-contrast, --no-creases; runtime/style.h, docs/styles.md): every style changes the
// frame and draws the same frame twice, the tone curve moves the tone the way it says, and bad
// values are one-line errors. (Looks from an asset's LOOK section: tests/runtime/
// test_style_looks.cpp, with a LooksView the test fills.)
#include <gtest/gtest.h>

#include <algorithm>

#include "tests/common/fixtures.h"

namespace {

using namespace stipple::test;

// One 320x240 frame of the walk drawn with `args`.
Image frame(const std::string& asset, const ScratchDir& dir, const std::string& name,
            const std::string& args) {
    std::string log;
    EXPECT_EQ(run(play_checked() + " " + asset + " --out " + dir.file(name) +
                      " --frames 1 --size 320x240 --time 0.4 --no-apng " + args,
                  &log),
              0)
        << log;
    Image img;
    EXPECT_TRUE(load_png(dir.file(name) + "/frame_0000.png", &img)) << name;
    return img;
}

size_t changed(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height) return size_t(-1);
    size_t n = 0;
    for (size_t i = 0; i < a.rgba.size(); ++i) n += a.rgba[i] != b.rgba[i];
    return n;
}

size_t dark(const Image& img) {
    size_t n = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) n += img.luminance(x, y) < 0.5f;
    return n;
}

TEST(Styles, EachStyleIsItsOwnDeterministicFrame) {
    const std::string asset = baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 20000");
    ScratchDir dir;
    const Image classic = frame(asset, dir, "classic", "");
    EXPECT_EQ(changed(classic, frame(asset, dir, "classic_named", "--style classic")), 0u);
    for (const char* style : {"toon", "colour", "transparent"}) {
        const Image a =
            frame(asset, dir, std::string(style) + "_a", std::string("--style ") + style);
        const Image b =
            frame(asset, dir, std::string(style) + "_b", std::string("--style ") + style);
        EXPECT_EQ(changed(a, b), 0u) << style << ": two runs differ";
        EXPECT_GT(changed(a, classic), 400u) << style << " looks like classic";
    }
    // Toon settings change the toon frame; --no-creases without crease lines changes nothing.
    const Image toon = frame(asset, dir, "toon", "--style toon");
    EXPECT_GT(changed(toon, frame(asset, dir, "toon2", "--style toon --toon-bands 2")), 100u);
    EXPECT_GT(changed(toon, frame(asset, dir, "toon_fill", "--style toon --fill 3366cc")), 1000u);
    EXPECT_GT(changed(toon, frame(asset, dir, "toon_ink", "--style toon --toon-ink 0.1")), 100u);
    EXPECT_EQ(changed(classic, frame(asset, dir, "no_creases", "--no-creases")), 0u);
}

TEST(Styles, TheToneCurveLightensAndDarkens) {
    const std::string asset = baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 20000");
    ScratchDir dir;
    const std::string flat = "--no-silhouettes --tone 0.5 ";
    const size_t base = dark(frame(asset, dir, "base", flat));
    const size_t lighter = dark(frame(asset, dir, "g2", flat + "--tone-gamma 2"));
    const size_t darker = dark(frame(asset, dir, "g05", flat + "--tone-gamma 0.5"));
    const size_t contrast_low = dark(frame(asset, dir, "c2low",
                                           "--no-silhouettes --tone 0.3 "
                                           "--tone-contrast 2"));
    const size_t low = dark(frame(asset, dir, "low", "--no-silhouettes --tone 0.3"));
    ASSERT_GT(base, 500u);
    EXPECT_LT(lighter, base * 3 / 4) << "gamma 2: tone 0.5 -> 0.25";
    EXPECT_GT(darker, base * 5 / 4) << "gamma 0.5: tone 0.5 -> 0.71";
    EXPECT_LT(contrast_low, low / 2) << "contrast 2: tone 0.3 -> 0.1";
    // Identity curve: the classic frame, byte for byte.
    EXPECT_EQ(changed(frame(asset, dir, "id", flat + "--tone-gamma 1 --tone-contrast 1"),
                      frame(asset, dir, "plain", flat)),
              0u);
}

TEST(Styles, BadLookOptionsAreOneLineErrors) {
    const std::string asset = baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 20000");
    ScratchDir dir;
    for (const char* bad :
         {"--style bogus", "--toon-bands 4", "--toon-bands 1", "--tone-gamma 0", "--tone-gamma 11",
          "--tone-contrast 0.01", "--fill 12345", "--fill zzzzzz", "--toon-ink 2"}) {
        std::string log;
        EXPECT_EQ(
            run(bin("stipple-play") + " " + asset + " --out " + dir.file("x") + " " + bad, &log), 1)
            << bad << ": " << log;
        EXPECT_EQ(std::count(log.begin(), log.end(), '\n'), 1) << bad << ": " << log;
    }
}

}  // namespace
