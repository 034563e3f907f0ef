// Level of detail allocates nothing per frame (runtime/point_clusters.h): the selection, its
// closure and the listed stages work in buffers taken at pipeline_init, over views that cull,
// cut and refine, and while LOD is switched off and on between frames.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "runtime/frame_pipeline.h"
#include "tests/alloc/alloc_counter.h"
#include "tests/alloc/cesium_pipeline.h"
#include "tests/common/fixtures.h"

using stipple::test::g_allocations;
using stipple::test::g_counting;

namespace {

TEST(LodAllocation, FramesWithLodAllocateNothing) {
    stipple::test::CesiumPipeline cesium;
    ASSERT_TRUE(stipple::test::open_cesium("--points 20000", {}, &cesium));
    stipple::Pipeline* pipeline = cesium.pipeline.get();
    const stipple::Asset& asset = cesium.asset;
    ASSERT_TRUE(pipeline->config.lod);
    std::vector<uint8_t> rgba(640 * 480 * 4);
    stipple::pipeline_frame(pipeline, 0, 0.0f, nullptr);

    stipple::StageTimes times;
    uint32_t least_run = UINT32_MAX, most_refined = 0, culled = 0;
    g_allocations = 0;
    g_counting = true;
    for (int f = 0; f < 300; ++f) {
        stipple::FrameConfig view = pipeline->config;
        view.zoom = 0.5f + 7.5f * float(f % 100) / 99.0f;  // far (cut) to close (culled, refined)
        view.yaw_degrees = float(f) * 3.0f;                // front, side and back
        view.lod = f % 50 != 49;                           // switched off now and then
        ASSERT_TRUE(stipple::pipeline_set_view(pipeline, view).ok());
        stipple::pipeline_frame(pipeline, 0, float(f) / 30.0f, &times);
        stipple::renderer_read_color(&pipeline->renderer, rgba.data());
        if (view.lod) least_run = std::min(least_run, pipeline->clusters.stats.points_run);
        most_refined = std::max(most_refined, pipeline->refined_count);
        culled += pipeline->clusters.stats.culled_frustum + pipeline->clusters.stats.culled_back;
    }
    g_counting = false;
    EXPECT_EQ(g_allocations.load(), 0);
    EXPECT_LT(least_run, asset.points.point_count / 2);  // the selection skipped points
    EXPECT_GT(culled, 0u);
    EXPECT_GT(most_refined, 1000u);  // and the refinement ran with it
    stipple::pipeline_destroy(pipeline);
}

}  // namespace
