// Shared by the benchmarks that draw or pose: a setup built once per process (the first
// benchmark that asks builds it; a failure is remembered and reported by every benchmark),
// the headless GL context, and the particle scene of bench_particles.cpp and
// bench_particle_temporary.cpp (CesiumMan baked to 20k points, a particle style's frame).
#pragma once
#include <memory>

#include "bench/bench_asset.h"
#include "platform/headless_context.h"
#include "runtime/particle_frame.h"

namespace stipple::bench {

// The T that build(T*) filled, made on the first call only; nullptr if that build failed.
template <typename T, typename Build>
T* build_once(Build build) {
    static std::unique_ptr<T> made;
    static bool tried = false;
    if (!tried) {
        tried = true;
        auto n = std::make_unique<T>();
        if (build(n.get())) made = std::move(n);
    }
    return made.get();
}

// A headless GL context with the GL API loaded. (A base: its members are destroyed last.)
struct HeadlessGl {
    platform::HeadlessContext context;
    GlApi gl;
};
inline bool headless_gl(HeadlessGl* out, const platform::HeadlessConfig& config = {}) {
    return platform::create_headless_context(config, &out->context).ok() &&
           load_gl_api(platform::proc_loader(out->context), &out->gl).ok();
}

struct ParticleScene : HeadlessGl {
    Asset asset;
    std::unique_ptr<Pipeline> pipeline = std::make_unique<Pipeline>();
    std::unique_ptr<ParticleStage> stage = std::make_unique<ParticleStage>();
};

// CesiumMan baked to 20k points, a pipeline for particle style `style`'s frame at `zoom`, and
// its particle stage (with the stage's GL half if `stage_gl`).
inline bool particle_scene(ParticleScene* s, const char* style, float zoom, bool stage_gl) {
    if (!headless_gl(s) || !bake_asset("CesiumMan/CesiumMan.glb", 20000, &s->asset)) return false;
    const ParticleStyle& particle_style = *find_particle_style(style);
    FrameConfig c;
    particle_style_frame_config(particle_style, &c);
    c.zoom = zoom;
    return pipeline_init(s->pipeline.get(), s->asset, s->gl, c).ok() &&
           particle_stage_init(s->stage.get(), s->asset, particle_style, c.width, c.height).ok() &&
           (!stage_gl || particle_stage_init_gl(s->stage.get(), s->gl).ok());
}

}  // namespace stipple::bench
