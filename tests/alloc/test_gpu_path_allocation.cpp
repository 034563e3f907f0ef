// Issue 9, item 4: the GPU path (runtime/gpu_stages.h) allocates nothing per frame either:
// 1,000 frames of the CesiumMan walk with place, relevance and size in the transform
// feedback pass, with view changes (zoom, tone) between them, counted by the global
// operator new.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "platform/headless_context.h"
#include "runtime/frame_pipeline.h"
#include "tests/alloc/alloc_counter.h"
#include "tests/alloc/cesium_pipeline.h"
#include "tests/common/fixtures.h"

using stipple::test::g_allocations;
using stipple::test::g_counting;

namespace {

TEST(FrameAllocation, GpuPathFramesAllocateNothing) {
    stipple::FrameConfig config;
    config.width = 160;
    config.height = 120;
    config.path = stipple::FramePath::gpu;
    stipple::test::CesiumPipeline cesium;
    ASSERT_TRUE(stipple::test::open_cesium("--points 10000", config, &cesium));
    stipple::Pipeline* pipeline = cesium.pipeline.get();
    std::vector<uint8_t> rgba(size_t(config.width) * size_t(config.height) * 4);
    stipple::pipeline_frame(pipeline, 0, 0.0f, nullptr);

    stipple::StageTimes times;
    g_allocations = 0;
    g_counting = true;
    for (int f = 0; f < 1000; ++f) {
        if (f % 100 == 0) {
            stipple::FrameConfig view = pipeline->config;
            view.zoom = 1.0f + float(f) / 250.0f;
            view.constant_tone = f % 200 == 0 ? 0.4f : stipple::kLightingTone;
            ASSERT_TRUE(stipple::pipeline_set_view(pipeline, view).ok());
        }
        stipple::pipeline_frame(pipeline, 0, float(f) / 30.0f, &times);
        stipple::renderer_read_color(&pipeline->renderer, rgba.data());
    }
    g_counting = false;
    EXPECT_EQ(g_allocations.load(), 0);
    // The frames did real work: some pixels carry ink.
    size_t dark = 0;
    for (size_t i = 0; i < rgba.size(); i += 4) dark += rgba[i] < 128;
    EXPECT_GT(dark, 50u);
    stipple::pipeline_destroy(pipeline);
}

}  // namespace
