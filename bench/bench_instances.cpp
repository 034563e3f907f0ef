// Many characters in one application frame (issue 8): N instances (pipelines) of one loaded
// CesiumMan asset (20k points) drawn into the application's 1280x720 framebuffer with
// pipeline_draw_into, on a 4x4 grid, each at its own walk phase. Reports ms per frame and per
// instance; the ratio to N times the one-instance frame (same run) says what sharing the
// frame costs or saves.
#include <benchmark/benchmark.h>

#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <vector>

#include "bench/bench_asset.h"
#include "platform/headless_context.h"
#include "runtime/app_frame.h"
#include "runtime/camera.h"

namespace {

constexpr int kW = 1280, kH = 720, kMaxInstances = 16;

struct Scene {
    stipple::platform::HeadlessContext context;
    stipple::GlApi gl;
    stipple::Asset asset;
    std::vector<std::unique_ptr<stipple::Pipeline>> instances;
    GLuint fbo = 0, rb[2] = {};
    stipple::AppView view;
    bool ok = false;
};

Scene* scene() {
    static std::unique_ptr<Scene> s;
    if (s) return s->ok ? s.get() : nullptr;
    s = std::make_unique<Scene>();
    stipple::platform::HeadlessConfig hc;
    hc.width = kW;
    hc.height = kH;
    if (!stipple::platform::create_headless_context(hc, &s->context).ok()) return nullptr;
    if (!stipple::load_gl_api(stipple::platform::proc_loader(s->context), &s->gl).ok())
        return nullptr;
    if (!stipple::bench::bake_asset("CesiumMan/CesiumMan.glb", 20000, &s->asset)) return nullptr;
    const stipple::GlApi& gl = s->gl;
    gl.GenFramebuffers(1, &s->fbo);
    gl.BindFramebuffer(GL_FRAMEBUFFER, s->fbo);
    gl.GenRenderbuffers(2, s->rb);
    gl.BindRenderbuffer(GL_RENDERBUFFER, s->rb[0]);
    gl.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, kW, kH);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, s->rb[0]);
    gl.BindRenderbuffer(GL_RENDERBUFFER, s->rb[1]);
    gl.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, kW, kH);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, s->rb[1]);
    stipple::FrameConfig config;
    config.width = kW;
    config.height = kH;
    for (int i = 0; i < kMaxInstances; ++i) {
        s->instances.push_back(std::make_unique<stipple::Pipeline>());
        if (!stipple::pipeline_init(s->instances.back().get(), s->asset, gl, config).ok())
            return nullptr;
    }
    // A camera that sees a 4 x 4 grid of walkers 1.2 units apart.
    s->view.view = glm::lookAt(glm::vec3(0, 3.5f, 7.5f), glm::vec3(0, 0.6f, 0), glm::vec3(0, 1, 0));
    s->view.projection = glm::perspective(glm::radians(40.0f), float(kW) / kH, 0.1f, 50.0f);
    s->view.viewport[2] = kW;
    s->view.viewport[3] = kH;
    s->ok = true;
    return s.get();
}

void draw_frame(Scene* s, int n, float time) {
    const stipple::GlApi& gl = s->gl;
    gl.BindFramebuffer(GL_FRAMEBUFFER, s->fbo);
    gl.Viewport(0, 0, kW, kH);
    gl.DepthMask(GL_TRUE);
    gl.ClearColor(1, 1, 1, 1);
    gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    for (int i = 0; i < n; ++i) {
        stipple::AppView v = s->view;
        v.model = glm::translate(glm::mat4(1.0f), glm::vec3(-1.8f + 1.2f * float(i % 4), 0,
                                                            -1.8f + 1.2f * float(i / 4)));
        stipple::AnimationState state;
        state.clip = 0;
        state.time = time + 0.37f * float(i);
        stipple::pipeline_draw_into(s->instances[size_t(i)].get(), state, v, nullptr);
    }
    gl.Finish();
}

void BM_Instances(benchmark::State& state) {
    Scene* s = scene();
    if (!s) {
        state.SkipWithError("no headless context or asset");
        return;
    }
    const int n = int(state.range(0));
    float time = 0;
    for (auto _ : state) {
        draw_frame(s, n, time);
        time += 1.0f / 30.0f;
    }
    state.counters["instances"] = n;
    // Per instance: the frame time over n (Google Benchmark prints it as time, e.g. "6.1ms").
    state.counters["per_instance"] = benchmark::Counter(
        double(n), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_Instances)->Arg(1)->Arg(4)->Arg(16)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
