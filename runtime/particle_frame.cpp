#include "runtime/particle_frame.h"

#include <cmath>
#include <cstring>

#include "runtime/stage_clock.h"

namespace stipple {

ParticleFrame pipeline_particle_input(const Pipeline& p) {
    ParticleFrame f;
    f.points = &p.asset->points;
    f.indices = p.asset->mesh.indices;
    f.positions = p.vertex_positions.get();
    f.normals = p.vertex_normals.get();
    f.view_projection = p.view_projection;
    f.eye = p.size_params.eye;
    f.width = p.viewport_width;
    f.height = p.viewport_height;
    f.focal_px = p.focal_px;
    f.lights = &p.size_params;
    return f;
}

void particle_style_frame_config(const ParticleStyle& style, FrameConfig* c) {
    std::memcpy(c->background, style.background, sizeof(c->background));
    if (style.fill == FillMode::solid)
        std::memcpy(c->paper, style.fill_colour, sizeof(c->paper));
    else
        std::memcpy(c->paper, style.background, sizeof(c->paper));
    c->constant_tone = 0.0f;
    c->silhouettes = false;
    c->refinement_budget = 0;
    c->strokes = false;
    if (c->particle_fades) c->depth_readback = true;
}

static_assert(kFrameSettings.particle_budget.fallback == kDefaultParticleTreePoints,
              "one default particle budget");

Status pipeline_particle_init(ParticleStage* s, const Asset& asset, const FrameConfig& c) {
    Status st =
        particle_stage_init(s, asset, *c.particle_style, c.width, c.height, c.particle_budget);
    if (st.ok() && c.particle_fades && s->enabled) st = particle_stage_enable_visibility_fades(s);
    return st;
}

void pipeline_particle_frame(Pipeline* p, ParticleStage* s, const AnimationState& state,
                             StageTimes* t) {
    pipeline_update(p, state, t);
    StageClock::time_point clock = StageClock::now();
    particle_stage_update(s, pipeline_particle_input(*p));
    if (t) t->strokes += ms_since(&clock);
    renderer_draw_mesh(&p->renderer, p->view_projection, p->vertex_positions.get(),
                       p->asset->mesh.vertex_count);
    ParticleVisibility& v = s->visibility;
    v.applied = false;
    if (v.enabled && s->enabled && p->renderer.config.depth_copy &&
        v.width == p->renderer.config.width && v.height == p->renderer.config.height) {
        renderer_read_depth(&p->renderer, v.scratch.get(), v.depth.get());
        particle_visibility_apply(&v, s->strokes.get(), s->stroke_id.get(), &s->stroke_count);
        s->stats.strokes = s->stroke_count;
    }
    particle_stage_draw(s, p->renderer.ink_fbo, v.applied ? 0u : p->renderer.depth_tex);
    p->renderer.gl.BindFramebuffer(GL_FRAMEBUFFER, p->renderer.fbo);
    renderer_check_errors(&p->renderer, "particle strokes");
    p->renderer.gl.Finish();
    if (t) t->draw += ms_since(&clock);
}

uint32_t particle_visible_strokes(const Pipeline& p, const ParticleStage& s, const float* depth,
                                  VisibleStroke* out, uint32_t capacity) {
    const int w = p.config.width, h = p.config.height;
    uint32_t n = 0;
    for (uint32_t k = 0; k < s.stroke_count && n < capacity; ++k) {
        const StrokeInstance& st = s.strokes[k];
        const int px = int(std::floor(st.x)), py = int(std::floor(st.y));
        if (px < 0 || py < 0 || px >= w || py >= h || st.depth > 1.0f) continue;
        // Hidden, as kStrokeVs tests; with visibility fades the strokes carry their
        // visibility in their opacity and are drawn untested.
        if (!s.visibility.applied && stroke_hidden(st, depth, w, h)) continue;
        out[n++] =
            VisibleStroke{s.stroke_id[k], st.x, st.y, st.angle, st.length, st.width, st.alpha};
    }
    return n;
}

}  // namespace stipple
