// The looks (runtime/style.h) drawn by the pipeline on a baked torus whose LooksView the test
// fills itself (arrays it owns): each style changes the frame and is deterministic, dots take
// the point colours (refinement points their hosts'), toon fills with the part colour, a
// transparent part shows the opaque part behind it (thesis §7.4), crease lines draw (§8.2),
// and the tone curve moves the measured tone.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "runtime/frame_pipeline.h"
#include "runtime/silhouette.h"
#include "tests/common/fixtures.h"

namespace {

using namespace stipple;
using namespace stipple::test;

constexpr int kW = 240, kH = 180;

struct Frame {
    std::vector<uint8_t> rgba;
    std::vector<float> depth;  // the mesh pass's window depth (1: nothing filled)
    size_t pixels() const { return size_t(kW) * kH; }
    float luminance(size_t i) const {
        return (0.299f * rgba[i * 4] + 0.587f * rgba[i * 4 + 1] + 0.114f * rgba[i * 4 + 2]) / 255;
    }
};

size_t changed_pixels(const Frame& a, const Frame& b) {
    size_t n = 0;
    for (size_t i = 0; i < a.pixels(); ++i)
        n += a.rgba[i * 4] != b.rgba[i * 4] || a.rgba[i * 4 + 1] != b.rgba[i * 4 + 1] ||
             a.rgba[i * 4 + 2] != b.rgba[i * 4 + 2];
    return n;
}

class StyleLooks : public ::testing::Test {
  protected:
    void SetUp() override {
        std::string error;
        ASSERT_TRUE(gl_.open(&error)) << error;
        const std::string path = baked_asset("assets/torus.obj", "--points 10000");
        ASSERT_TRUE(load_baked(path, &asset_, &error)) << error;
        config_.width = kW;
        config_.height = kH;
        config_.depth_readback = true;
    }
    // One frame of the rest pose with `c`; `view` (if set) is applied after init through
    // pipeline_set_view, as a per-frame change.
    Frame render(const FrameConfig& c, const FrameConfig* view = nullptr) {
        auto p = std::make_unique<Pipeline>();
        Frame f;
        const Status st = pipeline_init(p.get(), asset_, gl_.gl(), c);
        EXPECT_TRUE(st.ok()) << st.message;
        if (!st.ok()) return f;
        if (view) {
            EXPECT_TRUE(pipeline_set_view(p.get(), *view).ok());
        }
        pipeline_frame(p.get(), -1, 0.0f, nullptr);
        last_refined_ = p->refined_count;
        f.rgba.assign(f.pixels() * 4, 0);
        renderer_read_color(&p->renderer, f.rgba.data());
        std::vector<float> scratch(f.pixels() * 4);
        f.depth.assign(f.pixels(), 0.0f);
        renderer_read_depth(&p->renderer, scratch.data(), f.depth.data());
        pipeline_destroy(p.get());
        return f;
    }
    FrameConfig styled(Style s) const {
        FrameConfig c = config_;
        c.style = s;
        return c;
    }
    // Splits the torus in two parts by the plane through its centre facing the camera (the
    // orbit camera at yaw 0, pitch 0 looks down -z): part 0 the near half, part 1 the far one.
    void split_parts(uint8_t near_flags) {
        const MeshView& m = asset_.mesh;
        float lo = 1e30f, hi = -1e30f;
        for (uint32_t v = 0; v < m.vertex_count; ++v) {
            lo = std::min(lo, m.positions[v * 3 + 2]);
            hi = std::max(hi, m.positions[v * 3 + 2]);
        }
        const float centre = 0.5f * (lo + hi);
        parts_.resize(m.triangle_count);
        for (uint32_t t = 0; t < m.triangle_count; ++t) {
            float z = 0.0f;
            for (int c = 0; c < 3; ++c) z += m.positions[m.indices[t * 3 + c] * 3 + 2] / 3.0f;
            parts_[t] = z > centre ? 0 : 1;
        }
        flags_ = {near_flags, 0};
        asset_.looks.part_count = 2;
        asset_.looks.triangle_part = parts_.data();
        asset_.looks.part_flags = flags_.data();
        asset_.looks.part_colour = part_colours_;
    }

    HeadlessGl gl_;
    uint32_t last_refined_ = 0;  // refinement points of the last render
    Asset asset_;
    FrameConfig config_;
    std::vector<uint16_t> parts_;
    std::vector<uint8_t> flags_, point_colours_;
    std::vector<uint32_t> creases_;
    uint8_t part_colours_[8] = {0, 0, 255, 255, 0, 0, 255, 255};  // both parts blue
};

TEST_F(StyleLooks, EveryStyleChangesTheFrameAndIsDeterministic) {
    const Frame classic = render(config_);
    ASSERT_FALSE(classic.rgba.empty());
    for (Style s : {Style::toon, Style::colour, Style::transparent}) {
        const Frame a = render(styled(s)), b = render(styled(s));
        ASSERT_FALSE(a.rgba.empty());
        EXPECT_EQ(changed_pixels(a, b), 0u) << style_name(s) << ": two renders differ";
        EXPECT_GT(changed_pixels(a, classic), 200u) << style_name(s) << " looks like classic";
        // A per-frame change through pipeline_set_view draws the same frame as an init.
        const FrameConfig view = styled(s);
        const Frame switched = render(config_, &view);
        EXPECT_EQ(changed_pixels(a, switched), 0u) << style_name(s) << " via pipeline_set_view";
    }
}

TEST_F(StyleLooks, ColourDotsTakeThePointColourAndRefinementPointsTheirHosts) {
    config_.silhouettes = false;
    point_colours_.assign(size_t(asset_.points.point_count) * 4, 0);
    for (size_t i = 0; i < point_colours_.size(); i += 4) point_colours_[i] = 255;  // red
    for (size_t i = 3; i < point_colours_.size(); i += 4) point_colours_[i] = 255;
    asset_.looks.point_colour = point_colours_.data();
    for (float zoom : {1.0f, 8.0f}) {  // 8: the refinement's extra points draw too
        FrameConfig c = styled(Style::colour);
        c.zoom = zoom;
        const Frame f = render(c);
        size_t red = 0, dark = 0;
        for (size_t i = 0; i < f.pixels(); ++i) {
            const uint8_t* p = &f.rgba[i * 4];
            red += p[0] > 200 && p[1] < 120 && p[2] < 120;
            dark += p[0] < 100 && p[1] < 100 && p[2] < 100;
        }
        EXPECT_GT(red, 300u) << "zoom " << zoom;
        if (zoom > 1.0f) {
            EXPECT_GT(last_refined_, 100u) << "the close-up draws extra points";
        }
        EXPECT_EQ(dark, 0u) << "zoom " << zoom << ": black dots left (silhouettes are off)";
    }
}

TEST_F(StyleLooks, ToonFillsWithThePartColourInBandsAndDarkerDots) {
    split_parts(0);
    config_.silhouettes = false;
    for (int bands : {2, 3}) {
        FrameConfig c = styled(Style::toon);
        c.toon_bands = bands;
        const Frame f = render(c);
        size_t blue = 0, ink = 0, histogram[256] = {};
        for (size_t i = 0; i < f.pixels(); ++i) {
            const uint8_t* p = &f.rgba[i * 4];
            if (p[0] != 0 || p[1] != 0 || p[2] == 0) continue;
            ++blue;
            ++histogram[p[2]];
            ink += p[2] <= 110;  // dots: the blue times toon_ink 0.4 (102), edges blended
        }
        EXPECT_GT(blue, size_t(f.pixels() / 20)) << bands << " bands";
        EXPECT_GT(ink, 50u) << "darker dots over the fill";
        // The fill's levels: blues that cover more than 3% of the blue pixels (antialiased dot
        // edges spread over many values, each rare).
        int levels = 0;
        for (int b = 111; b < 256; ++b) levels += histogram[b] > blue * 3 / 100;
        EXPECT_EQ(levels, bands) << "one fill level per band";
    }
}

// Thesis §7.4: the near half is transparent, the far half opaque; the near half's dots stay.
TEST_F(StyleLooks, ATransparentPartShowsWhatLiesBehindIt) {
    split_parts(kPartTransparent);
    config_.silhouettes = false;
    const Frame classic = render(config_);
    const Frame clear = render(styled(Style::transparent));
    size_t seen_through = 0, nearer = 0, covered = 0, ink_classic = 0, ink_clear = 0;
    for (size_t i = 0; i < classic.pixels(); ++i) {
        if (classic.depth[i] >= 1.0f) continue;
        ++covered;
        nearer += clear.depth[i] + 1e-6f < classic.depth[i];
        if (clear.depth[i] > classic.depth[i] + 1e-4f) {
            ++seen_through;
            ink_classic += classic.luminance(i) < 0.5f;
            ink_clear += clear.luminance(i) < 0.5f;
        }
    }
    EXPECT_EQ(nearer, 0u) << "the transparent style never adds surface in front";
    EXPECT_GT(seen_through, covered / 10) << "the far half shows through the near half";
    EXPECT_GT(ink_classic, 20u) << "the near half's dots are drawn in classic";
    EXPECT_GT(ink_clear, ink_classic) << "... and the far half's dots are added behind them";
    // Without marked parts the whole mesh is transparent: no fill at all, dots remain.
    asset_.looks = LooksView();
    const Frame all = render(styled(Style::transparent));
    size_t filled = 0, ink = 0;
    for (size_t i = 0; i < all.pixels(); ++i) {
        filled += all.depth[i] < 1.0f;
        ink += all.luminance(i) < 0.5f;
    }
    EXPECT_EQ(filled, 0u);
    EXPECT_GT(ink, 100u);
}

TEST_F(StyleLooks, CreaseLinesDrawBesideSilhouettesUnlessTurnedOff) {
    config_.silhouettes = false;
    const auto dark = [](const Frame& f) {
        size_t n = 0;
        for (size_t i = 0; i < f.pixels(); ++i) n += f.luminance(i) < 0.5f;
        return n;
    };
    const Frame none = render(config_);
    // Every fourth edge of the mesh as a crease.
    for (uint32_t e = 0; e < asset_.edges.edge_count; e += 4)
        creases_.insert(creases_.end(), asset_.edges.edges + e * 4, asset_.edges.edges + e * 4 + 4);
    asset_.looks.crease_count = uint32_t(creases_.size() / 4);
    asset_.looks.creases = creases_.data();
    const Frame with = render(config_);
    FrameConfig off = config_;
    off.creases = false;
    const Frame without = render(off);
    EXPECT_GT(dark(with), dark(none) + dark(none) / 4) << "crease lines add ink";
    EXPECT_EQ(changed_pixels(without, none), 0u) << "creases off: the frame without creases";
    for (Style s : {Style::toon, Style::colour, Style::transparent}) {
        FrameConfig c = styled(s);
        c.silhouettes = false;
        const Frame a = render(c);
        c.creases = false;
        EXPECT_GT(changed_pixels(a, render(c)), 100u) << style_name(s) << " draws creases";
    }
}

TEST(CreaseLines, DrawnWhereAtLeastOneFaceLooksAtTheEye) {
    const float positions[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    const uint32_t creases[12] = {0, 1, 0, 1, 1, 2, 1, 2, 2, 3, 2, 0xFFFFFFFFu};
    LooksView looks;
    looks.crease_count = 3;
    looks.creases = creases;
    const uint8_t front[3] = {0, 1, 0};  // faces 0 and 2 turned away
    float lines[18];
    // Edge 0: faces 0 and 1 (one toward the eye); edge 1: faces 1 and 2; edge 2: face 2 only.
    EXPECT_EQ(crease_lines(looks, front, positions, lines), 2u);
    EXPECT_EQ(lines[3], 1.0f);  // edge 0 ends at vertex 1
    EXPECT_EQ(lines[6 + 0], 1.0f);
    const uint8_t none[3] = {0, 0, 0};
    EXPECT_EQ(crease_lines(looks, none, positions, lines), 0u);
}

TEST_F(StyleLooks, TheToneCurveMovesTheMeasuredTone) {
    config_.silhouettes = false;
    config_.constant_tone = 0.5f;
    const auto darkness = [](const Frame& f) {
        double ink = 0;
        size_t n = 0;
        for (size_t i = 0; i < f.pixels(); ++i)
            if (f.depth[i] < 1.0f) ink += 1.0 - f.luminance(i), ++n;
        return n ? ink / double(n) : 0.0;
    };
    const double base = darkness(render(config_));
    FrameConfig c = config_;
    c.tone_gamma = 2.0f;  // 0.5 -> 0.25
    const double lighter = darkness(render(c));
    c.tone_gamma = 0.5f;  // 0.5 -> 0.71
    const double darker = darkness(render(c));
    c.tone_gamma = 1.0f;
    c.constant_tone = 0.3f;
    const double low = darkness(render(c));
    c.tone_contrast = 2.0f;  // 0.3 -> 0.1
    const double low_contrast = darkness(render(c));
    ASSERT_GT(base, 0.2);
    EXPECT_NEAR(lighter / base, 0.5, 0.15) << "gamma 2 halves tone 0.5";
    EXPECT_GT(darker, base * 1.2);
    EXPECT_LT(low_contrast, low * 0.6) << "contrast 2 pushes 0.3 toward white";
}

}  // namespace
