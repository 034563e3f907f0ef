// The depth pass's simplified occluder (issue 9 item 5; runtime/renderer_occluder.cpp): the
// dots drawn over the occluder's depth pass against those drawn over the full mesh's, on
// CesiumMan (walking) and the horse, from several views. Each frame is drawn by
// pipeline_frame (the occluder), then its depth pass again with the full mesh; a dot's
// visibility is the dots shader's test (runtime/renderer_shaders.h kPointVs, on the CPU:
// pipeline_visible_dots) replayed on the two depth copies. Wrongly hidden dots (drawn over the full
// mesh, not over the occluder) must be at most 0.5% of the drawn ones; wrongly shown ones at most
// kShownBound.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <string>
#include <vector>

#include "runtime/frame_pipeline.h"
#include "tests/common/pipeline_view.h"

namespace {

using namespace stipple::test;

constexpr double kHiddenBound = 0.005;
constexpr double kShownBound = 0.02;

// The ids of the frame's dots that the dots shader's visibility test passes on `depth`
// (pipeline_visible_dots: the centre pixel, else the depth interpolated around it), sorted.
std::vector<uint64_t> visible(const stipple::Pipeline& p, const std::vector<float>& depth) {
    std::vector<stipple::VisibleDot> dots(p.point_capacity);
    dots.resize(
        stipple::pipeline_visible_dots(p, depth.data(), dots.data(), uint32_t(dots.size())));
    std::vector<uint64_t> ids;
    for (const stipple::VisibleDot& d : dots) ids.push_back(d.id);
    std::sort(ids.begin(), ids.end());
    return ids;
}

// How many of `a` are not in `b` (both sorted).
uint64_t missing(const std::vector<uint64_t>& a, const std::vector<uint64_t>& b) {
    std::vector<uint64_t> d;
    std::set_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(d));
    return d.size();
}

struct Counts {
    uint64_t drawn = 0, hidden = 0, shown = 0;
};

// `share`: the occluder's triangles as a share of the mesh's, at most (the bake's ratio).
void check_asset(const std::string& input, const std::string& options, int clip, double share) {
    SCOPED_TRACE(input);
    PipelineView view;
    std::string error;
    ASSERT_TRUE(view.open(baked_asset(input, options), 640, 480, &error)) << error;
    const stipple::Asset& asset = view.asset();
    ASSERT_NE(asset.occluder_indices, nullptr);
    EXPECT_LE(double(asset.occluder_triangle_count), share * double(asset.mesh.triangle_count));
    stipple::Pipeline* p = view.pipeline();
    ASSERT_TRUE(p->renderer.occluder_enabled);
    const CameraView cameras[] = {{1.0f, 0.0f, 0.0f},     {1.0f, 90.0f, 20.0f},
                                  {2.5f, 200.0f, -30.0f}, {0.6f, -60.0f, 60.0f},
                                  {4.0f, 30.0f, 5.0f},    {1.5f, 135.0f, -10.0f}};
    Counts total;
    for (const CameraView& v : cameras) {
        ASSERT_TRUE(view.set_view(v));
        stipple::pipeline_frame(p, clip, 0.4f, nullptr);
        const std::vector<uint64_t> occ = visible(*p, view.read_depth());
        p->renderer.occluder_enabled = false;
        stipple::renderer_draw_mesh(&p->renderer, p->view_projection, p->vertex_positions.get(),
                                    p->asset->mesh.vertex_count);
        p->renderer.occluder_enabled = true;
        const std::vector<uint64_t> full = visible(*p, view.read_depth());
        Counts c;
        c.drawn = full.size();
        c.hidden = missing(full, occ);
        c.shown = missing(occ, full);
        std::printf(
            "occluder %s zoom %.1f yaw %.0f pitch %.0f: %llu dots drawn, %llu wrongly "
            "hidden, %llu wrongly shown\n",
            input.c_str(), double(v.zoom), double(v.yaw_degrees), double(v.pitch_degrees),
            (unsigned long long)c.drawn, (unsigned long long)c.hidden, (unsigned long long)c.shown);
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
}

TEST(Occluder, SameDotsAsTheFullMesh) {
    // The horse (96,966 triangles, each below a pixel at 1280x720: the case the occluder is
    // for) at 10%: 0.11% of the dots wrongly hidden, 0.20% wrongly shown over these views
    // (the bend rig's walk, checked by hand: 0.30% and 0.27%, worst view 0.41% and 1.02%).
    check_asset("assets/Horse/horse.ply", "--up z --occluder 0.1", -1, 0.1);
    // CesiumMan has 4,672 triangles: at 10% (466) or 30% its coarse outline spans the gaps
    // between legs and arms and hides dots of the far limbs (3.3% and 1.1% wrongly hidden on
    // the walk with the deviation measured over its poses, docs/measurements-after.md), which
    // no push along the view can undo; at 60% 0.014%. The occluder is only worth baking for
    // meshes much finer than the screen.
    check_asset("assets/CesiumMan/CesiumMan.glb", "--occluder 0.6", 0, 0.6);
}

// Without the frame setting the depth pass draws the full mesh.
TEST(Occluder, OffWhenTheConfigSaysSo) {
    stipple::FrameConfig config;
    config.width = 64;
    config.height = 48;
    config.occluder = false;
    PipelineView view;
    std::string error;
    ASSERT_TRUE(
        view.open(baked_asset("assets/Horse/horse.ply", "--up z --occluder 0.1"), config, &error))
        << error;
    EXPECT_FALSE(view.pipeline()->renderer.occluder_enabled);
    EXPECT_EQ(view.pipeline()->renderer.occluder_program, 0u);
}

}  // namespace
