// The depth pass's simplified occluder (issue 9 item 5; runtime/renderer_occluder.cpp): the
// dots drawn over the occluder's depth pass against those drawn over the full mesh's, on
// CesiumMan (walking) and the horse, from several views. Each frame is drawn by
// pipeline_frame (the occluder), then its depth pass again with the full mesh; a dot's
// visibility is the dots shader's test (runtime/renderer.cpp kPointVs) replayed on the two
// depth copies. Wrongly hidden dots (drawn over the full mesh, not over the occluder) must be
// at most 0.5% of the drawn ones; wrongly shown ones at most kShownBound.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "runtime/frame_pipeline.h"
#include "tests/common/fixtures.h"

namespace {

using namespace stipple::test;

constexpr double kHiddenBound = 0.005;
constexpr double kShownBound = 0.02;

std::vector<float> read_depth(stipple::Pipeline* p) {
    const size_t n = size_t(p->config.width) * size_t(p->config.height);
    std::vector<float> depth(n), scratch(n * 4);
    stipple::renderer_read_depth(&p->renderer, scratch.data(), depth.data());
    return depth;
}

// The dots shader's visibility test for each of the frame's dots.
std::vector<uint8_t> visible(const stipple::Pipeline& p, const std::vector<float>& depth) {
    const int w = p.config.width, h = p.config.height;
    std::vector<uint8_t> out(p.points_drawn, 0);
    for (uint32_t i = 0; i < p.points_drawn; ++i) {
        if (p.draw_sizes[i] <= 0.0f) continue;
        const float* x = p.draw_positions.get() + size_t(i) * 3;
        const glm::vec4 clip = p.view_projection * glm::vec4(x[0], x[1], x[2], 1.0f);
        if (clip.w <= 0.0f) continue;
        const glm::vec3 ndc = glm::vec3(clip) / clip.w;
        const int px = int(std::floor((ndc.x * 0.5f + 0.5f) * float(w)));
        const int py = int(std::floor((ndc.y * 0.5f + 0.5f) * float(h)));
        if (px < 0 || py < 0 || px >= w || py >= h) continue;
        const float mesh = depth[size_t(py) * size_t(w) + size_t(px)];
        out[i] = mesh < 1.0f && ndc.z * 0.5f + 0.5f <= mesh + 1e-5f;
    }
    return out;
}

struct Counts {
    uint64_t drawn = 0, hidden = 0, shown = 0;
};

// `share`: the occluder's triangles as a share of the mesh's, at most (the bake's ratio).
void check_asset(const std::string& input, const std::string& options, int clip, double share) {
    SCOPED_TRACE(input);
    stipple::Asset asset;
    std::string error;
    ASSERT_TRUE(load_baked(baked_asset(input, options), &asset, &error)) << error;
    ASSERT_NE(asset.occluder_indices, nullptr);
    EXPECT_LE(double(asset.occluder_triangle_count), share * double(asset.mesh.triangle_count));
    HeadlessGl gl;
    ASSERT_TRUE(gl.open(&error)) << error;
    stipple::FrameConfig config;
    config.width = 640;
    config.height = 480;
    config.depth_readback = true;
    auto p = std::make_unique<stipple::Pipeline>();
    ASSERT_TRUE(stipple::pipeline_init(p.get(), asset, gl.gl(), config).ok());
    ASSERT_TRUE(p->renderer.occluder_enabled);
    const float views[][3] = {{1.0f, 0.0f, 0.0f},    {1.0f, 90.0f, 20.0f}, {2.5f, 200.0f, -30.0f},
                              {0.6f, -60.0f, 60.0f}, {4.0f, 30.0f, 5.0f},  {1.5f, 135.0f, -10.0f}};
    Counts total;
    for (const auto& v : views) {
        stipple::FrameConfig view = p->config;
        view.zoom = v[0];
        view.yaw_degrees = v[1];
        view.pitch_degrees = v[2];
        ASSERT_TRUE(stipple::pipeline_set_view(p.get(), view).ok());
        stipple::pipeline_frame(p.get(), clip, 0.4f, nullptr);
        const std::vector<uint8_t> occ = visible(*p, read_depth(p.get()));
        p->renderer.occluder_enabled = false;
        stipple::renderer_draw_mesh(&p->renderer, p->view_projection, p->vertex_positions.get(),
                                    p->asset->mesh.vertex_count);
        p->renderer.occluder_enabled = true;
        const std::vector<uint8_t> full = visible(*p, read_depth(p.get()));
        Counts c;
        for (size_t i = 0; i < occ.size(); ++i) {
            c.drawn += full[i];
            c.hidden += full[i] && !occ[i];
            c.shown += !full[i] && occ[i];
        }
        std::printf(
            "occluder %s zoom %.1f yaw %.0f pitch %.0f: %llu dots drawn, %llu wrongly "
            "hidden, %llu wrongly shown\n",
            input.c_str(), double(v[0]), double(v[1]), double(v[2]), (unsigned long long)c.drawn,
            (unsigned long long)c.hidden, (unsigned long long)c.shown);
        ASSERT_GT(c.drawn, 100u);
        EXPECT_LE(double(c.hidden), kHiddenBound * double(c.drawn));
        EXPECT_LE(double(c.shown), kShownBound * double(c.drawn));
        total.drawn += c.drawn;
        total.hidden += c.hidden;
        total.shown += c.shown;
    }
    std::printf(
        "occluder %s: %u of %u triangles, deviation %g; all views: %llu drawn, %.3f%% "
        "wrongly hidden, %.3f%% wrongly shown\n",
        input.c_str(), asset.occluder_triangle_count, asset.mesh.triangle_count,
        double(asset.occluder_deviation), (unsigned long long)total.drawn,
        100.0 * double(total.hidden) / double(total.drawn),
        100.0 * double(total.shown) / double(total.drawn));
    stipple::pipeline_destroy(p.get());
}

TEST(Occluder, SameDotsAsTheFullMesh) {
    // The horse (96,966 triangles, each below a pixel at 1280x720: the case the occluder is
    // for) at 10%: 0.11% of the dots wrongly hidden, 0.20% wrongly shown over these views
    // (the bend rig's walk, checked by hand: 0.30% and 0.27%, worst view 0.41% and 1.02%).
    check_asset("assets/Horse/horse.ply", "--up z --occluder 0.1", -1, 0.1);
    // CesiumMan has 4,672 triangles: at 10% (466) or 30% its coarse outline spans the gaps
    // between legs and arms and hides dots of the far limbs (8.6% and 3.9% wrongly hidden on
    // the walk, docs/measurements-after.md), which no push along the view can undo; at 60%
    // 0.07%. The occluder is only worth baking for meshes much finer than the screen.
    check_asset("assets/CesiumMan/CesiumMan.glb", "--occluder 0.6", 0, 0.6);
}

// Without the frame setting the depth pass draws the full mesh.
TEST(Occluder, OffWhenTheConfigSaysSo) {
    stipple::Asset asset;
    std::string error;
    ASSERT_TRUE(
        load_baked(baked_asset("assets/Horse/horse.ply", "--up z --occluder 0.1"), &asset, &error))
        << error;
    HeadlessGl gl;
    ASSERT_TRUE(gl.open(&error)) << error;
    stipple::FrameConfig config;
    config.width = 64;
    config.height = 48;
    config.occluder = false;
    auto p = std::make_unique<stipple::Pipeline>();
    ASSERT_TRUE(stipple::pipeline_init(p.get(), asset, gl.gl(), config).ok());
    EXPECT_FALSE(p->renderer.occluder_enabled);
    EXPECT_EQ(p->renderer.occluder_program, 0u);
    stipple::pipeline_destroy(p.get());
}

}  // namespace
