// Issue 9, item 4: the frame with the point stages on the CPU against the GPU path
// (runtime/gpu_stages.h: place, relevance and size in a transform feedback vertex shader),
// CesiumMan at 100k points walking, 1280x720, both without run-time refinement (the GPU path
// draws the baked points only). The two pipelines share one context and draw alternately,
// frame by frame, so both see the same machine load; min and median per path, and the ratio.
// Also the point stages alone: CPU place + relevance + size (StageTimes) against the
// transform feedback pass alone (upload of the posed vertices + the pass + glFinish).
// On llvmpipe the "GPU" is these same CPU cores running the shader through LLVM; see
// docs/gpu-path.md for what the ratio says and does not say about a real GPU.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "bench/bench_asset.h"
#include "platform/headless_context.h"
#include "runtime/frame_pipeline.h"

namespace {

using Clock = std::chrono::steady_clock;

double ms(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
}

struct Stats {
    double min = 0, median = 0;
};

Stats stats(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return {v.front(), v[v.size() / 2]};
}

struct Setup {
    stipple::platform::HeadlessContext context;
    stipple::Asset asset;
    // The CPU path with level of detail (the default), without it, and the GPU path.
    std::unique_ptr<stipple::Pipeline> pipelines[3];
};

bool make_setup(Setup* s) {
    stipple::platform::HeadlessConfig hc;
    hc.width = 1280;
    hc.height = 720;
    if (!stipple::platform::create_headless_context(hc, &s->context).ok()) return false;
    if (!stipple::bench::bake_asset("CesiumMan/CesiumMan.glb", 100000, &s->asset)) return false;
    stipple::GlApi gl;
    if (!stipple::load_gl_api(stipple::platform::proc_loader(s->context), &gl).ok()) return false;
    stipple::FrameConfig pc;
    pc.width = 1280;
    pc.height = 720;
    pc.yaw_degrees = -60;
    pc.frame_clip = 0;
    pc.refinement_budget = 0;
    for (int k = 0; k < 3; ++k) {
        pc.lod = k == 0;
        pc.path = k == 2 ? stipple::FramePath::gpu : stipple::FramePath::cpu;
        s->pipelines[k] = std::make_unique<stipple::Pipeline>();
        if (!stipple::pipeline_init(s->pipelines[k].get(), s->asset, gl, pc).ok()) return false;
    }
    return true;
}

// The transform feedback pass alone (upload, pass, glFinish) on the pose the last frame left.
double feedback_pass_ms(stipple::Pipeline* g, bool relevance_update) {
    const Clock::time_point a = Clock::now();
    stipple::gpu_stages_run(&g->gpu, g->vertex_positions.get(), g->vertex_normals.get(),
                            g->size_params, relevance_update);
    g->renderer.gl.Finish();
    return ms(a, Clock::now());
}

// Whole frames, alternating the three pipelines frame by frame over the walk.
void BM_FrameCpuVsGpuPath(benchmark::State& state) {
    static Setup s;
    static const bool ok = make_setup(&s);
    if (!ok) {
        state.SkipWithError("no EGL context, bake or pipeline");
        return;
    }
    constexpr int kFrames = 60;
    for (auto _ : state) {
        std::vector<double> frame_ms[3], stage_ms[3], place_size_ms;
        for (int f = 0; f < kFrames; ++f) {
            for (int k = 0; k < 3; ++k) {
                stipple::StageTimes times;
                const Clock::time_point a = Clock::now();
                stipple::pipeline_frame(s.pipelines[k].get(), 0, float(f) / 30.0f, &times);
                frame_ms[k].push_back(ms(a, Clock::now()));
                stage_ms[k].push_back(times.select + times.place + times.relevance + times.size);
            }
            stage_ms[2].back() = feedback_pass_ms(s.pipelines[2].get(), true);
            // Without Alg. 6.4 (rest-pose radii): no neighbour walk.
            place_size_ms.push_back(feedback_pass_ms(s.pipelines[2].get(), false));
        }
        const char* names[3] = {"cpu, LOD", "cpu, no LOD", "gpu"};
        const char* keys[3] = {"cpu_lod", "cpu_nolod", "gpu"};
        std::printf(
            "CesiumMan 100k walk, 1280x720, %d interleaved frames (ms)\n"
            "| path | frame min | frame median | point stages min | point stages median |\n",
            kFrames);
        for (int k = 0; k < 3; ++k) {
            const Stats fs = stats(frame_ms[k]), ss = stats(stage_ms[k]);
            state.counters[std::string(keys[k]) + "_frame_median_ms"] = fs.median;
            state.counters[std::string(keys[k]) + "_stages_median_ms"] = ss.median;
            std::printf("| %s | %.2f | %.2f | %.2f | %.2f |\n", names[k], fs.min, fs.median, ss.min,
                        ss.median);
        }
        const Stats ps = stats(place_size_ms);
        std::printf(
            "gpu / cpu (LOD) frame median: %.2f; gpu / cpu (no LOD): %.2f; gpu pass without "
            "relevance (place + size only): min %.2f, median %.2f\n",
            stats(frame_ms[2]).median / stats(frame_ms[0]).median,
            stats(frame_ms[2]).median / stats(frame_ms[1]).median, ps.min, ps.median);
    }
}
BENCHMARK(BM_FrameCpuVsGpuPath)->Iterations(1)->Unit(benchmark::kMillisecond);

}  // namespace
