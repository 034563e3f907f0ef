// The C API end to end: load, create a player on a headless context, draw, read back.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "platform/headless_context.h"
#include "runtime/stipple.h"
#include "tests/common/fixtures.h"

extern "C" long c_api_blend_height(const char* asset_path, stipple_get_proc_fn get_proc,
                                   float weight);
extern "C" long c_api_render_dark_pixels(const char* asset_path, stipple_get_proc_fn get_proc,
                                         float time, uint32_t* points_drawn, uint32_t* gl_errors);
extern "C" long c_api_closeup_dark_pixels(const char* asset_path, stipple_get_proc_fn get_proc,
                                          int refinement_budget);
extern "C" long c_api_strokes_drawn(const char* asset_path, stipple_get_proc_fn get_proc,
                                    int no_strokes, int quality, uint32_t* triangles);

namespace {

using namespace stipple::test;

TEST(CApi, RendersAStippledFrameFromC) {
    const std::string asset = baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 20000");
    ASSERT_FALSE(asset.empty());
    HeadlessGl gl;
    std::string error;
    ASSERT_TRUE(gl.open(&error)) << error;
    uint32_t drawn = 0, gl_errors = 1;
    long dark = c_api_render_dark_pixels(
        asset.c_str(), stipple::platform::proc_loader(gl.context()), 0.5f, &drawn, &gl_errors);
    EXPECT_GT(dark, 300) << stipple_last_error();
    EXPECT_GT(drawn, 200u);
    EXPECT_EQ(gl_errors, 0u);  // desc.check_gl_errors: no pass raised a GL error
}

// Blending through the C API (with DQS): the tube's upper bone at scale 1 + weight.
TEST(CApi, BlendsTwoClips) {
    const std::string asset = baked_asset("assets/stretch_tube/stretch_tube.gltf", "--points 3000");
    ASSERT_FALSE(asset.empty());
    HeadlessGl gl;
    std::string error;
    ASSERT_TRUE(gl.open(&error)) << error;
    const long rest =
        c_api_blend_height(asset.c_str(), stipple::platform::proc_loader(gl.context()), 0);
    const long half =
        c_api_blend_height(asset.c_str(), stipple::platform::proc_loader(gl.context()), 0.5f);
    ASSERT_GT(rest, 50) << stipple_last_error();
    // Height 0.5 + 1.5 s: s = 1 -> 2, s = 1.5 -> 2.75.
    EXPECT_NEAR(double(half) / double(rest), 2.75 / 2.0, 0.05);
}

// A close-up through the C API: the run-time refinement keeps the tone (issue 7); with the
// budget set to none the hierarchy runs out and the frame fades.
TEST(CApi, CloseUpsKeepTheirToneWithRunTimeRefinement) {
    const std::string asset = baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 5000");
    ASSERT_FALSE(asset.empty());
    HeadlessGl gl;
    std::string error;
    ASSERT_TRUE(gl.open(&error)) << error;
    const long refined =
        c_api_closeup_dark_pixels(asset.c_str(), stipple::platform::proc_loader(gl.context()), 0);
    const long plain =
        c_api_closeup_dark_pixels(asset.c_str(), stipple::platform::proc_loader(gl.context()), -1);
    std::printf("close-up dark pixels: refined %ld, without refinement %ld\n", refined, plain);
    ASSERT_GT(refined, 0) << stipple_last_error();
    EXPECT_GT(refined, 4 * plain);
    EXPECT_GT(refined, 320 * 240 / 10);  // a tone of 0.3 over most of the frame
}

TEST(CApi, ErrorsAreCodesWithAMessage) {
    stipple_asset* asset = nullptr;
    EXPECT_EQ(stipple_asset_load_file("/nonexistent/x.stip", &asset), STIPPLE_ERROR_IO);
    EXPECT_EQ(asset, nullptr);
    EXPECT_NE(std::strstr(stipple_last_error(), "x.stip"), nullptr);
    const char junk[64] = "definitely not an asset";
    EXPECT_EQ(stipple_asset_load_memory(junk, sizeof(junk), &asset), STIPPLE_ERROR_BAD_ASSET);
    EXPECT_EQ(stipple_asset_load_file(nullptr, &asset), STIPPLE_ERROR_INVALID_ARGUMENT);
    stipple_player* player = nullptr;
    stipple_player_desc desc = {};
    EXPECT_EQ(stipple_player_create(nullptr, &desc, &player), STIPPLE_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(stipple_asset_find_clip(nullptr, "walk"), -1);
    EXPECT_EQ(stipple_asset_clip_name(nullptr, 0), nullptr);
}

// Paintstroke switches through the C API: strokes draw by default, no_strokes turns them
// off, quality 0 / 2 change the tessellation (2^q polygons per side), an unknown quality is
// refused with a named error.
TEST(CApi, PaintstrokeSwitches) {
    const std::string asset =
        baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 20000 --fur 3000");
    ASSERT_FALSE(asset.empty());
    HeadlessGl gl;
    std::string error;
    ASSERT_TRUE(gl.open(&error)) << error;
    const stipple_get_proc_fn proc = stipple::platform::proc_loader(gl.context());
    uint32_t auto_tris = 0, q0 = 0, q2 = 0, none = 0;
    EXPECT_EQ(c_api_strokes_drawn(asset.c_str(), proc, 0, STIPPLE_STROKE_QUALITY_AUTO, &auto_tris),
              3000)
        << stipple_last_error();
    EXPECT_EQ(c_api_strokes_drawn(asset.c_str(), proc, 0, STIPPLE_STROKE_QUALITY_0, &q0), 3000);
    EXPECT_EQ(c_api_strokes_drawn(asset.c_str(), proc, 0, STIPPLE_STROKE_QUALITY_2, &q2), 3000);
    EXPECT_EQ(c_api_strokes_drawn(asset.c_str(), proc, 1, STIPPLE_STROKE_QUALITY_AUTO, &none), 0);
    EXPECT_EQ(none, 0u);
    EXPECT_GT(q0, 10000u);
    EXPECT_GT(q2, 3 * q0);  // 8 triangles a segment instead of 2 (caps aside)
    EXPECT_GE(auto_tris, q0);
    EXPECT_LE(auto_tris, q2);

    stipple_player_desc bad = {};
    bad.stroke_quality = 7;
    stipple_player_desc out;
    EXPECT_EQ(stipple_player_desc_resolve(&bad, &out), STIPPLE_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::strstr(stipple_last_error(), "stroke_quality"), nullptr) << stipple_last_error();
}

// stipple_player_draw_into through the C API: the orbit camera's matrices, the test's own
// framebuffer cleared to white, and the frame matches the player's own frame of the state.
TEST(CApi, DrawsIntoTheApplicationsFramebuffer) {
    const std::string path = baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 20000");
    HeadlessGl gl;
    std::string error;
    ASSERT_TRUE(gl.open(&error)) << error;
    const stipple::GlApi& g = gl.gl();
    stipple_asset* asset = nullptr;
    ASSERT_EQ(stipple_asset_load_file(path.c_str(), &asset), STIPPLE_OK);
    stipple_player_desc desc = {};
    desc.width = 320;
    desc.height = 240;
    desc.get_proc_address = stipple::platform::proc_loader(gl.context());
    stipple_player* player = nullptr;
    ASSERT_EQ(stipple_player_create(asset, &desc, &player), STIPPLE_OK) << stipple_last_error();
    stipple_app_view view = {};
    ASSERT_EQ(stipple_orbit_camera(asset, &desc, view.view, view.projection), STIPPLE_OK);
    for (int k = 0; k < 4; ++k) view.model[k * 5] = 1.0f;
    view.viewport[2] = 320;
    view.viewport[3] = 240;
    TestFramebuffer framebuffer;
    ASSERT_TRUE(framebuffer.create(g, 320, 240));
    g.Viewport(0, 0, 320, 240);
    g.DepthMask(GL_TRUE);  // stipple_player_create drew a frame of its own (player state)
    g.ClearColor(1, 1, 1, 1);
    g.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    stipple_player_draw_into(player, &view, 0, 0.5f, -1, 0.0f, 0.0f);
    std::vector<uint8_t> app(320 * 240 * 4), own(320 * 240 * 4);
    g.BindFramebuffer(GL_FRAMEBUFFER, framebuffer.fbo());
    g.ReadPixels(0, 0, 320, 240, GL_RGBA, GL_UNSIGNED_BYTE, app.data());
    stipple_player_draw(player, 0, 0.5f);
    stipple_player_read_rgba(player, own.data());
    size_t differ = 0, ink = 0;
    for (size_t i = 0; i < own.size(); i += 4) {
        ink += own[i] < 100;
        differ += std::abs(int(app[i]) - int(own[i])) > 8;
    }
    size_t ink_app = 0;
    for (size_t i = 0; i < app.size(); i += 4) ink_app += app[i] < 100;
    EXPECT_GT(ink, 400u);
    EXPECT_LT(differ, 320u * 240u / 200u) << differ << " ink " << ink << " app ink " << ink_app;
    view.viewport[2] = 0;  // out of range: refused with a message, nothing drawn
    stipple_player_draw_into(player, &view, 0, 0.5f, -1, 0.0f, 0.0f);
    EXPECT_NE(std::strstr(stipple_last_error(), "viewport"), nullptr) << stipple_last_error();
    stipple_player_destroy(player);
    stipple_asset_destroy(asset);
}

// Per-frame settings through the C API, on one player, between draws: ink colour, lights
// (a world-space light from behind darkens the front), silhouettes, constant tone; a bad
// value is refused by name and changes nothing.
TEST(CApi, PerFrameSettingsWithoutRecreation) {
    const std::string path = baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 20000");
    HeadlessGl gl;
    std::string error;
    ASSERT_TRUE(gl.open(&error)) << error;
    stipple_asset* asset = nullptr;
    ASSERT_EQ(stipple_asset_load_file(path.c_str(), &asset), STIPPLE_OK);
    stipple_player_desc desc = {};
    desc.width = 320;
    desc.height = 240;
    desc.get_proc_address = stipple::platform::proc_loader(gl.context());
    stipple_player* player = nullptr;
    ASSERT_EQ(stipple_player_create(asset, &desc, &player), STIPPLE_OK) << stipple_last_error();
    std::vector<uint8_t> rgba(320 * 240 * 4);
    auto count = [&](auto pred) {
        stipple_player_draw(player, 0, 0.5f);
        stipple_player_read_rgba(player, rgba.data());
        size_t n = 0;
        for (size_t i = 0; i < rgba.size(); i += 4) n += pred(&rgba[i]);
        return n;
    };
    auto dark = [](const uint8_t* p) { return p[0] < 100 && p[1] < 100 && p[2] < 100; };
    auto red = [](const uint8_t* p) { return p[0] > 150 && p[1] < 60 && p[2] < 60; };
    const size_t dark_key_light = count(dark);
    EXPECT_GT(dark_key_light, 400u);
    EXPECT_EQ(count(red), 0u);

    ASSERT_EQ(stipple_player_set_colours(player, 0xFFFFFF, 0xE01010, 0xFFFFFF), STIPPLE_OK);
    EXPECT_GT(count(red), 400u) << "the ink turned red";
    ASSERT_EQ(stipple_player_set_colours(player, 0xFFFFFF, 0x000000, 0xFFFFFF), STIPPLE_OK);

    stipple_light behind = {{0.0f, 0.0f, -1.0f}, 1.0f, 1};  // world space, from behind
    ASSERT_EQ(stipple_player_set_lights(player, &behind, 1, 0.0f), STIPPLE_OK);
    const size_t dark_behind = count(dark);
    EXPECT_GT(dark_behind, dark_key_light * 5 / 4) << "lit from behind, the front darkens";
    stipple_light bright = {{0.0f, 1.0f, 0.0f}, 1.0f, 0};
    ASSERT_EQ(stipple_player_set_lights(player, &bright, 1, 1.0f), STIPPLE_OK);  // ambient 1
    ASSERT_EQ(stipple_player_set_silhouettes(player, 0, 0.0f), STIPPLE_OK);
    EXPECT_LT(count(dark), dark_key_light / 4) << "fully lit, no outline: almost no ink";

    stipple_light zero = {{0.0f, 0.0f, 0.0f}, 1.0f, 0};
    EXPECT_EQ(stipple_player_set_lights(player, &zero, 1, 0.0f), STIPPLE_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::strstr(stipple_last_error(), "direction"), nullptr) << stipple_last_error();
    EXPECT_EQ(stipple_player_set_tone(player, 1, 1.5f, 0.0f), STIPPLE_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::strstr(stipple_last_error(), "constant_tone"), nullptr);
    ASSERT_EQ(stipple_player_set_tone(player, 1, 0.5f, 0.0f), STIPPLE_OK);
    EXPECT_GT(count(dark), dark_key_light / 2) << "constant tone 0.5 ignores the lights";
    stipple_player_destroy(player);
    stipple_asset_destroy(asset);
}

// The logger hook gets every failure's message and the warnings; loads keep the C++ loader's
// distinct error codes.
TEST(CApi, LoggerAndDistinctLoadErrors) {
    struct Log {
        std::vector<std::pair<int, std::string>> lines;
    } log;
    stipple_set_logger(
        [](int level, const char* message, void* user) {
            static_cast<Log*>(user)->lines.emplace_back(level, message);
        },
        &log);
    stipple_asset* asset = nullptr;
    EXPECT_EQ(stipple_asset_load_file("/nonexistent/x.stip", &asset), STIPPLE_ERROR_IO);
    EXPECT_EQ(stipple_last_load_error(), STIPPLE_LOAD_IO_ERROR);
    ASSERT_EQ(log.lines.size(), 1u);
    EXPECT_EQ(log.lines[0].first, 2);
    EXPECT_EQ(log.lines[0].second, stipple_last_error());

    // A flipped byte inside a section: the checksum check names it.
    const std::string path = baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 5000");
    std::ifstream in(path, std::ios::binary);
    std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_GT(bytes.size(), 4096u);
    bytes[bytes.size() / 2] ^= 0x5A;
    EXPECT_EQ(stipple_asset_load_memory(bytes.data(), bytes.size(), &asset),
              STIPPLE_ERROR_BAD_ASSET);
    EXPECT_EQ(stipple_last_load_error(), STIPPLE_LOAD_CHECKSUM_MISMATCH) << stipple_last_error();

    // A warning once: fur at quality 2 overflows the smallest stroke budget.
    const std::string fur =
        baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 20000 --fur 3000");
    HeadlessGl gl;
    std::string error;
    ASSERT_TRUE(gl.open(&error)) << error;
    ASSERT_EQ(stipple_asset_load_file(fur.c_str(), &asset), STIPPLE_OK);
    EXPECT_EQ(stipple_last_load_error(), STIPPLE_LOAD_OK);
    stipple_player_desc desc = {};
    desc.width = 320;
    desc.height = 240;
    desc.stroke_vertex_budget = 1024;
    desc.stroke_quality = STIPPLE_STROKE_QUALITY_2;
    desc.get_proc_address = stipple::platform::proc_loader(gl.context());
    stipple_player* player = nullptr;
    ASSERT_EQ(stipple_player_create(asset, &desc, &player), STIPPLE_OK);
    log.lines.clear();
    stipple_player_draw(player, 0, 0.1f);
    stipple_player_draw(player, 0, 0.2f);
    ASSERT_EQ(log.lines.size(), 1u);
    EXPECT_EQ(log.lines[0].first, 1);
    EXPECT_NE(log.lines[0].second.find("stroke budget"), std::string::npos);
    stipple_set_logger(nullptr, nullptr);
    stipple_player_destroy(player);
    stipple_asset_destroy(asset);
}

}  // namespace
