// Particle styles through the C API (issue 11): the built-in ones by name, and a user style
// written against the C callbacks (examples/particle_style/blue_hatching.c) registered and drawn.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "platform/headless_context.h"
#include "runtime/stipple.h"
#include "tests/common/fixtures.h"

extern "C" int register_blue_hatching(void);

namespace {

using namespace stipple::test;

struct Counts {
    long blue = 0, dark = 0;
};

// Draws 6 frames of the walk at 320x240 with `style` and counts blue and dark pixels.
Counts draw(int style, std::vector<uint8_t>* rgba = nullptr) {
    const std::string path = baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 20000");
    HeadlessGl gl;
    std::string error;
    EXPECT_TRUE(gl.open(&error)) << error;
    stipple_asset* asset = nullptr;
    EXPECT_EQ(stipple_asset_load_file(path.c_str(), &asset), STIPPLE_OK);
    stipple_player_desc desc;
    std::memset(&desc, 0, sizeof(desc));
    desc.width = 320;
    desc.height = 240;
    desc.style = style;
    desc.check_gl_errors = 1;
    desc.get_proc_address = stipple::platform::proc_loader(gl.context());
    stipple_player* player = nullptr;
    EXPECT_EQ(stipple_player_create(asset, &desc, &player), STIPPLE_OK) << stipple_last_error();
    Counts c;
    if (!player) return c;
    std::vector<uint8_t> px(320 * 240 * 4);
    for (int f = 0; f < 6; ++f) stipple_player_draw(player, 0, 0.5f);
    stipple_player_read_rgba(player, px.data());
    for (size_t i = 0; i < px.size(); i += 4) {
        c.blue += px[i + 2] > px[i] + 60;
        c.dark += px[i] < 100 && px[i + 2] < 100;
    }
    EXPECT_EQ(stipple_player_gl_errors(player), 0u);
    stipple_player_destroy(player);
    stipple_asset_destroy(asset);
    if (rgba) *rgba = px;
    return c;
}

TEST(ParticleCApi, BuiltInStylesByName) {
    const int ink = stipple_find_style("ink");
    ASSERT_GE(ink, 4);
    EXPECT_STREQ(stipple_style_name(ink), "ink");
    EXPECT_EQ(stipple_find_style("painterly-long"), ink - 7);
    const Counts c = draw(ink);
    EXPECT_GT(c.dark, 200);
    EXPECT_EQ(c.blue, 0);
}

TEST(ParticleCApi, AUserStyleDrawsWithItsCallbacks) {
    const int style = register_blue_hatching();
    ASSERT_GE(style, 12) << stipple_last_error();
    EXPECT_EQ(register_blue_hatching(), style);  // registered once
    EXPECT_EQ(stipple_find_style("blue-hatching"), style);
    EXPECT_STREQ(stipple_style_name(style), "blue-hatching");
    std::vector<uint8_t> a, b;
    const Counts c = draw(style, &a);
    EXPECT_GT(c.blue, 300) << "the callbacks' blue hatching";
    EXPECT_LT(c.dark, c.blue / 4);
    draw(style, &b);
    EXPECT_EQ(a, b) << "deterministic";
}

TEST(ParticleCApi, BadRegistrationsAreRefusedWithAMessage) {
    stipple_style_desc d;
    std::memset(&d, 0, sizeof(d));
    EXPECT_EQ(stipple_register_style(nullptr), -1);
    EXPECT_EQ(stipple_register_style(&d), -1);  // no name
    d.name = "classic";
    EXPECT_EQ(stipple_register_style(&d), -1);  // a stipple look's name
    EXPECT_NE(std::strstr(stipple_last_error(), "taken"), nullptr) << stipple_last_error();
    d.name = "ok-name";
    d.base = "no-such-style";
    EXPECT_EQ(stipple_register_style(&d), -1);
    d.base = nullptr;
    d.spacing_px = 2000.0f;
    EXPECT_EQ(stipple_register_style(&d), -1);
    d.spacing_px = 0.0f;
    d.name = "Bad Name";
    EXPECT_EQ(stipple_register_style(&d), -1);
}

}  // namespace
