// GI'98 Table 1 as a Google Benchmark (the full table with image errors is
// stipple-paintstroke-table): the 27-tube cluster of bench/paintstroke_scene.h at 640x480 on
// headless EGL, per scale (0 large, 1 medium, 2 small), paintstrokes at quality 2, 1, 0 against
// static 9-, 5- and 3-gon extrusions. Time per frame = CPU work (tessellation + back-to-front
// sort, or the static model's eye transform + back-face cull) + draw + glFinish; the frame
// index walks the 50-frame orbit. Counters: triangles per tube (total; rendered for static),
// the tessellation's CPU cost per stroke and per emitted triangle.
#include <benchmark/benchmark.h>

#include <chrono>
#include <memory>

#include "bench/bench_setup.h"
#include "bench/paintstroke_scene.h"
#include "runtime/stroke_renderer.h"
#include "runtime/stroke_sort.h"

namespace {

using namespace stipple;
using namespace stipple::bench;

struct Setup : HeadlessGl {
    StrokeRenderer renderer;
    Target target;
    Scene scene;
    StaticModel statics[3];                   // 9, 5, 3 sides
    std::unique_ptr<StrokeFrame> strokes[3];  // quality 0, 1, 2
    StaticFrame static_frame;
};

// Builds the scene, its static models, the tessellators and the renderer sized for the largest.
bool build(Setup* n) {
    if (!headless_gl(n)) return false;
    n->scene = make_gi98_scene();
    const int sides[3] = {9, 5, 3};
    uint64_t max_v = 0, max_i = 0;
    for (int i = 0; i < 3; ++i) {
        n->statics[i] = build_extrusion(n->scene, sides[i], glm::radians(10.0f));
        TessellationParams params;
        params.quality = i;
        n->strokes[i].reset(new StrokeFrame());
        stroke_frame_init(n->strokes[i].get(), params);
        max_v = std::max<uint64_t>(
            {max_v, n->strokes[i]->bound.vertices, n->statics[i].vertices.size()});
        max_i =
            std::max<uint64_t>({max_i, n->strokes[i]->bound.indices, n->statics[i].indices.size()});
    }
    StrokeRendererConfig rc;
    rc.max_vertices = uint32_t(std::min<uint64_t>(max_v, 1u << 24));
    rc.max_indices = uint32_t(std::min<uint64_t>(max_i, 1u << 26));
    return stroke_renderer_init(&n->renderer, n->gl, rc).ok() &&
           target_init(n->gl, kWidth, kHeight, &n->target);
}

Setup* setup() {
    return build_once<Setup>(build);
}

void draw(Setup* s, const View& view, const StrokeVertex* v, uint32_t vn, const uint32_t* idx,
          uint32_t in) {
    target_clear(s->gl, s->target);
    StrokeLighting lighting;
    lighting.light_eye = view.light_eye;
    stroke_renderer_draw(&s->renderer, view.projection, lighting, v, vn, idx, in);
    s->gl.Finish();
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Args: scale, quality.
void BM_PaintstrokeFrame(benchmark::State& state) {
    Setup* s = setup();
    if (!s) return state.SkipWithError("no headless context");
    const int scale = int(state.range(0));
    StrokeFrame& f = *s->strokes[state.range(1)];
    int frame = 0;
    double tess_s = 0, triangles = 0, strokes = 0;
    for (auto _ : state) {
        const View view = scene_view(scale, frame);
        frame = (frame + 1) % kFrames;
        const auto t0 = std::chrono::steady_clock::now();
        tessellate_scene_only(s->scene, view, &f);
        tess_s += seconds_since(t0);
        sort_segments_back_to_front(f.mesh, f.order.get(), f.scratch.get());
        gather_sorted_indices(f.mesh, f.order.get(), f.sorted_indices.get());
        draw(s, view, f.mesh.vertices, f.mesh.vertex_count, f.sorted_indices.get(),
             f.mesh.index_count);
        triangles += f.mesh.index_count / 3;
        strokes += kTubeCount;
    }
    state.counters["tris_per_tube"] = triangles / strokes;
    state.counters["tess_ns_per_stroke"] = 1e9 * tess_s / strokes;
    state.counters["tess_ns_per_tri"] = triangles > 0 ? 1e9 * tess_s / triangles : 0.0;
}

// Args: scale, index of the static model (0: 9-gon, 1: 5-gon, 2: 3-gon).
void BM_StaticFrame(benchmark::State& state) {
    Setup* s = setup();
    if (!s) return state.SkipWithError("no headless context");
    const int scale = int(state.range(0));
    const StaticModel& m = s->statics[state.range(1)];
    StaticFrame& sf = s->static_frame;
    int frame = 0;
    double rendered = 0, frames = 0;
    for (auto _ : state) {
        const View view = scene_view(scale, frame);
        frame = (frame + 1) % kFrames;
        static_to_eye(m, view.view, &sf);
        draw(s, view, sf.vertices.data(), uint32_t(sf.vertices.size()), sf.indices.data(),
             uint32_t(sf.indices.size()));
        rendered += sf.rendered_triangles;
        frames += 1;
    }
    state.counters["tris_per_tube"] = double(m.triangles) / kTubeCount;
    state.counters["rendered_per_tube"] = rendered / (frames * kTubeCount);
}

void args(benchmark::internal::Benchmark* b) {
    for (int scale = 0; scale < kScales; ++scale)
        for (int model = 0; model < 3; ++model) b->Args({scale, model});
    b->ArgNames({"scale", "model"})->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(0.15);
}

}  // namespace

// model: paintstroke quality (0, 1, 2) here; the static n-gon (0: 9, 1: 5, 2: 3) below.
BENCHMARK(BM_PaintstrokeFrame)->Apply(args);
BENCHMARK(BM_StaticFrame)->Apply(args);
