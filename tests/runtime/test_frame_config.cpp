// Frame settings: one table of defaults and limits (runtime/frame_config.h), resolved the same
// way by the C++ API and the C API; and the runtime Status codes the C API reports.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>

#include "runtime/asset.h"
#include "runtime/frame_config.h"
#include "runtime/stipple.h"
#include "tests/common/fixtures.h"

namespace stipple {
namespace {

TEST(FrameConfig, DefaultsAreTheHistoricOnes) {
    const FrameConfig d = default_frame_config();
    EXPECT_EQ(d.width, 640);
    EXPECT_EQ(d.height, 480);
    EXPECT_EQ(d.zoom, 1.0f);
    EXPECT_EQ(d.fov_degrees, 30.0f);
    EXPECT_EQ(d.max_point_size, 3.0f);
    EXPECT_EQ(d.smooth_slope, 2.0f);
    EXPECT_EQ(d.line_width, 1.0f);
    EXPECT_EQ(d.dark_tone, 0.6f);
    EXPECT_EQ(d.refinement_budget, 262144u);
    EXPECT_EQ(d.constant_tone, kLightingTone);
    for (float c : d.background) EXPECT_EQ(c, 1.0f);
    EXPECT_TRUE(d.relevance_update);
    EXPECT_TRUE(d.silhouettes);
}

TEST(FrameConfig, ZeroFieldsResolveToDefaultsAndDefaultsResolveToThemselves) {
    FrameConfig zero;
    zero.width = zero.height = 0;
    zero.zoom = zero.max_point_size = zero.line_width = 0;
    FrameConfig out;
    ASSERT_TRUE(resolve_frame_config(zero, &out).ok());
    EXPECT_EQ(out.width, 640);
    EXPECT_EQ(out.height, 480);
    EXPECT_EQ(out.zoom, 1.0f);
    EXPECT_EQ(out.max_point_size, 3.0f);
    EXPECT_EQ(out.line_width, 1.0f);
    FrameConfig same;
    ASSERT_TRUE(resolve_frame_config(FrameConfig(), &same).ok());
    EXPECT_EQ(same.width, out.width);
    EXPECT_EQ(same.height, out.height);
    EXPECT_EQ(same.zoom, out.zoom);
    EXPECT_EQ(same.fov_degrees, out.fov_degrees);
    EXPECT_EQ(same.max_point_size, out.max_point_size);
    EXPECT_EQ(same.smooth_slope, out.smooth_slope);
    EXPECT_EQ(same.line_width, out.line_width);
    EXPECT_EQ(same.dark_tone, out.dark_tone);
    EXPECT_EQ(same.refinement_budget, out.refinement_budget);
}

TEST(FrameConfig, ValuesOutsideTheirRangeAreRejectedByName) {
    struct Case {
        const char* field;
        void (*set)(FrameConfig*);
    };
    const Case cases[] = {
        {"width", [](FrameConfig* c) { c->width = kFrameSettings.width.max + 1; }},
        {"height", [](FrameConfig* c) { c->height = -5; }},
        {"zoom", [](FrameConfig* c) { c->zoom = std::nanf(""); }},
        {"pitch_degrees", [](FrameConfig* c) { c->pitch_degrees = 91.0f; }},
        {"constant_tone", [](FrameConfig* c) { c->constant_tone = 1.5f; }},
        {"max_point_size", [](FrameConfig* c) { c->max_point_size = 100.0f; }},
        {"dark_tone", [](FrameConfig* c) { c->dark_tone = -0.1f; }},
        {"refinement_budget",
         [](FrameConfig* c) { c->refinement_budget = kFrameSettings.refinement_budget.max + 1; }},
        {"background", [](FrameConfig* c) { c->background[1] = 2.0f; }},
        {"particle_budget",
         [](FrameConfig* c) { c->particle_budget = kFrameSettings.particle_budget.max + 1; }},
    };
    for (const Case& k : cases) {
        FrameConfig in;
        k.set(&in);
        FrameConfig out;
        out.width = 123;
        const Status st = resolve_frame_config(in, &out);
        EXPECT_EQ(st.code, StatusCode::invalid_argument) << k.field;
        EXPECT_NE(std::strstr(st.message, k.field), nullptr) << st.message;
        EXPECT_EQ(out.width, 123) << "out is left unchanged on failure";
    }
}

TEST(FrameConfig, CDescriptionResolvesThroughTheSameTable) {
    stipple_player_desc zero = {};
    stipple_player_desc d;
    ASSERT_EQ(stipple_player_desc_resolve(&zero, &d), STIPPLE_OK);
    const FrameConfig c = default_frame_config();
    EXPECT_EQ(d.width, c.width);
    EXPECT_EQ(d.height, c.height);
    EXPECT_EQ(d.zoom, c.zoom);
    EXPECT_EQ(d.max_point_size, c.max_point_size);
    EXPECT_EQ(d.dark_tone_set, 1);
    EXPECT_EQ(d.dark_tone, c.dark_tone);
    EXPECT_EQ(d.refinement_budget, int(c.refinement_budget));
    EXPECT_EQ(d.background_set, 1);
    EXPECT_EQ(d.background_rgb, 0xFFFFFFu);
    EXPECT_EQ(d.use_constant_tone, 0);
    stipple_player_desc again;  // a resolved description resolves to itself
    ASSERT_EQ(stipple_player_desc_resolve(&d, &again), STIPPLE_OK);
    EXPECT_EQ(std::memcmp(&again, &d, sizeof(d)), 0);

    stipple_player_desc none = {};
    none.refinement_budget = -1;
    none.background_set = 1;
    none.background_rgb = 0x808080;
    ASSERT_EQ(stipple_player_desc_resolve(&none, &d), STIPPLE_OK);
    EXPECT_EQ(d.refinement_budget, -1);
    EXPECT_EQ(d.background_rgb, 0x808080u);

    stipple_player_desc bad = {};
    bad.width = 99999;
    EXPECT_EQ(stipple_player_desc_resolve(&bad, &d), STIPPLE_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::strstr(stipple_last_error(), "width"), nullptr) << stipple_last_error();
}

void* no_gl(const char*) {
    return nullptr;
}

TEST(FrameConfig, PlayerCreateRejectsOutOfRangeSettingsBeforeAnyGlCall) {
    const std::string path =
        test::baked_asset("assets/stretch_tube/stretch_tube.gltf", "--points 3000");
    ASSERT_FALSE(path.empty());
    stipple_asset* asset = nullptr;
    ASSERT_EQ(stipple_asset_load_file(path.c_str(), &asset), STIPPLE_OK) << stipple_last_error();
    stipple_player_desc desc = {};
    desc.get_proc_address = no_gl;
    desc.dark_tone_set = 1;
    desc.dark_tone = 1.5f;
    stipple_player* player = nullptr;
    EXPECT_EQ(stipple_player_create(asset, &desc, &player), STIPPLE_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(player, nullptr);
    desc.dark_tone = 0.5f;  // in range: now the missing GL entry points fail
    EXPECT_EQ(stipple_player_create(asset, &desc, &player), STIPPLE_ERROR_GL);
    stipple_asset_destroy(asset);
}

TEST(RuntimeStatus, AnAllocationThatFailsAtLoadIsOutOfMemory) {
    const uint8_t byte = 0;
    const size_t huge = size_t(1) << 46;  // 64 TiB: more than any test machine can give
    Asset a;
    const Status st = load_asset_memory(&byte, huge, &a);
    EXPECT_EQ(st.code, StatusCode::out_of_memory) << st.message;
    EXPECT_EQ(st.error, LoadError::out_of_memory);
    stipple_asset* asset = nullptr;
    EXPECT_EQ(stipple_asset_load_memory(&byte, huge, &asset), STIPPLE_ERROR_OUT_OF_MEMORY);
}

TEST(RuntimeStatus, LoadErrorsMapOntoStatusCodes) {
    EXPECT_EQ(status_code_of(LoadError::io_error), StatusCode::io_error);
    EXPECT_EQ(status_code_of(LoadError::unsupported_version), StatusCode::unsupported_version);
    EXPECT_EQ(status_code_of(LoadError::out_of_memory), StatusCode::out_of_memory);
    for (LoadError e :
         {LoadError::bad_magic, LoadError::truncated, LoadError::checksum_mismatch,
          LoadError::malformed_section, LoadError::out_of_range, LoadError::bad_value})
        EXPECT_EQ(status_code_of(e), StatusCode::bad_asset) << load_error_name(e);
}

}  // namespace
}  // namespace stipple
