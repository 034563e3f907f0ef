/* A particle style written by a user against the C callbacks of runtime/stipple.h
 * (docs/particles.md): blue cross-hatching.
 * Stage 1 unfolds particles while their children would be more than 6 px apart. (A coarse
 * particle stands for a whole region: folding it for facing away would keep the front of that
 * region from ever unfolding.)
 * Stage 4 draws one bar per particle that faces the viewer and is darker than 0.7, at 45
 * degrees on screen, and a second bar across it where darker than 0.35.
 * tests/runtime/test_particle_c_api.cpp registers it and checks its frames. */
#include <stdint.h>

#include "runtime/stipple.h"

static const float kSpacing = 6.0f;

static void hatching_adjust(const stipple_particles* p, uint8_t* unfold, void* user) {
    (void)user;
    for (uint32_t k = 0; k < p->count; ++k)
        unfold[k] = p->depth[k] <= 1.0f && 0.5f * p->radius_px[k] > kSpacing;
}

static stipple_stroke bar(const stipple_particles* p, uint32_t k, float angle) {
    stipple_stroke s;
    s.x = p->x[k];
    s.y = p->y[k];
    s.depth = p->depth[k];
    s.angle = angle;
    s.length = 2.2f * kSpacing;
    s.width = 1.5f;
    s.brush = (float)STIPPLE_BRUSH_SOLID;
    s.alpha = 0.9f * p->alpha[k];
    s.rgba[0] = 20, s.rgba[1] = 40, s.rgba[2] = 200, s.rgba[3] = 255;
    s.fill[0] = s.fill[1] = s.fill[2] = s.fill[3] = 255;
    return s;
}

static uint32_t hatching_strokes(const stipple_particles* p, stipple_stroke* out, uint32_t* id,
                                 uint32_t capacity, void* user) {
    (void)user;
    uint32_t n = 0;
    for (uint32_t k = 0; k < p->count && n < capacity; ++k) {
        if (p->depth[k] > 1.0f || p->facing[k] <= 0.0f || p->intensity[k] >= 0.7f) continue;
        id[n] = p->id[k];
        out[n++] = bar(p, k, 0.785398f);
        if (p->intensity[k] < 0.35f && n < capacity) {
            id[n] = p->id[k];
            out[n++] = bar(p, k, -0.785398f);
        }
    }
    return n;
}

/* Registers the style once; returns its number for stipple_player_desc.style, or -1. */
int register_blue_hatching(void) {
    static int style = -2;
    if (style == -2) {
        stipple_style_desc d = {0};
        d.name = "blue-hatching";
        d.base = "ink";
        d.adjust = hatching_adjust;
        d.strokes = hatching_strokes;
        style = stipple_register_style(&d);
    }
    return style;
}
