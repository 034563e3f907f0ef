// View-dependent particles (GI'01, runtime/particle_stage.h) on CesiumMan (20k points)
// walking, 640x480, headless EGL. Per frame, each stage against its simplest alternative in
// the same run:
//   Adjust       stage 1 over the persistent active set; counter ns per active particle.
//   AdjustZoom8  stage 1 at zoom 8, where the tree unfolds past the 20k baked points into
//                temporary particles (runtime/particle_temporary.h); ns per active particle,
//                to compare with Adjust's.
//   AdjustFull   the alternative: the same criterion asked of every particle of the tree
//                each frame (no persistent set); ns per particle.
//   Transform    stage 3 over the listed particles; ns per listed particle.
//   Strokes      stage 4's CPU half (tone rule, foreshortening, binning); ns per stroke.
//   Render       stage 4's draw of the instanced brush quads + glFinish; ns per stroke.
//   RenderFloor  the same instances drawn 1 px wide and long (vertex work, no fill); the
//                ratio Render / RenderFloor is the cost of the brush texels.
// Zero allocations per frame are checked in tests/alloc/test_particle_allocation.cpp.
#include <benchmark/benchmark.h>

#include <memory>
#include <vector>

#include "bench/bench_setup.h"

namespace {

using namespace stipple;

struct Setup : bench::ParticleScene {
    std::vector<uint32_t> all;  // every particle id, for AdjustFull
    std::vector<uint8_t> unfold;
    std::vector<StrokeInstance> thin;
};

Setup* setup() {
    return bench::build_once<Setup>([](Setup* s) {
        if (!bench::particle_scene(s, "painterly-long", 1.0f, true)) return false;
        s->all.resize(s->asset.points.point_count);
        for (uint32_t i = 0; i < s->all.size(); ++i) s->all[i] = i;
        s->unfold.resize(s->all.size());
        return true;
    });
}

// Poses frame f of the walk (30 fps) and runs stage 1 once, so the set follows the walk.
void pose(Setup* s, int f) {
    AnimationState state;
    state.clip = 0;
    state.time = float(f % 60) / 30.0f;
    pipeline_update(s->pipeline.get(), state, nullptr);
}

void BM_Adjust(benchmark::State& state) {
    Setup* s = setup();
    if (!s) return state.SkipWithError("no headless GL or asset");
    int f = 0;
    double active = 0;
    for (auto _ : state) {
        state.PauseTiming();
        pose(s, f++);
        const ParticleFrame frame = pipeline_particle_input(*s->pipeline);
        state.ResumeTiming();
        particle_stage_adjust(s->stage.get(), frame);
        active += s->stage->set.active_count;
    }
    state.counters["active"] = active / double(state.iterations());
    state.counters["ns_per_active"] = benchmark::Counter(
        active * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// Stage 1 at `zoom`, after a few settling frames; the view goes back to zoom 1 afterwards.
void adjust_at(benchmark::State& state, float zoom) {
    Setup* s = setup();
    if (!s) return state.SkipWithError("no headless GL or asset");
    FrameConfig view = s->pipeline->config;
    view.zoom = zoom;
    if (!pipeline_set_view(s->pipeline.get(), view).ok()) return state.SkipWithError("view");
    int f = 0;
    for (int k = 0; k < 8; ++k) {
        pose(s, f++);
        particle_stage_adjust(s->stage.get(), pipeline_particle_input(*s->pipeline));
    }
    double active = 0, temporary = 0;
    for (auto _ : state) {
        state.PauseTiming();
        pose(s, f++);
        const ParticleFrame frame = pipeline_particle_input(*s->pipeline);
        state.ResumeTiming();
        particle_stage_adjust(s->stage.get(), frame);
        active += s->stage->set.active_count;
        state.PauseTiming();
        for (uint32_t k = 0; k < s->stage->set.count; ++k)
            temporary += s->stage->set.list[k] >= s->asset.points.point_count;
        state.ResumeTiming();
    }
    view.zoom = 1.0f;
    if (!pipeline_set_view(s->pipeline.get(), view).ok()) return state.SkipWithError("view");
    state.counters["active"] = active / double(state.iterations());
    state.counters["temporary_listed"] = temporary / double(state.iterations());
    state.counters["ns_per_active"] = benchmark::Counter(
        active * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_AdjustZoom8(benchmark::State& state) {
    adjust_at(state, 8.0f);
}

void BM_AdjustFull(benchmark::State& state) {
    Setup* s = setup();
    if (!s) return state.SkipWithError("no headless GL or asset");
    ParticleSamples& scratch = s->stage->samples;  // the whole tree (asked holds a chunk)
    int f = 0;
    for (auto _ : state) {
        state.PauseTiming();
        pose(s, f++);
        const ParticleFrame frame = pipeline_particle_input(*s->pipeline);
        state.ResumeTiming();
        transform_particles(frame, s->all.data(), uint32_t(s->all.size()), nullptr,
                            s->stage->style.field, &scratch);
        for (uint32_t k = 0; k < scratch.count; ++k) scratch.unfolded[k] = 0;
        particle_style_adjust(s->stage->style, scratch, s->unfold.data());
        benchmark::DoNotOptimize(s->unfold.data());
    }
    state.counters["ns_per_particle"] =
        benchmark::Counter(double(state.iterations()) * double(s->all.size()) * 1e-9,
                           benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_Transform(benchmark::State& state) {
    Setup* s = setup();
    if (!s) return state.SkipWithError("no headless GL or asset");
    int f = 0;
    double listed = 0;
    for (auto _ : state) {
        state.PauseTiming();
        pose(s, f++);
        particle_stage_adjust(s->stage.get(), pipeline_particle_input(*s->pipeline));
        state.ResumeTiming();
        particle_stage_transform(s->stage.get());
        listed += s->stage->set.count;
    }
    state.counters["listed"] = listed / double(state.iterations());
    state.counters["ns_per_listed"] = benchmark::Counter(
        listed * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_Strokes(benchmark::State& state) {
    Setup* s = setup();
    if (!s) return state.SkipWithError("no headless GL or asset");
    pose(s, 0);
    particle_stage_update(s->stage.get(), pipeline_particle_input(*s->pipeline));
    for (auto _ : state) particle_stage_build_strokes(s->stage.get());
    state.counters["strokes"] = s->stage->stroke_count;
    state.counters["ns_per_stroke"] =
        benchmark::Counter(double(state.iterations()) * s->stage->stroke_count * 1e-9,
                           benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// Draws the strokes (thin: 1 px quads) over the frame's polygon pass, then glFinish.
void render(benchmark::State& state, bool thin) {
    Setup* s = setup();
    if (!s) return state.SkipWithError("no headless GL or asset");
    pose(s, 0);
    ParticleStage& st = *s->stage;
    particle_stage_update(&st, pipeline_particle_input(*s->pipeline));
    std::vector<StrokeInstance> strokes(st.strokes.get(), st.strokes.get() + st.stroke_count);
    if (thin)
        for (StrokeInstance& i : strokes) i.length = i.width = 1.0f;
    Renderer& r = s->pipeline->renderer;
    renderer_draw_mesh(&r, s->pipeline->view_projection, s->pipeline->vertex_positions.get(),
                       s->asset.mesh.vertex_count);
    for (auto _ : state) {
        particle_renderer_draw(&st.renderer, r.ink_fbo, r.depth_tex, st.width, st.height,
                               strokes.data(), uint32_t(strokes.size()));
        s->gl.Finish();
    }
    state.counters["strokes"] = double(strokes.size());
    state.counters["ns_per_stroke"] =
        benchmark::Counter(double(state.iterations()) * double(strokes.size()) * 1e-9,
                           benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_Render(benchmark::State& state) {
    render(state, false);
}
void BM_RenderFloor(benchmark::State& state) {
    render(state, true);
}

// Interleaved, repeated: report min and median (the machine is noisy).
BENCHMARK(BM_Adjust)->Repetitions(5)->ReportAggregatesOnly(false);
BENCHMARK(BM_AdjustZoom8)->Repetitions(5);
BENCHMARK(BM_AdjustFull)->Repetitions(5);
BENCHMARK(BM_Transform)->Repetitions(5);
BENCHMARK(BM_Strokes)->Repetitions(5);
BENCHMARK(BM_Render)->Repetitions(5);
BENCHMARK(BM_RenderFloor)->Repetitions(5);

}  // namespace
