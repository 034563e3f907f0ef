// Whole frames on llvmpipe through headless EGL: the stipple pipeline (CPU stages + depth
// pass + silhouettes + sized dots) against the simplest alternative in the same run —
// drawing every point of the hierarchy as a fixed 2.5 px dot over the same depth pass (a
// static point cloud: no skinning of points, no relevance, no sizing).
// CesiumMan at 20k and 100k points, 1280x720; reports ms per frame and ns per point, and the
// raster floor: the same frame's GL work (depth pass + the dots drawn) with no CPU stage.
#include <benchmark/benchmark.h>

#include <memory>
#include <string>
#include <vector>

#include "bench/bench_asset.h"
#include "platform/headless_context.h"
#include "runtime/frame_pipeline.h"

namespace {

struct Setup {
    stipple::platform::HeadlessContext context;
    stipple::Asset asset;
    std::unique_ptr<stipple::Pipeline> pipeline;
    std::vector<float> fixed_sizes;
    bool ok = false;
};

Setup* setup(uint32_t points) {
    static std::unique_ptr<Setup> cache[2];
    static stipple::platform::HeadlessContext context;
    static bool have_context = false;
    if (!have_context) {
        stipple::platform::HeadlessConfig hc;
        hc.width = 1280;
        hc.height = 720;
        if (!stipple::platform::create_headless_context(hc, &context).ok()) return nullptr;
        have_context = true;
    }
    int slot = points > 50000;
    if (cache[slot]) return cache[slot].get();
    auto s = std::make_unique<Setup>();
    if (!stipple::bench::bake_asset("CesiumMan/CesiumMan.glb", points, &s->asset)) return nullptr;
    stipple::GlApi gl;
    if (!stipple::load_gl_api(stipple::platform::proc_loader(context), &gl).ok()) return nullptr;
    stipple::FrameConfig pc;
    pc.width = 1280;
    pc.height = 720;
    pc.yaw_degrees = -60;
    s->pipeline = std::make_unique<stipple::Pipeline>();
    if (!stipple::pipeline_init(s->pipeline.get(), s->asset, gl, pc).ok()) return nullptr;
    s->fixed_sizes.assign(s->asset.points.point_count, 2.5f);
    stipple::pipeline_frame(s->pipeline.get(), 0, 0.0f, nullptr);  // compile shaders
    cache[slot] = std::move(s);
    return cache[slot].get();
}

void per_point(benchmark::State& state, uint32_t points) {
    state.counters["per_point"] =
        benchmark::Counter(double(points), benchmark::Counter::kIsIterationInvariantRate |
                                               benchmark::Counter::kInvert);
}

void BM_StippleFrame(benchmark::State& state) {
    Setup* s = setup(uint32_t(state.range(0)));
    if (!s) return state.SkipWithError("no headless context or asset");
    float t = 0;
    for (auto _ : state) {
        stipple::pipeline_frame(s->pipeline.get(), 0, t, nullptr);
        t += 1.0f / 30.0f;
    }
    per_point(state, s->asset.points.point_count);
    state.counters["dots_drawn"] = s->pipeline->points_drawn;
}

void BM_StaticPointCloudFrame(benchmark::State& state) {
    Setup* s = setup(uint32_t(state.range(0)));
    if (!s) return state.SkipWithError("no headless context or asset");
    stipple::Pipeline& p = *s->pipeline;
    for (auto _ : state) {
        stipple::renderer_draw_mesh(&p.renderer, p.view_projection, p.vertex_positions.get(),
                                    s->asset.mesh.vertex_count);
        stipple::renderer_draw_points(&p.renderer, p.view_projection, p.point_positions.get(),
                                      s->fixed_sizes.data(), s->asset.points.point_count);
        p.renderer.gl.Finish();
    }
    per_point(state, s->asset.points.point_count);
}

// The raster floor of the stipple frame (issue 9): exactly the GL work of the last frame —
// the depth pass of the posed mesh and the dots it drew — with no CPU stage. The frame's
// ratio to this is what the CPU stages and the passes' overheads cost on top.
void BM_RasterFloor(benchmark::State& state) {
    Setup* s = setup(uint32_t(state.range(0)));
    if (!s) return state.SkipWithError("no headless context or asset");
    stipple::Pipeline& p = *s->pipeline;
    stipple::pipeline_frame(&p, 0, 0.5f, nullptr);  // the frame whose dots are replayed
    for (auto _ : state) {
        stipple::renderer_draw_mesh(&p.renderer, p.view_projection, p.vertex_positions.get(),
                                    s->asset.mesh.vertex_count);
        stipple::renderer_draw_points(&p.renderer, p.view_projection, p.draw_positions.get(),
                                      p.draw_sizes.get(), p.points_drawn);
        p.renderer.gl.Finish();
    }
    state.counters["dots_drawn"] = p.points_drawn;
}

BENCHMARK(BM_StippleFrame)->Arg(20000)->Arg(100000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_RasterFloor)->Arg(20000)->Arg(100000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_StaticPointCloudFrame)
    ->Arg(20000)
    ->Arg(100000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
