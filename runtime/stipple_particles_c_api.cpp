// The C API's particle styles (runtime/stipple.h, docs/particles.md): user styles registered
// with C callbacks, adapted to runtime/particle_style.h's. The callbacks see the transformed
// particles in place (stipple_particles points into ParticleSamples), and write strokes in a
// layout identical to StrokeInstance, so no copy is made per frame.
#include <cstddef>
#include <cstdio>

#include "runtime/c_api_internal.h"
#include "runtime/particle_style.h"
#include "runtime/style.h"

static_assert(sizeof(stipple_stroke) == sizeof(stipple::StrokeInstance), "stroke layout");
static_assert(offsetof(stipple_stroke, length) == offsetof(stipple::StrokeInstance, length), "");
static_assert(offsetof(stipple_stroke, brush) == offsetof(stipple::StrokeInstance, brush), "");
static_assert(offsetof(stipple_stroke, rgba) == offsetof(stipple::StrokeInstance, colour), "");
static_assert(offsetof(stipple_stroke, fill) == offsetof(stipple::StrokeInstance, fill), "");

namespace {

using stipple::ParticleSamples;
using stipple::ParticleStyle;

// A registered style's C callbacks (the ParticleStyle's user pointer points here).
struct CCallbacks {
    stipple_adjust_fn adjust;
    stipple_strokes_fn strokes;
    void* user;
};
CCallbacks g_callbacks[stipple::kMaxUserParticleStyles];
int g_callback_count = 0;

stipple_particles view_of(const ParticleSamples& p) {
    stipple_particles v;
    v.count = p.count;
    v.id = p.id.get();
    v.x = p.x.get();
    v.y = p.y.get();
    v.depth = p.depth.get();
    v.radius_px = p.radius_px.get();
    v.intensity = p.intensity.get();
    v.facing = p.facing.get();
    v.angle = p.angle.get();
    v.foreshortening = p.foreshortening.get();
    v.alpha = p.alpha.get();
    v.unfolded = p.unfolded.get();
    return v;
}

void adjust_adapter(const ParticleStyle&, const ParticleSamples& p, uint8_t* unfold, void* user) {
    const CCallbacks* c = static_cast<const CCallbacks*>(user);
    const stipple_particles v = view_of(p);
    c->adjust(&v, unfold, c->user);
}

uint32_t strokes_adapter(const ParticleStyle&, const ParticleSamples& p,
                         stipple::StrokeInstance* out, uint32_t* out_id, uint32_t capacity,
                         void* user) {
    const CCallbacks* c = static_cast<const CCallbacks*>(user);
    const stipple_particles v = view_of(p);
    const uint32_t n =
        c->strokes(&v, reinterpret_cast<stipple_stroke*>(out), out_id, capacity, c->user);
    return n < capacity ? n : capacity;
}

int fail(const char* message) {
    stipple::c_api_fail(STIPPLE_ERROR_INVALID_ARGUMENT, message);
    return -1;
}

}  // namespace

int stipple_register_style(const stipple_style_desc* d) {
    if (!d || !d->name) return fail("stipple_register_style: NULL description or name");
    const ParticleStyle* base = stipple::find_particle_style(d->base ? d->base : "painterly-long");
    if (!base || stipple::particle_style_index(base) >= 8)
        return fail("stipple_register_style: the base is not a built-in particle style");
    if (stipple::find_style(d->name) >= 0 || stipple::find_particle_style(d->name))
        return fail("stipple_register_style: the name is taken");
    if (!(d->spacing_px == 0.0f || (d->spacing_px >= 0.5f && d->spacing_px <= 1024.0f)) ||
        d->fade_frames < 0 || d->fade_frames > 255)
        return fail("stipple_register_style: spacing_px or fade_frames out of range");
    if (g_callback_count == stipple::kMaxUserParticleStyles)
        return fail("stipple_register_style: 16 styles are registered already");
    ParticleStyle s = *base;
    s.name = d->name;
    if (d->spacing_px > 0.0f) s.spacing_px = s.silhouette_spacing_px = d->spacing_px;
    if (d->fade_frames > 0) s.fade_frames = d->fade_frames;
    CCallbacks& c = g_callbacks[g_callback_count];
    c = CCallbacks{d->adjust, d->strokes, d->user};
    s.adjust = d->adjust ? adjust_adapter : nullptr;
    s.strokes = d->strokes ? strokes_adapter : nullptr;
    s.user = &c;
    const int index = stipple::register_particle_style(s);
    if (index < 0)
        return fail("stipple_register_style: the name must be 1-31 characters of [a-z0-9_-]");
    ++g_callback_count;
    return stipple::kStyleTotal + index;
}
