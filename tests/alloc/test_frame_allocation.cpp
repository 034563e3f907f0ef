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
#include "runtime/frame_pipeline.h"
#include "tests/alloc/alloc_counter.h"
#include "tests/common/fixtures.h"

using stipple::test::g_allocations;
using stipple::test::g_counting;

namespace {

TEST(FrameAllocation, FramesAllocateNothingAfterLoad) {
    stipple::Asset asset;
    std::string error;
    ASSERT_TRUE(stipple::test::load_baked(
        stipple::test::baked_asset("assets/CesiumMan/CesiumMan.glb", "--points 10000"), &asset,
        &error))
        << error;

    stipple::test::HeadlessGl gl;
    ASSERT_TRUE(gl.open(&error)) << error;
    auto pipeline = std::make_unique<stipple::Pipeline>();
    const stipple::Status init = stipple::pipeline_init(pipeline.get(), asset, gl.gl(), {});
    ASSERT_TRUE(init.ok()) << init.message;
    std::vector<uint8_t> rgba(640 * 480 * 4);
    stipple::pipeline_frame(pipeline.get(), 0, 0.0f, nullptr);  // first draw compiles shaders

    stipple::StageTimes times;
    g_allocations = 0;
    g_counting = true;
    for (int f = 0; f < 200; ++f) {
        stipple::pipeline_frame(pipeline.get(), 0, float(f) / 30.0f, &times);
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
        ASSERT_TRUE(stipple::pipeline_set_view(pipeline.get(), view).ok());
        stipple::pipeline_frame(pipeline.get(), 0, float(f) / 30.0f, &times);
        stipple::renderer_read_color(&pipeline->renderer, rgba.data());
        most_refined = std::max(most_refined, pipeline->refined_count);
    }
    g_counting = false;
    EXPECT_EQ(g_allocations.load(), 0);
    EXPECT_GT(most_refined, 10000u);  // the refinement did real work

    stipple::pipeline_destroy(pipeline.get());
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

}  // namespace
