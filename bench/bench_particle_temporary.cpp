// Temporary particles generated per view (runtime/particle_temporary.h, GI'01 §5) on
// CesiumMan (20k points) walking at zoom 8, 640x480, painterly-long, the default budget
// (262,144 ids), headless EGL. Stage 1's three parts each frame, each timed alone (the pose
// and the other parts outside the timing), in the same run:
//   TreeHalf     the baked tree's folds and unfolds (particle_stage_adjust_tree), the
//                baseline; ns per active particle.
//   Temporaries  the temporary particles: clip and N.V per vertex, need per triangle, the
//                budget, joins and leaves (particle_stage_adjust_temporaries); ns per
//                temporary shown, ns per triangle asked.
//   Finish       the merge of the new members, every member's fade, and the release of
//                faded slots (particle_stage_adjust_finish); ns per listed particle.
// Zero allocations per frame are checked in tests/alloc/test_particle_allocation.cpp.
#include <benchmark/benchmark.h>

#include <memory>

#include "bench/bench_setup.h"

namespace {

using namespace stipple;

struct Setup : bench::ParticleScene {
    int frame = 0;
};

Setup* setup() {
    return bench::build_once<Setup>(
        [](Setup* s) { return bench::particle_scene(s, "painterly-long", 8.0f, false); });
}

// Poses the next frame of the walk (30 fps).
ParticleFrame pose(Setup* s) {
    AnimationState state;
    state.clip = 0;
    state.time = float(s->frame++ % 60) / 30.0f;
    pipeline_update(s->pipeline.get(), state, nullptr);
    return pipeline_particle_input(*s->pipeline);
}

enum Part { kTree = 0, kTemporaries = 1, kFinish = 2 };

// One frame of stage 1 with only `part` timed.
void stage1(benchmark::State& state, Part part) {
    Setup* s = setup();
    if (!s) return state.SkipWithError("no headless GL or asset");
    ParticleStage* st = s->stage.get();
    for (int k = 0; k < 8; ++k) particle_stage_adjust(st, pose(s));  // settle at zoom 8
    double per = 0, triangles = 0;
    for (auto _ : state) {
        state.PauseTiming();
        const ParticleFrame f = pose(s);
        if (part != kTree) particle_stage_adjust_tree(st, f);
        if (part == kFinish) particle_stage_adjust_temporaries(st);
        state.ResumeTiming();
        if (part == kTree) particle_stage_adjust_tree(st, f);
        if (part == kTemporaries) particle_stage_adjust_temporaries(st);
        if (part == kFinish) particle_stage_adjust_finish(st);
        state.PauseTiming();
        if (part == kTree) particle_stage_adjust_temporaries(st);
        if (part != kFinish) particle_stage_adjust_finish(st);
        per += part == kTree          ? double(st->set.active_count - st->temporary.stats.shown)
               : part == kTemporaries ? double(st->temporary.stats.shown)
                                      : double(st->set.count);
        triangles += st->temporary.stats.triangles;
        state.ResumeTiming();
    }
    const double n = double(state.iterations());
    state.counters["per_frame"] = per / n;
    state.counters["triangles"] = triangles / n;
    state.counters["slots_held"] = st->temporary.stats.live;
    state.counters["ns_per"] =
        benchmark::Counter(per * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
    if (part == kTemporaries)
        state.counters["ns_per_triangle"] = benchmark::Counter(
            triangles * 1e-9, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_TreeHalf(benchmark::State& state) {
    stage1(state, kTree);
}
void BM_Temporaries(benchmark::State& state) {
    stage1(state, kTemporaries);
}
void BM_Finish(benchmark::State& state) {
    stage1(state, kFinish);
}

}  // namespace

BENCHMARK(BM_TreeHalf)->Repetitions(5);
BENCHMARK(BM_Temporaries)->Repetitions(5);
BENCHMARK(BM_Finish)->Repetitions(5);
