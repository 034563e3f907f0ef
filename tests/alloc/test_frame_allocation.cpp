// A frame allocates nothing: every buffer is taken at load (pipeline_init). Counts global
// operator new calls over many frames of sampling, skinning, point stages and drawing.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <memory>
#include <new>
#include <string>

#include "platform/headless_context.h"
#include "runtime/app_frame.h"
#include "runtime/camera.h"
#include "runtime/frame_pipeline.h"
#include "tests/alloc/alloc_counter.h"
#include "tests/alloc/cesium_pipeline.h"
#include "tests/common/fixtures.h"

using stipple::test::g_allocations;
using stipple::test::g_counting;

namespace {

TEST(FrameAllocation, FramesAllocateNothingAfterLoad) {
    stipple::test::CesiumPipeline cesium;
    ASSERT_TRUE(stipple::test::open_cesium("--points 10000", {}, &cesium));
    stipple::Pipeline* pipeline = cesium.pipeline.get();
    std::vector<uint8_t> rgba(640 * 480 * 4);
    stipple::pipeline_frame(pipeline, 0, 0.0f, nullptr);  // first draw compiles shaders

    stipple::StageTimes times;
    g_allocations = 0;
    g_counting = true;
    for (int f = 0; f < 200; ++f) {
        stipple::pipeline_frame(pipeline, 0, float(f) / 30.0f, &times);
        stipple::renderer_read_color(&pipeline->renderer, rgba.data());
    }
    g_counting = false;
    EXPECT_EQ(g_allocations.load(), 0);
    EXPECT_GT(pipeline->points_drawn, 100u);  // the frames did real work

    // Close-ups, dark tones and zooming: the run-time refinement generates extra points into
    // memory taken at load, and changing the view takes none either.
    g_allocations = 0;
    g_counting = true;
    uint32_t most_refined = 0;
    for (int f = 0; f < 60; ++f) {
        stipple::FrameConfig view = pipeline->config;
        view.zoom = 1.0f + 15.0f * float(f) / 59.0f;
        view.constant_tone = 0.6f;
        ASSERT_TRUE(stipple::pipeline_set_view(pipeline, view).ok());
        stipple::pipeline_frame(pipeline, 0, float(f) / 30.0f, &times);
        stipple::renderer_read_color(&pipeline->renderer, rgba.data());
        most_refined = std::max(most_refined, pipeline->refined_count);
    }
    g_counting = false;
    EXPECT_EQ(g_allocations.load(), 0);
    EXPECT_GT(most_refined, 10000u);  // the refinement did real work

    stipple::pipeline_destroy(pipeline);
}

TEST(FrameAllocation, FramesWithStrokesAllocateNothing) {
    stipple::Asset asset;
    std::string error;
    ASSERT_TRUE(stipple::test::load_baked(
        stipple::test::baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 20000 --fur 3000"),
        &asset, &error))
        << error;
    ASSERT_GT(asset.strokes.stroke_count, 0u);
    stipple::test::HeadlessGl gl;
    ASSERT_TRUE(gl.open(&error)) << error;
    auto pipeline = std::make_unique<stipple::Pipeline>();
    const stipple::Status init = stipple::pipeline_init(pipeline.get(), asset, gl.gl(), {});
    ASSERT_TRUE(init.ok()) << init.message;
    std::vector<uint8_t> rgba(640 * 480 * 4);
    stipple::pipeline_frame(pipeline.get(), 0, 0.0f, nullptr);
    g_allocations = 0;
    g_counting = true;
    uint32_t most_triangles = 0;
    for (int f = 0; f < 60; ++f) {
        stipple::FrameConfig view = pipeline->config;
        view.zoom = 1.0f + 3.0f * float(f) / 59.0f;  // quality and subdivision change with scale
        ASSERT_TRUE(stipple::pipeline_set_view(pipeline.get(), view).ok());
        stipple::pipeline_frame(pipeline.get(), 0, float(f) / 30.0f, nullptr);
        stipple::renderer_read_color(&pipeline->renderer, rgba.data());
        most_triangles = std::max(most_triangles, pipeline->strokes.stats.triangles);
    }
    g_counting = false;
    EXPECT_EQ(g_allocations.load(), 0);
    EXPECT_GT(most_triangles, 3000u);  // the strokes were tessellated and drawn
    stipple::pipeline_destroy(pipeline.get());
}

// Three instances of one asset drawn into the application's framebuffer for 1,000 frames,
// with per-frame setting changes (lights, ink, silhouettes) between them: no allocation,
// counted by the global operator new and by the instances' allocator hook.
TEST(FrameAllocation, ThreeInstancesInTheApplicationsFrameAllocateNothing) {
    stipple::Asset asset;
    std::string error;
    ASSERT_TRUE(stipple::test::load_baked(
        stipple::test::baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 5000"), &asset,
        &error))
        << error;
    stipple::test::HeadlessGl gl;
    ASSERT_TRUE(gl.open(&error)) << error;
    const stipple::GlApi& g = gl.gl();
    constexpr int kW = 96, kH = 72;
    stipple::test::TestFramebuffer framebuffer;
    ASSERT_TRUE(framebuffer.create(g, kW, kH));
    stipple::FrameConfig config;
    config.width = kW;
    config.height = kH;
    // Their memory through an allocator hook that counts its calls.
    static std::atomic<long> hook_calls{0};
    stipple::Allocator hook;
    hook.allocate = [](size_t bytes, void*) -> void* {
        ++hook_calls;
        return std::malloc(bytes);
    };
    hook.release = [](void* p, void*) { std::free(p); };
    std::unique_ptr<stipple::Pipeline> instances[3];
    for (auto& p : instances) {
        p = std::make_unique<stipple::Pipeline>();
        ASSERT_TRUE(stipple::pipeline_init(p.get(), asset, g, config, hook).ok());
    }
    EXPECT_GT(hook_calls.load(), 30);  // the buffers came through the hook
    const stipple::OrbitCamera cam = stipple::orbit_camera(asset, instances[0]->config, nullptr);
    stipple::AppView view;
    view.view = cam.view;
    view.projection = cam.projection;
    view.viewport[2] = kW;
    view.viewport[3] = kH;
    // The first draw into the application's frame has the GL driver compile its pass variants
    // (llvmpipe allocates for that, through this counter too): once, before counting.
    for (auto& p : instances) stipple::pipeline_draw_into(p.get(), {}, view, nullptr);
    g_allocations = 0;
    hook_calls = 0;
    g_counting = true;
    uint32_t drawn = 0;
    for (int f = 0; f < 1000; ++f) {
        g.BindFramebuffer(GL_FRAMEBUFFER, framebuffer.fbo());
        g.DepthMask(GL_TRUE);
        g.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        for (int i = 0; i < 3; ++i) {
            stipple::FrameConfig settings = instances[i]->config;
            settings.ink[0] = float(f % 2);
            settings.silhouettes = f % 3 != 0;
            settings.lights[0].direction[0] = float(f % 5) - 2.0f;
            ASSERT_TRUE(stipple::pipeline_set_view(instances[i].get(), settings).ok());
            view.model[3][0] = 0.3f * float(i - 1);
            stipple::AnimationState state;
            state.clip = 0;
            state.time = float(f) / 30.0f + float(i);
            stipple::pipeline_draw_into(instances[i].get(), state, view, nullptr);
            drawn += instances[i]->points_drawn;
        }
    }
    g.Finish();
    g_counting = false;
    EXPECT_EQ(g_allocations.load(), 0);
    EXPECT_EQ(hook_calls.load(), 0);
    EXPECT_GT(drawn, 3000u * 20u);  // real frames
    for (auto& p : instances) stipple::pipeline_destroy(p.get());
}

}  // namespace
