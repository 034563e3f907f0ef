// View-dependent particles allocate nothing per frame (issue 11): the particle tree, the active
// set, the transformed particles and the strokes all take their memory at init.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "runtime/particle_frame.h"
#include "tests/alloc/alloc_counter.h"
#include "tests/alloc/cesium_pipeline.h"
#include "tests/common/fixtures.h"

using stipple::test::g_allocations;
using stipple::test::g_counting;

namespace {

TEST(ParticleAllocation, ParticleFramesAllocateNothingAfterInit) {
    stipple::test::CesiumPipeline cesium;  // the asset and the context; a pipeline per style
    ASSERT_TRUE(stipple::test::open_cesium("--points 10000", &cesium));
    const stipple::Asset& asset = cesium.asset;
    stipple::test::HeadlessGl& gl = cesium.gl;
    for (const char* name : {"painterly-long", "graftals", "two-tone"}) {
        const stipple::ParticleStyle* style = stipple::find_particle_style(name);
        ASSERT_NE(style, nullptr);
        stipple::FrameConfig config;
        stipple::particle_style_frame_config(*style, &config);
        const bool fades = std::string(name) == "two-tone";  // visibility fades: a readback
        config.depth_readback = fades;
        auto pipeline = std::make_unique<stipple::Pipeline>();
        auto stage = std::make_unique<stipple::ParticleStage>();
        ASSERT_TRUE(stipple::pipeline_init(pipeline.get(), asset, gl.gl(), config).ok());
        ASSERT_TRUE(
            stipple::particle_stage_init(stage.get(), asset, *style, config.width, config.height)
                .ok());
        ASSERT_TRUE(stipple::particle_stage_init_gl(stage.get(), gl.gl()).ok());
        if (fades) {
            ASSERT_TRUE(stipple::particle_stage_enable_visibility_fades(stage.get()).ok());
        }
        stipple::AnimationState state;
        state.clip = 0;
        stipple::pipeline_particle_frame(pipeline.get(), stage.get(), state, nullptr);
        std::vector<uint8_t> rgba(size_t(config.width) * config.height * 4);
        uint32_t most = 0;
        g_allocations = 0;
        g_counting = true;
        for (int f = 0; f < 120; ++f) {  // walking, and zooming in from 1 to 6
            stipple::FrameConfig view = pipeline->config;
            view.zoom = 1.0f + 5.0f * float(f) / 119.0f;
            ASSERT_TRUE(stipple::pipeline_set_view(pipeline.get(), view).ok());
            state.time = float(f) / 30.0f;
            stipple::pipeline_particle_frame(pipeline.get(), stage.get(), state, nullptr);
            stipple::renderer_read_color(&pipeline->renderer, rgba.data());
            most = std::max(most, stage->stats.strokes);
        }
        g_counting = false;
        EXPECT_EQ(g_allocations.load(), 0) << name;
        // The close-up unfolded past the bake: temporary particles were listed.
        uint32_t temporary = 0;
        for (uint32_t k = 0; k < stage->set.count; ++k)
            temporary += stage->set.list[k] >= asset.points.point_count;
        EXPECT_GT(temporary, 0u) << name;
        EXPECT_EQ(stage->visibility.applied, fades) << name;
        EXPECT_GT(most, 20u) << name << ": the frames drew strokes";
        stipple::particle_stage_destroy(stage.get());
        stipple::pipeline_destroy(pipeline.get());
    }
}

}  // namespace
