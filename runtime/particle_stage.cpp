#include "runtime/particle_stage.h"

#include <algorithm>
#include <cmath>

namespace stipple {

static_assert(kNoParent == format::kNoParticleParent, "one root marker");

namespace {

bool style_valid(const ParticleStyle& s) {
    auto in = [](float v, float lo, float hi) { return v >= lo && v <= hi; };
    return in(s.spacing_px, 0.5f, 1024.0f) && in(s.silhouette_spacing_px, 0.5f, 1024.0f) &&
           in(s.silhouette_band, 0.0f, 1.0f) && in(s.length, 0.0f, 64.0f) &&
           in(s.width, 0.0f, 64.0f) && in(s.bin_size, 0.1f, 64.0f) && s.bin_cap >= 0 &&
           s.bin_cap <= 65535 && s.fade_frames >= 1 && s.fade_frames <= 255 &&
           in(s.opacity, 0.0f, 1.0f);
}

// The hierarchy's points in the bind pose (Thesis Alg. 6.3 on the unposed mesh).
void bind_positions(const Asset& a, float* out) {
    const PointsView& p = a.points;
    for (uint32_t i = 0; i < p.point_count; ++i) {
        const uint32_t* t = a.mesh.indices + size_t(p.host_triangle[i]) * 3;
        const float u = p.bary_u[i], v = p.bary_v[i], w = 1.0f - u - v;
        for (int k = 0; k < 3; ++k)
            out[size_t(i) * 3 + k] = u * a.mesh.positions[size_t(t[0]) * 3 + k] +
                                     v * a.mesh.positions[size_t(t[1]) * 3 + k] +
                                     w * a.mesh.positions[size_t(t[2]) * 3 + k];
    }
}

// Stage 1's question, answered from the particles transformed for this frame's view.
void decide(const uint32_t* ids, uint32_t count, uint8_t* unfold, void* user) {
    ParticleStage* s = static_cast<ParticleStage*>(user);
    transform_particles(s->frame, ids, count, nullptr, s->style.field, &s->asked);
    for (uint32_t k = 0; k < s->asked.count; ++k)
        s->asked.unfolded[k] = (s->set.state[ids[k]] & kParticleUnfolded) != 0;
    if (s->style.adjust)
        s->style.adjust(s->style, s->asked, unfold, s->style.user);
    else
        particle_style_adjust(s->style, s->asked, unfold);
}

}  // namespace

Status particle_stage_init(ParticleStage* s, const Asset& asset, const ParticleStyle& style,
                           int width, int height) {
    *s = ParticleStage();
    if (!style_valid(style))
        return make_status(StatusCode::invalid_argument,
                           "particle style '%s': a value is out of its range",
                           style.name ? style.name : "");
    const uint32_t n = asset.points.point_count;
    s->style = style;
    s->width = width;
    s->height = height;
    // The tree the bake stored (PTRE), else the same rule run here (runtime/particle_tree.h).
    const uint32_t* parents = asset.particle_parent;
    Status st;
    if (!parents) {
        s->parent = make_buffer<uint32_t>(n);
        Buffer<float> bind = make_buffer<float>(size_t(n) * 3);
        if (!s->parent || !bind)
            return make_status(StatusCode::out_of_memory, "out of memory for %u particles", n);
        bind_positions(asset, bind.get());
        st = particle_parents(n, bind.get(), INFINITY, s->parent.get());
        parents = s->parent.get();
    }
    if (st.ok()) st = particle_tree_build(&s->tree, n, parents);
    if (st.ok()) st = particle_set_init(&s->set, s->tree, style.fade_frames);
    if (!st.ok()) return st;
    s->bin_count = particle_bin_count(width, height, style);
    s->bins = make_buffer<uint16_t>(s->bin_count);
    s->strokes = make_buffer<StrokeInstance>(n);
    s->stroke_id = make_buffer<uint32_t>(n);
    s->facing_alpha = make_buffer<float>(n);
    s->last_frame = make_buffer<uint32_t>(n);
    if (!particle_samples_init(&s->asked, n) || !particle_samples_init(&s->samples, n) ||
        !s->bins || !s->strokes || !s->stroke_id || !s->facing_alpha || !s->last_frame)
        return make_status(StatusCode::out_of_memory, "out of memory for %u particles", n);
    std::fill(s->last_frame.get(), s->last_frame.get() + n, 0u);  // "not drawn last frame"
    std::fill(s->facing_alpha.get(), s->facing_alpha.get() + n, 0.0f);
    s->frame_index = 2;
    s->enabled = n > 0;
    return {};
}

namespace {

constexpr float kHorizonDither = 0.1f;

// Particles turning their back fade out (and in when they come round) at the fold's pace,
// instead of popping where the outline passes over them (GI'01 §5's fades, applied to the
// visibility the back face decides; what other parts hide still pops).
void fade_back_faces(ParticleStage* s) {
    ParticleSamples& p = s->samples;
    const float step = s->set.fade_step;
    for (uint32_t k = 0; k < p.count; ++k) {
        const uint32_t id = p.id[k];
        // The horizon is dithered per particle (+-kHorizonDither in N.V), so a flat face
        // turning away fades out over a few frames, not all in one.
        const float horizon = kHorizonDither * (random_field_angle(id) / 3.14159265f - 1.0f);
        const float target = p.facing[k] > horizon ? 1.0f : 0.0f;
        float& a = s->facing_alpha[id];
        if (s->last_frame[id] + 1 != s->frame_index)
            a = target;
        else
            a = target > a ? std::min(a + step, 1.0f) : std::max(a - step, 0.0f);
        s->last_frame[id] = s->frame_index;
        p.alpha[k] *= a;
    }
    ++s->frame_index;
}

}  // namespace

Status particle_stage_init_gl(ParticleStage* s, const GlApi& gl) {
    if (!s->enabled) return {};
    return particle_renderer_init(&s->renderer, gl, s->set.capacity);
}

void particle_stage_adjust(ParticleStage* s, const ParticleFrame& frame) {
    if (!s->enabled) return;
    s->frame = frame;
    particles_adjust(&s->set, s->tree, decide, s);
}

void particle_stage_transform(ParticleStage* s) {
    if (!s->enabled) return;
    transform_particles(s->frame, s->set.list.get(), s->set.count, s->set.alpha.get(),
                        s->style.field, &s->samples);
    fade_back_faces(s);
}

void particle_stage_build_strokes(ParticleStage* s) {
    if (!s->enabled) return;
    if (s->style.strokes)
        s->stroke_count = s->style.strokes(s->style, s->samples, s->strokes.get(),
                                           s->stroke_id.get(), s->set.capacity, s->style.user);
    else
        s->stroke_count =
            particle_style_strokes(s->style, s->samples, s->width, s->height, s->bins.get(),
                                   s->strokes.get(), s->stroke_id.get(), s->set.capacity);
    s->stroke_count = std::min(s->stroke_count, s->set.capacity);
    ParticleStageStats& t = s->stats;
    t.active = s->set.active_count;
    t.listed = s->set.count;
    t.joined = s->set.joined;
    t.left = s->set.left;
    t.asked = s->set.asked;
    t.strokes = s->stroke_count;
}

void particle_stage_update(ParticleStage* s, const ParticleFrame& frame) {
    particle_stage_adjust(s, frame);
    particle_stage_transform(s);
    particle_stage_build_strokes(s);
}

void particle_stage_draw(ParticleStage* s, GLuint framebuffer, GLuint depth_texture) {
    if (!s->enabled) return;
    particle_renderer_draw(&s->renderer, framebuffer, depth_texture, s->width, s->height,
                           s->strokes.get(), s->stroke_count);
}

void particle_stage_destroy(ParticleStage* s) {
    particle_renderer_destroy(&s->renderer);
    *s = ParticleStage();
}

}  // namespace stipple
