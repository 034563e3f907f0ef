// "All memory is taken at load" includes the pages under it: a buffer the pipeline takes at
// init is written there (runtime/memory.h's make_buffer), so no frame is the first to touch a
// page and pay the kernel's fault for it (measured before: a fresh pipeline's first 30 frames
// of the CesiumMan walk took ~750 minor faults, ~3 MB, in the point stages and the refinement).
// The CPU half of the frame (pipeline_update: no GL call) over views that cut, cull and refine.
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <algorithm>

#include "runtime/frame_pipeline.h"
#include "tests/alloc/cesium_pipeline.h"

namespace {

long minor_faults() {
    struct rusage usage;
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_minflt;
}

TEST(PipelineMemory, FramesTouchNoNewPages) {
    stipple::FrameConfig config;
    config.refinement_budget = 200000;  // close-ups write far into the refined points' buffers
    stipple::test::CesiumPipeline cesium;
    ASSERT_TRUE(stipple::test::open_cesium("--points 20000", config, &cesium));
    stipple::Pipeline* pipeline = cesium.pipeline.get();
    stipple::AnimationState state;
    stipple::pipeline_update(pipeline, state, nullptr);  // the stack and the code's pages

    uint32_t most_refined = 0;
    const long before = minor_faults();
    for (int f = 0; f < 200; ++f) {
        stipple::FrameConfig view = pipeline->config;
        view.zoom = 0.5f + 7.5f * float(f % 100) / 99.0f;  // far (cut) to close (culled, refined)
        view.yaw_degrees = float(f) * 3.0f;
        ASSERT_TRUE(stipple::pipeline_set_view(pipeline, view).ok());
        state.time = float(f) / 30.0f;
        stipple::pipeline_update(pipeline, state, nullptr);
        most_refined = std::max(most_refined, pipeline->refined_count);
    }
    const long faults = minor_faults() - before;
    EXPECT_GT(most_refined, 10000u);  // the refinement filled much of its budget
    // A page is 4 KiB: a few faults (the C library, the kernel's own bookkeeping) are allowed;
    // buffers first touched in frames gave hundreds.
    EXPECT_LE(faults, 16) << "minor page faults in 200 frames";
    stipple::pipeline_destroy(pipeline);
}

}  // namespace
