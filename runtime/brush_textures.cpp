#include "runtime/brush_textures.h"

#include <algorithm>
#include <cmath>

namespace stipple {

namespace {

// Integer hash of two coordinates and a seed, to [0, 1).
float noise(int x, int y, uint32_t seed) {
    uint32_t h = uint32_t(x) * 0x8da6b343u ^ uint32_t(y) * 0xd8163841u ^ seed * 0xcb1ab31fu;
    h ^= h >> 15;
    h *= 0x2c1b3c6du;
    h ^= h >> 12;
    h *= 0x297a2d39u;
    h ^= h >> 15;
    return float(h >> 8) / 16777216.0f;
}

// 1 inside (d < 0), 0 outside, a linear ramp one texel wide across the edge.
float inside(float signed_distance, float texel) {
    return std::clamp(0.5f - signed_distance / texel, 0.0f, 1.0f);
}

struct Texel {
    float coverage, ink;
};

// (u, v) in [-1, 1]^2: u along the stroke, v across; `texel` is one texel in those units.
Texel long_thin(float u, float v, int x, int y, float texel) {
    const float half_width = 0.32f * std::sqrt(std::max(1.0f - u * u * u * u, 0.0f));
    const float edge = inside(std::abs(v) - half_width, texel) * inside(std::abs(u) - 0.97f, texel);
    // Bristle streaks: the paint varies across the stroke and barely along it.
    const float streak = 0.55f + 0.45f * noise(0, int((v + 1.0f) * 12.0f), 11u);
    (void)x;
    (void)y;
    return {edge * streak, 1.0f};
}

Texel round_dab(float u, float v, int x, int y, float texel) {
    const float r = std::sqrt(u * u + v * v);
    const float edge =
        inside(r - 0.9f + 0.08f * noise(int(std::atan2(v, u) * 5.0f), 0, 5u), 2.0f * texel);
    return {edge * (0.8f + 0.2f * noise(x / 3, y / 3, 7u)), 1.0f};
}

Texel crayon(float u, float v, int x, int y, float texel) {
    const float half_width = 0.45f * std::min(1.0f, (1.0f - std::abs(u)) * 6.0f);
    const float edge = inside(std::abs(v) - half_width, texel) * inside(std::abs(u) - 0.95f, texel);
    // Paper grain: wax catches the tops of the grain, skips the valleys.
    const float grain = noise(x, y, 3u) * 0.6f + noise(x / 2, y / 2, 9u) * 0.4f;
    return {edge * (grain > 0.38f ? 1.0f : 0.25f), 1.0f};
}

// A tuft: a leaf standing on the stroke's axis, filled, with an inked outline.
Texel graftal(float u, float v, int, int, float texel) {
    const float a = 0.42f, b = 0.95f;  // semi-axes along and across
    const float cv = v + 0.05f;
    const float r = std::sqrt((u / a) * (u / a) + (cv / b) * (cv / b));
    const float d = (r - 1.0f) * a;  // about the distance to the outline, in u units
    const float coverage = inside(d, texel);
    const float ink = 1.0f - inside(d + 0.14f, texel);  // the outer band is ink
    return {coverage, ink};
}

Texel solid(float u, float v, int, int, float texel) {
    return {inside(std::abs(v) - 0.5f, texel) * inside(std::abs(u) - 0.98f, texel), 1.0f};
}

uint8_t to_byte(float f) {
    return uint8_t(std::lround(std::clamp(f, 0.0f, 1.0f) * 255.0f));
}

}  // namespace

void make_brush_atlas(uint8_t* texels) {
    using Shape = Texel (*)(float, float, int, int, float);
    const Shape shapes[kBrushCount] = {long_thin, round_dab, crayon, graftal, solid};
    const int row = kBrushCount * kBrushTile;
    const float texel = 2.0f / float(kBrushTile);
    for (int b = 0; b < kBrushCount; ++b)
        for (int y = 0; y < kBrushTile; ++y)
            for (int x = 0; x < kBrushTile; ++x) {
                const float u = (float(x) + 0.5f) * texel - 1.0f;
                const float v = (float(y) + 0.5f) * texel - 1.0f;
                const Texel t = shapes[b](u, v, x, y, texel);
                uint8_t* out = texels + (size_t(y) * row + size_t(b) * kBrushTile + x) * 2;
                out[0] = to_byte(t.coverage);
                out[1] = to_byte(t.ink);
            }
}

}  // namespace stipple
