// Threads over point ranges allocate nothing per frame (runtime/thread_pool.h): the workers
// are started in pipeline_init, a frame only wakes them (mutex and condition variables), and
// the point stages' ranges (or the whole point part, beside the mesh pass) write into buffers
// taken at init.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "runtime/frame_pipeline.h"
#include "runtime/point_stages.h"
#include "tests/alloc/alloc_counter.h"
#include "tests/alloc/cesium_pipeline.h"
#include "tests/common/fixtures.h"

using stipple::test::g_allocations;
using stipple::test::g_counting;

namespace {

TEST(ThreadAllocation, FramesOnThreeThreadsAllocateNothing) {
    stipple::FrameConfig config;
    config.threads = 3;
    stipple::test::CesiumPipeline cesium;
    ASSERT_TRUE(stipple::test::open_cesium("--points 60000", config, &cesium));
    stipple::Pipeline* pipeline = cesium.pipeline.get();
    ASSERT_EQ(pipeline->pool.threads, 3);
    std::vector<uint8_t> rgba(640 * 480 * 4);
    stipple::pipeline_frame(pipeline, 0, 0.0f, nullptr);

    g_allocations = 0;
    g_counting = true;
    uint32_t most_run = 0;
    for (int f = 0; f < 200; ++f) {
        stipple::FrameConfig view = pipeline->config;
        view.zoom = 1.0f + 5.0f * float(f % 50) / 49.0f;  // full views to refining close-ups
        view.lod = f % 20 != 19;                          // and the full stages now and then
        ASSERT_TRUE(stipple::pipeline_set_view(pipeline, view).ok());
        // pipeline_frame runs the point part on a worker beside the mesh pass,
        // pipeline_update (an application's frame) beside the line stages.
        if (f % 2 == 0)
            stipple::pipeline_frame(pipeline, 0, float(f) / 30.0f, nullptr);
        else
            stipple::pipeline_update(pipeline, {0, float(f) / 30.0f}, nullptr);
        if (f % 4 == 1) {  // and the stages split in ranges over the threads, as callers may
            stipple::Pipeline* p = pipeline;
            const stipple::PointStageFrame sf = stipple::point_stage_frame(p);
            const stipple::PointClusters& c = p->clusters;
            stipple::point_stage_place(&p->pool, sf, c.placed.get(), c.placed_count);
            stipple::point_stage_relevance(&p->pool, sf, c.run.get(), c.run_count);
            stipple::point_stage_size(&p->pool, sf, c.run.get(), c.run_count);
        }
        stipple::renderer_read_color(&pipeline->renderer, rgba.data());
        most_run = std::max(most_run, pipeline->clusters.stats.points_run);
    }
    g_counting = false;
    EXPECT_EQ(g_allocations.load(), 0);
    EXPECT_GT(most_run, 3u * 2048u);  // ranges big enough to be split over the threads
    EXPECT_GT(pipeline->points_drawn, 100u);
    stipple::pipeline_destroy(pipeline);
}

}  // namespace
