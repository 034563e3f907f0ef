#include "runtime/particle_stage.h"

#include <algorithm>
#include <cmath>

namespace stipple {

static_assert(kNoParent == format::kNoParticleParent, "one root marker");

namespace {

// Stage 1's scratch (ParticleStage::asked) holds this many particles, not the whole tree: the
// adjust criterion is asked in chunks (41 bytes per particle saved: 10.7 MB at 262,144).
constexpr uint32_t kAskChunk = 4096;

bool style_valid(const ParticleStyle& s) {
    auto in = [](float v, float lo, float hi) { return v >= lo && v <= hi; };
    return in(s.spacing_px, 0.5f, 1024.0f) && in(s.silhouette_spacing_px, 0.5f, 1024.0f) &&
           in(s.silhouette_band, 0.0f, 1.0f) && in(s.length, 0.0f, 64.0f) &&
           in(s.width, 0.0f, 64.0f) && in(s.bin_size, 0.1f, 64.0f) && s.bin_cap >= 0 &&
           s.bin_cap <= 65535 && s.fade_frames >= 1 && s.fade_frames <= 255 &&
           in(s.opacity, 0.0f, 1.0f);
}

// A node whose whole cluster lies outside the image stays folded, whatever the criterion
// says (view-frustum culling of the simplification hierarchy, GI'01 §2): its descendants lie
// within about twice its radius, and their strokes reach half a stroke's length further. So a
// close-up unfolds only what it shows (at zoom 8 on the walk, 640x480: 190k active particles
// of 262k without this).
void fold_outside_view(const ParticleStage& s, uint8_t* unfold) {
    const ParticleSamples& p = s.asked;
    const float stroke =
        0.5f * s.style.length * std::max(s.style.spacing_px, s.style.silhouette_spacing_px);
    const float w = float(s.frame.width), h = float(s.frame.height);
    for (uint32_t k = 0; k < p.count; ++k) {
        const float reach = 2.5f * p.radius_px[k] + stroke;
        if (p.x[k] + reach < 0.0f || p.y[k] + reach < 0.0f || p.x[k] - reach > w ||
            p.y[k] - reach > h)
            unfold[k] = 0;
    }
}

// Stage 1's question, answered from the particles transformed for this frame's view, a chunk
// of kAskChunk at a time (each answer depends on its own particle only).
void decide(const uint32_t* ids, uint32_t count, uint8_t* unfold, void* user) {
    ParticleStage* s = static_cast<ParticleStage*>(user);
    for (uint32_t first = 0; first < count; first += s->asked.capacity) {
        const uint32_t n = std::min(count - first, s->asked.capacity);
        transform_particles(s->frame, ids + first, n, nullptr, s->style.field, &s->asked);
        for (uint32_t k = 0; k < s->asked.count; ++k)
            s->asked.unfolded[k] = (s->set.state[ids[first + k]] & kParticleUnfolded) != 0;
        if (s->style.adjust)
            s->style.adjust(s->style, s->asked, unfold + first, s->style.user);
        else
            particle_style_adjust(s->style, s->asked, unfold + first);
        fold_outside_view(*s, unfold + first);
    }
}

// The tree's parents over the asset's points: its PTRE, or the rule (runtime/particle_tree.h)
// over the bind pose. The temporary particles are not in the tree: they join and leave per
// view (runtime/particle_temporary.h).
Status tree_parents(ParticleStage* s, const Asset& asset) {
    const uint32_t n = asset.points.point_count;
    if (asset.particle_parent) {
        s->tree.parent = asset.particle_parent;
        return {};
    }
    s->parent = make_buffer<uint32_t>(n);
    Buffer<float> bind = make_buffer<float>(size_t(n) * 3);
    if (!s->parent || !bind)
        return make_status(StatusCode::out_of_memory, "out of memory for %u particles", n);
    particle_bind_positions(asset.mesh, asset.points, bind.get());
    s->tree.parent = s->parent.get();
    return particle_parents(n, bind.get(), INFINITY, s->parent.get());
}

}  // namespace

Status particle_stage_init(ParticleStage* s, const Asset& asset, const ParticleStyle& style,
                           int width, int height, uint32_t tree_points, uint32_t list_points) {
    *s = ParticleStage();
    if (!style_valid(style))
        return make_status(StatusCode::invalid_argument,
                           "particle style '%s': a value is out of its range",
                           style.name ? style.name : "");
    s->style = style;
    s->width = width;
    s->height = height;
    Status st = tree_parents(s, asset);
    const uint32_t* parents = s->tree.parent;
    if (st.ok()) st = particle_tree_build(&s->tree, asset.points.point_count, parents);
    if (st.ok()) st = temporary_particles_build(&s->temporary, asset, tree_points);
    const uint32_t n = s->temporary.count;  // ids: the tree's, then the temporary slots
    if (st.ok())
        st = particle_set_init(&s->set, s->tree, style.fade_frames, list_points, n - s->tree.count);
    if (!st.ok()) return st;
    const uint32_t m = s->set.list_capacity;  // listed at most: samples and strokes
    s->bin_count = particle_bin_count(width, height, style);
    s->bins = make_buffer<uint16_t>(s->bin_count);
    s->strokes = make_buffer<StrokeInstance>(m);
    s->stroke_id = make_buffer<uint32_t>(m);
    s->facing_alpha = make_buffer<float>(n);
    s->last_frame = make_buffer<uint32_t>(n);
    if (!particle_samples_init(&s->asked, std::min(m, kAskChunk)) ||
        !particle_samples_init(&s->samples, m) || !s->bins || !s->strokes || !s->stroke_id ||
        !s->facing_alpha || !s->last_frame)
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
    return particle_renderer_init(&s->renderer, gl, s->set.list_capacity);
}

void particle_stage_adjust_tree(ParticleStage* s, const ParticleFrame& frame) {
    if (!s->enabled) return;
    s->frame = frame;
    s->frame.points = &s->temporary.view;  // the asset's points and the temporary ones
    // Recomputed radii cover the asset's points only; with temporary particles the tree runs
    // on the bind radii (a stretch changes its density by the stretch, as for the stipples'
    // hierarchy without relevance updates).
    if (s->temporary.slots > 0) s->frame.radius = nullptr;
    particles_adjust_tree(&s->set, s->tree, decide, s);
}

void particle_stage_adjust_temporaries(ParticleStage* s) {
    if (!s->enabled) return;
    temporary_particles_update(&s->temporary, &s->set, s->frame, s->style);
}

void particle_stage_adjust_finish(ParticleStage* s) {
    if (!s->enabled) return;
    particles_adjust_finish(&s->set);
    temporary_particles_release(&s->temporary, &s->set);
}

void particle_stage_adjust(ParticleStage* s, const ParticleFrame& frame) {
    particle_stage_adjust_tree(s, frame);
    // Temporary particles per view (GI'01 §5), then the merge and fades of every member.
    particle_stage_adjust_temporaries(s);
    particle_stage_adjust_finish(s);
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
                                           s->stroke_id.get(), s->set.list_capacity, s->style.user);
    else
        s->stroke_count =
            particle_style_strokes(s->style, s->samples, s->width, s->height, s->bins.get(),
                                   s->strokes.get(), s->stroke_id.get(), s->set.list_capacity);
    s->stroke_count = std::min(s->stroke_count, s->set.list_capacity);
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

Status particle_stage_enable_visibility_fades(ParticleStage* s) {
    return particle_visibility_init(&s->visibility, s->set.capacity, s->width, s->height,
                                    s->style.fade_frames);
}

void particle_stage_destroy(ParticleStage* s) {
    particle_renderer_destroy(&s->renderer);
    *s = ParticleStage();
}

}  // namespace stipple
