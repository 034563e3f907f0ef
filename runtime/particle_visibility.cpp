#include "runtime/particle_visibility.h"

#include <algorithm>
#include <cmath>

namespace stipple {

Status particle_visibility_init(ParticleVisibility* v, uint32_t particles, int width, int height,
                                int fade_frames) {
    *v = ParticleVisibility();
    if (fade_frames < 1 || fade_frames > 255 || width <= 0 || height <= 0)
        return make_status(StatusCode::invalid_argument,
                           "visibility fades: fade frames %d or size %dx%d out of range",
                           fade_frames, width, height);
    const size_t pixels = size_t(width) * size_t(height);
    if (!alloc(&v->scratch, pixels * 4) || !alloc(&v->depth, pixels) ||
        !alloc(&v->alpha, std::max(particles, 1u)) ||
        !alloc(&v->last_frame, std::max(particles, 1u)))
        return make_status(StatusCode::out_of_memory, "out of memory for visibility fades");
    std::fill(v->depth.get(), v->depth.get() + pixels, 1.0f);
    std::fill(v->alpha.get(), v->alpha.get() + std::max(particles, 1u), 0.0f);
    std::fill(v->last_frame.get(), v->last_frame.get() + std::max(particles, 1u), 0u);
    v->width = width;
    v->height = height;
    v->step = 1.0f / float(fade_frames);
    v->enabled = true;
    return {};
}

bool stroke_hidden(const StrokeInstance& s, const float* depth, int width, int height) {
    const int px = int(std::floor(s.x)), py = int(std::floor(s.y));
    if (px < 0 || py < 0 || px >= width || py >= height) return false;
    const float mesh = depth[size_t(height - 1 - py) * size_t(width) + size_t(px)];
    return mesh < 1.0f && s.depth > mesh + 1e-5f;  // as the stroke shader tests it
}

void particle_visibility_apply(ParticleVisibility* v, StrokeInstance* strokes, uint32_t* ids,
                               uint32_t* count) {
    v->hidden = v->dropped = 0;
    uint32_t n = 0;
    for (uint32_t k = 0; k < *count; ++k) {
        const uint32_t id = ids[k];
        const bool hidden = stroke_hidden(strokes[k], v->depth.get(), v->width, v->height);
        v->hidden += hidden;
        const float target = hidden ? 0.0f : 1.0f;
        float& a = v->alpha[id];
        // A stroke not drawn last frame starts where it is: its own fades (fold, facing) ramp
        // it in, and one that appears hidden stays out.
        if (v->last_frame[id] + 1 != v->frame_index)
            a = target;
        else
            a = target > a ? std::min(a + v->step, 1.0f) : std::max(a - v->step, 0.0f);
        v->last_frame[id] = v->frame_index;
        if (a <= 0.0f) {
            ++v->dropped;
            continue;
        }
        strokes[n] = strokes[k];
        strokes[n].alpha *= a;
        ids[n++] = id;
    }
    *count = n;
    ++v->frame_index;
    v->applied = true;
}

}  // namespace stipple
