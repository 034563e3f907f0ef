// The looks' names and settings (runtime/style.h, runtime/frame_config.h): one set of names for
// every API, the settings' defaults and limits, the tone curve, and each style through the C
// API (stipple_player_desc::style, stipple_player_set_style).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "platform/headless_context.h"
#include "runtime/frame_config.h"
#include "runtime/stipple.h"
#include "runtime/stipple_size.h"
#include "runtime/style.h"
#include "tests/common/fixtures.h"

namespace {

using namespace stipple;
using namespace stipple::test;

TEST(StyleNames, RoundTripForEveryStyleInEveryApi) {
    std::vector<std::string> seen;
    for (int i = 0; i < kStyleTotal; ++i) {
        const char* name = style_name(Style(i));
        EXPECT_EQ(find_style(name), i) << name;
        ASSERT_NE(stipple_style_name(i), nullptr);
        EXPECT_STREQ(stipple_style_name(i), name);
        EXPECT_EQ(stipple_find_style(name), i);
        EXPECT_NE(std::string(style_name_list()).find(name), std::string::npos) << name;
        for (const std::string& s : seen) EXPECT_NE(s, name);
        seen.push_back(name);
    }
    EXPECT_EQ(int(STIPPLE_STYLE_CLASSIC), int(Style::classic));
    EXPECT_EQ(int(STIPPLE_STYLE_TOON), int(Style::toon));
    EXPECT_EQ(int(STIPPLE_STYLE_COLOUR), int(Style::colour));
    EXPECT_EQ(int(STIPPLE_STYLE_TRANSPARENT), int(Style::transparent));
    EXPECT_EQ(find_style("color"), int(Style::colour));
    EXPECT_EQ(find_style("bogus"), -1);
    EXPECT_EQ(find_style(nullptr), -1);
    // The C API numbers the particle styles (issue 11) after these; far past them: none.
    EXPECT_EQ(stipple_style_name(100000), nullptr);
    EXPECT_EQ(stipple_style_name(-1), nullptr);
    EXPECT_STREQ(style_name(Style(99)), "unknown");
}

TEST(StyleSettings, DefaultsAreClassicAndTheIdentityCurve) {
    const FrameConfig d = default_frame_config();
    EXPECT_EQ(d.style, Style::classic);
    EXPECT_EQ(d.tone_gamma, 1.0f);
    EXPECT_EQ(d.tone_contrast, 1.0f);
    EXPECT_TRUE(d.creases);
    EXPECT_EQ(d.dark_tone, kFrameSettings.dark_tone.fallback);  // thesis §8.4's cap
    FrameConfig c;
    c.tone_gamma = c.tone_contrast = 0.0f;
    c.toon_bands = 0;
    FrameConfig r;
    ASSERT_TRUE(resolve_frame_config(c, &r).ok());
    EXPECT_EQ(r.tone_gamma, 1.0f) << "zero means the default";
    EXPECT_EQ(r.toon_bands, kFrameSettings.toon_bands.fallback);
    for (const auto& bad : std::vector<std::pair<const char*, void (*)(FrameConfig*)>>{
             {"style", [](FrameConfig* f) { f->style = Style(kStyleTotal); }},
             {"toon_bands", [](FrameConfig* f) { f->toon_bands = 4; }},
             {"tone_gamma", [](FrameConfig* f) { f->tone_gamma = 20.0f; }},
             {"tone_contrast", [](FrameConfig* f) { f->tone_contrast = -1.0f; }},
             {"toon_ink", [](FrameConfig* f) { f->toon_ink = 2.0f; }},
             {"fill channel", [](FrameConfig* f) { f->fill[1] = 1.5f; }}}) {
        FrameConfig f;
        bad.second(&f);
        const Status st = resolve_frame_config(f, &r);
        EXPECT_EQ(st.code, StatusCode::invalid_argument) << bad.first;
        EXPECT_NE(std::string(st.message).find(bad.first), std::string::npos) << st.message;
    }
}

TEST(ToneCurve, GammaAndContrastAroundTheIdentity) {
    SizeParams p;
    for (float t : {0.0f, 0.13f, 0.5f, 0.77f, 1.0f}) EXPECT_EQ(tone_curve(p, t), t);
    p.tone_gamma = 2.0f;
    EXPECT_FLOAT_EQ(tone_curve(p, 0.5f), 0.25f);
    EXPECT_LT(ink_for_tone(p, 0.5f), ink_for_tone(SizeParams(), 0.5f)) << "gamma > 1: lighter";
    p.tone_gamma = 1.0f;
    p.tone_contrast = 2.0f;
    EXPECT_FLOAT_EQ(tone_curve(p, 0.3f), 0.1f);
    EXPECT_FLOAT_EQ(tone_curve(p, 0.7f), 0.9f);
    EXPECT_EQ(tone_curve(p, 0.05f), 0.0f) << "clamped";
    EXPECT_EQ(tone_curve(p, 0.5f), 0.5f);
}

class StyleCApi : public ::testing::Test {
  protected:
    void SetUp() override {
        std::string error;
        ASSERT_TRUE(gl_.open(&error)) << error;
        const std::string path = baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 5000");
        ASSERT_EQ(stipple_asset_load_file(path.c_str(), &asset_), STIPPLE_OK);
        desc_.width = 160;
        desc_.height = 120;
        desc_.get_proc_address = platform::proc_loader(gl_.context());
    }
    void TearDown() override { stipple_asset_destroy(asset_); }
    std::vector<uint8_t> draw(const stipple_player_desc& d, int set_style = -1) {
        stipple_player* p = nullptr;
        std::vector<uint8_t> rgba;
        EXPECT_EQ(stipple_player_create(asset_, &d, &p), STIPPLE_OK) << stipple_last_error();
        if (!p) return rgba;
        if (set_style >= 0) {
            EXPECT_EQ(stipple_player_set_style(p, set_style, 1.0f, 1.0f, 1), STIPPLE_OK);
        }
        stipple_player_draw(p, 0, 0.3f);
        rgba.resize(size_t(d.width) * d.height * 4);
        stipple_player_read_rgba(p, rgba.data());
        stipple_player_destroy(p);
        return rgba;
    }
    HeadlessGl gl_;
    stipple_asset* asset_ = nullptr;
    stipple_player_desc desc_ = {};
};

size_t differing(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
    size_t n = 0;
    for (size_t i = 0; i + 3 < a.size() && i + 3 < b.size(); i += 4)
        n += a[i] != b[i] || a[i + 1] != b[i + 1] || a[i + 2] != b[i + 2];
    return n;
}

TEST_F(StyleCApi, EachStyleThroughTheDescAndBetweenFrames) {
    const std::vector<uint8_t> classic = draw(desc_);
    ASSERT_FALSE(classic.empty());
    for (int s = 1; s < kStyleTotal; ++s) {
        stipple_player_desc d = desc_;
        d.style = s;
        const std::vector<uint8_t> a = draw(d);
        EXPECT_GT(differing(a, classic), 100u) << stipple_style_name(s);
        EXPECT_EQ(differing(a, draw(desc_, s)), 0u)
            << stipple_style_name(s) << ": stipple_player_set_style draws what the desc does";
    }
    // Tone curve through the desc: gamma 3 lightens the frame.
    stipple_player_desc light = desc_;
    light.tone_gamma = 3.0f;
    const std::vector<uint8_t> lighter = draw(light);
    size_t dark_classic = 0, dark_lighter = 0;
    for (size_t i = 0; i < classic.size(); i += 4) {
        dark_classic += classic[i] < 128;
        dark_lighter += lighter[i] < 128;
    }
    EXPECT_LT(dark_lighter, dark_classic);
}

TEST_F(StyleCApi, BadLooksAreInvalidArguments) {
    stipple_player_desc d = desc_;
    d.style = 100000;  // past the looks and the particle styles after them
    stipple_player* p = nullptr;
    EXPECT_EQ(stipple_player_create(asset_, &d, &p), STIPPLE_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(stipple_last_error()).find("style"), std::string::npos);
    d = desc_;
    d.toon_bands = 7;
    EXPECT_EQ(stipple_player_create(asset_, &d, &p), STIPPLE_ERROR_INVALID_ARGUMENT);
    ASSERT_EQ(stipple_player_create(asset_, &desc_, &p), STIPPLE_OK);
    EXPECT_EQ(stipple_player_set_style(p, -1, 1, 1, 1), STIPPLE_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(stipple_player_set_style(p, 1, 50, 1, 1), STIPPLE_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(stipple_player_set_style(nullptr, 1, 1, 1, 1), STIPPLE_ERROR_INVALID_ARGUMENT);
    stipple_player_destroy(p);
    // resolve: every look field explicit.
    stipple_player_desc r = {};
    ASSERT_EQ(stipple_player_desc_resolve(&desc_, &r), STIPPLE_OK);
    EXPECT_EQ(r.style, 0);
    EXPECT_EQ(r.toon_bands, kFrameSettings.toon_bands.fallback);
    EXPECT_EQ(r.tone_gamma, 1.0f);
    EXPECT_EQ(r.tone_contrast, 1.0f);
    EXPECT_EQ(r.fill_set, 1);
    EXPECT_EQ(r.fill_rgb, 0x8CCC59u);
    EXPECT_EQ(r.no_creases, 0);
}

}  // namespace
