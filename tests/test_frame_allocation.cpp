// A frame allocates nothing: every buffer is taken at load (pipeline_init). Counts global
// operator new calls over many frames of sampling, skinning, point stages and drawing.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <memory>
#include <new>
#include <string>

#include "bake/asset_writer.h"
#include "bake/point_hierarchy.h"
#include "bake/scene_import.h"
#include "platform/headless_context.h"
#include "runtime/frame_pipeline.h"

#include "tests/alloc_counter.h"

// The one definition of the shared counters (tests/alloc_counter.h).
namespace stipple::test {
std::atomic<bool> g_counting{false};
std::atomic<long> g_allocations{0};
}  // namespace stipple::test
using stipple::test::g_allocations;
using stipple::test::g_counting;

void* operator new(std::size_t size) {
    if (g_counting) ++g_allocations;
    if (void* p = std::malloc(size ? size : 1)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return operator new(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
    if (g_counting) ++g_allocations;
    return std::malloc(size ? size : 1);
}
void* operator new[](std::size_t size, const std::nothrow_t& tag) noexcept {
    return operator new(size, tag);
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

namespace {

TEST(FrameAllocation, FramesAllocateNothingAfterLoad) {
    stipple::bake::RawScene scene;
    std::string error;
    ASSERT_TRUE(stipple::bake::import_scene(
        std::string(STIPPLE_SOURCE_DIR) + "/assets/CesiumMan/CesiumMan.glb", &scene, &error))
        << error;
    stipple::bake::HierarchyConfig config;
    config.point_count = 10000;
    stipple::bake::PointHierarchy points;
    ASSERT_TRUE(stipple::bake::build_point_hierarchy(scene, config, &points, nullptr, &error));
    std::vector<uint8_t> bytes = stipple::bake::encode_asset(scene, points);
    stipple::Asset asset;
    ASSERT_TRUE(stipple::load_asset_memory(bytes.data(), bytes.size(), &asset).ok());

    stipple::platform::HeadlessContext context;
    ASSERT_TRUE(stipple::platform::create_headless_context({}, &context, &error)) << error;
    stipple::GlApi gl;
    ASSERT_EQ(stipple::load_gl_api(stipple::platform::proc_loader(context), &gl), nullptr);
    auto pipeline = std::make_unique<stipple::Pipeline>();
    char message[256];
    ASSERT_TRUE(stipple::pipeline_init(pipeline.get(), asset, gl, {}, message, sizeof(message)))
        << message;
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
        stipple::PipelineConfig view = pipeline->config;
        view.zoom = 1.0f + 15.0f * float(f) / 59.0f;
        view.constant_tone = 0.6f;
        stipple::pipeline_set_view(pipeline.get(), view);
        stipple::pipeline_frame(pipeline.get(), 0, float(f) / 30.0f, &times);
        stipple::renderer_read_color(&pipeline->renderer, rgba.data());
        most_refined = std::max(most_refined, pipeline->refined_count);
    }
    g_counting = false;
    EXPECT_EQ(g_allocations.load(), 0);
    EXPECT_GT(most_refined, 10000u);  // the refinement did real work

    stipple::pipeline_destroy(pipeline.get());
    stipple::platform::destroy_headless_context(&context);
}

}  // namespace
