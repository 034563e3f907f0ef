#include "runtime/particle_style.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace stipple {

namespace {

// The built-in styles, after the paper's figures (GI'01 §4).
ParticleStyle make(const char* name) {
    ParticleStyle s;
    s.name = name;
    return s;
}

ParticleStyle painterly_long() {  // §4.3 top: long thin strokes, random orientation, lit
    ParticleStyle s = make("painterly-long");
    s.spacing_px = 5.0f;
    s.length = 3.2f, s.width = 1.0f;
    return s;
}

ParticleStyle painterly_dab() {  // §4.3 bottom: round dabs
    ParticleStyle s = make("painterly-dab");
    s.brush = Brush::round_dab;
    s.spacing_px = 4.5f;
    s.length = s.width = 1.8f;
    return s;
}

ParticleStyle sketch() {  // §4.4: choppy crayon strokes tangent to the outline, on silhouettes
    ParticleStyle s = make("sketch");
    s.spacing_px = 12.0f;
    s.silhouette_band = 0.35f;
    s.silhouette_spacing_px = 3.5f;
    s.silhouette_only = true;
    s.field = OrientationField::normal_tangent;
    s.angle_jitter = 0.25f;
    s.brush = Brush::crayon;
    s.length = 2.6f, s.width = 0.4f;
    s.tone = ToneRule::ink;
    s.ink[0] = s.ink[1] = s.ink[2] = 0.25f;
    s.opacity = 0.8f;
    return s;
}

ParticleStyle cartoon() {  // §4.5 top: solid fill, strong black strokes on the silhouette
    ParticleStyle s = make("cartoon");
    s.spacing_px = 16.0f;
    s.silhouette_band = 0.25f;
    s.silhouette_spacing_px = 4.0f;
    s.silhouette_only = true;
    s.fill = FillMode::solid;
    s.fill_colour[0] = 1.0f, s.fill_colour[1] = 0.85f, s.fill_colour[2] = 0.55f;
    s.field = OrientationField::normal_tangent;
    s.brush = Brush::solid;
    s.length = 1.8f, s.width = 0.5f;
    s.min_width_px = 2.0f;
    s.tone = ToneRule::ink;
    s.ink[0] = s.ink[1] = s.ink[2] = 0.0f;
    s.opacity = 1.0f;
    return s;
}

ParticleStyle graftals() {  // §4.5 bottom: Markosian-style tufts, binned
    ParticleStyle s = cartoon();
    s.name = "graftals";
    s.fill_colour[0] = 0.55f, s.fill_colour[1] = 0.8f, s.fill_colour[2] = 0.45f;
    s.silhouette_band = 0.4f;
    s.silhouette_spacing_px = 9.0f;
    s.brush = Brush::graftal;
    s.length = 1.4f, s.width = 2.0f;
    s.bin_size = 1.5f;
    s.bin_cap = 1;
    return s;
}

ParticleStyle charcoal() {  // §4.6: a few long, thick overlapping silhouette strokes
    ParticleStyle s = make("charcoal");
    s.spacing_px = 30.0f;
    s.silhouette_band = 0.45f;
    s.silhouette_spacing_px = 9.0f;
    s.silhouette_only = true;
    s.field = OrientationField::normal_tangent;
    s.brush = Brush::crayon;
    s.length = 3.0f, s.width = 0.7f;
    s.tone = ToneRule::ink;
    s.ink[0] = s.ink[1] = s.ink[2] = 0.08f;
    s.opacity = 0.7f;
    return s;
}

ParticleStyle two_tone() {  // §4.7: light and dark strokes on neutral grey
    ParticleStyle s = make("two-tone");
    s.spacing_px = 5.0f;
    // Strokes across the larger curvature where the asset stores it (stipple-bake --curvature;
    // else random): hatching that follows the form (GI'01 §1's curvature fields).
    s.field = OrientationField::curvature;
    s.background[0] = s.background[1] = s.background[2] = 0.5f;
    s.fill_colour[0] = s.fill_colour[1] = s.fill_colour[2] = 0.5f;
    s.brush = Brush::solid;
    s.length = 1.6f, s.width = 0.45f;
    s.tone = ToneRule::threshold;
    s.dark_below = 0.35f, s.light_above = 0.75f;
    s.ink[0] = s.ink[1] = s.ink[2] = 0.0f;
    s.opacity = 1.0f;
    return s;
}

ParticleStyle ink() {  // §4.8: black strokes densely placed where dark
    ParticleStyle s = two_tone();
    s.name = "ink";
    s.spacing_px = 3.5f;
    s.background[0] = s.background[1] = s.background[2] = 1.0f;
    s.fill_colour[0] = s.fill_colour[1] = s.fill_colour[2] = 1.0f;
    s.light_above = 2.0f;  // no light strokes
    s.dark_below = 0.45f;
    s.length = 2.0f, s.width = 0.6f;
    return s;
}

const ParticleStyle kStyles[] = {painterly_long(), painterly_dab(), sketch(),   cartoon(),
                                 graftals(),       charcoal(),      two_tone(), ink()};
constexpr int kStyleCount = int(sizeof(kStyles) / sizeof(kStyles[0]));

// Relative band around the density target in which a node keeps its fold state.
constexpr float kHysteresis = 0.15f;

uint8_t to_byte(float f) {
    return uint8_t(std::lround(std::clamp(f, 0.0f, 1.0f) * 255.0f));
}

bool near_silhouette(const ParticleStyle& s, float facing) {
    return s.silhouette_band > 0.0f && std::abs(facing) < s.silhouette_band;
}

// The stroke colour of a particle, or false when the tone rule draws none.
bool stroke_colour(const ParticleStyle& s, float intensity, uint8_t* rgb) {
    float c[3] = {0.0f, 0.0f, 0.0f};
    switch (s.tone) {
        case ToneRule::ink:
            std::memcpy(c, s.ink, sizeof(c));
            break;
        case ToneRule::lit:
            for (int k = 0; k < 3; ++k) c[k] = s.ink[k] + (s.light[k] - s.ink[k]) * intensity;
            break;
        case ToneRule::threshold:
            if (intensity < s.dark_below)
                std::memcpy(c, s.ink, sizeof(c));
            else if (intensity > s.light_above)
                std::memcpy(c, s.light, sizeof(c));
            else
                return false;
            break;
    }
    for (int k = 0; k < 3; ++k) rgb[k] = to_byte(c[k]);
    return true;
}

float bin_px(const ParticleStyle& s) {
    return std::max(
        s.bin_size * std::min(s.spacing_px,
                              s.silhouette_band > 0.0f ? s.silhouette_spacing_px : s.spacing_px),
        1.0f);
}

// Styles registered by users (register_particle_style), with their names' storage.
struct UserStyles {
    ParticleStyle styles[kMaxUserParticleStyles];
    char names[kMaxUserParticleStyles][32];
    int count = 0;
};
UserStyles& user_styles() {
    static UserStyles u;
    return u;
}

bool valid_style_name(const char* name) {
    const size_t n = name ? std::strlen(name) : 0;
    if (n == 0 || n > 31) return false;
    for (size_t i = 0; i < n; ++i) {
        const char c = name[i];
        if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '_'))
            return false;
    }
    return true;
}

}  // namespace

const ParticleStyle* find_particle_style(const char* name) {
    if (!name) return nullptr;
    for (int i = 0; i < particle_style_count(); ++i)
        if (std::strcmp(particle_style_at(i).name, name) == 0) return &particle_style_at(i);
    return nullptr;
}

const ParticleStyle& particle_style_at(int i) {
    i = std::clamp(i, 0, particle_style_count() - 1);
    return i < kStyleCount ? kStyles[i] : user_styles().styles[i - kStyleCount];
}

int particle_style_count() {
    return kStyleCount + user_styles().count;
}

int particle_style_index(const ParticleStyle* style) {
    for (int i = 0; i < particle_style_count(); ++i)
        if (&particle_style_at(i) == style) return i;
    return -1;
}

int register_particle_style(const ParticleStyle& style) {
    UserStyles& u = user_styles();
    if (!valid_style_name(style.name) || find_particle_style(style.name) ||
        u.count == kMaxUserParticleStyles)
        return -1;
    std::memcpy(u.names[u.count], style.name, std::strlen(style.name) + 1);
    u.styles[u.count] = style;
    u.styles[u.count].name = u.names[u.count];
    return kStyleCount + u.count++;
}

void particle_style_adjust(const ParticleStyle& s, const ParticleSamples& p, uint8_t* unfold) {
    for (uint32_t k = 0; k < p.count; ++k) {
        // Off the silhouette a node unfolds only down to the coarse spacing (with
        // silhouette_only it then draws nothing), so the tree still reaches the silhouette's
        // particles below it.
        const bool silhouette = near_silhouette(s, p.facing[k]);
        const float spacing = silhouette ? s.silhouette_spacing_px : s.spacing_px;
        // Children are half the node's radius apart (runtime/particle_tree.h's levels). A
        // node stays as it is within kHysteresis of the target, so one that sits at the
        // threshold while the character moves does not fold and unfold every few frames.
        const float target = spacing * (p.unfolded[k] ? 1.0f - kHysteresis : 1.0f + kHysteresis);
        unfold[k] = p.depth[k] <= 1.0f && 0.5f * p.radius_px[k] > target;
    }
}

uint32_t particle_bin_count(int width, int height, const ParticleStyle& s) {
    const float b = bin_px(s);
    const uint64_t n =
        uint64_t(std::ceil(float(width) / b)) * uint64_t(std::ceil(float(height) / b));
    return uint32_t(std::min<uint64_t>(n, 1u << 20));
}

uint32_t particle_style_strokes(const ParticleStyle& s, const ParticleSamples& p, int width,
                                int height, uint16_t* bins, StrokeInstance* out, uint32_t* out_id,
                                uint32_t capacity) {
    const float b = bin_px(s);
    const uint32_t columns = uint32_t(std::ceil(float(width) / b));
    const uint32_t bin_count = particle_bin_count(width, height, s);
    std::fill(bins, bins + bin_count, uint16_t(0));
    uint32_t n = 0;
    for (uint32_t k = 0; k < p.count && n < capacity; ++k) {
        if (!(p.depth[k] <= 1.0f) || !(p.x[k] >= 0.0f && p.x[k] < float(width)) ||
            !(p.y[k] >= 0.0f && p.y[k] < float(height)) || p.alpha[k] <= 0.0f)
            continue;
        const bool silhouette = near_silhouette(s, p.facing[k]);
        if (s.silhouette_only && !silhouette) continue;
        StrokeInstance& st = out[n];
        if (!stroke_colour(s, p.intensity[k], st.colour)) continue;
        const uint32_t bin =
            std::min(uint32_t(p.y[k] / b) * columns + uint32_t(p.x[k] / b), bin_count - 1);
        if (s.bin_cap > 0 && bins[bin] >= s.bin_cap) continue;
        ++bins[bin];
        const float spacing = silhouette ? s.silhouette_spacing_px : s.spacing_px;
        st.x = p.x[k];
        st.y = p.y[k];
        st.depth = p.depth[k];
        st.angle =
            p.angle[k] +
            s.angle_jitter * (random_field_angle(p.id[k] ^ 0x9e3779b9u) / 3.14159265f - 1.0f);
        // Foreshortened with its direction, down to a dab (GI'01 §2 stage 3: the vector
        // "transformed into screen-space"; where it points at the eye its angle is not seen).
        st.width = std::max(s.width * spacing, s.min_width_px);
        st.length = std::max(s.length * spacing * p.foreshortening[k], st.width);
        st.brush = float(int(s.brush));
        st.alpha = s.opacity * p.alpha[k];
        st.colour[3] = 255;
        for (int c = 0; c < 3; ++c) st.fill[c] = to_byte(s.fill_colour[c]);
        st.fill[3] = 255;
        out_id[n++] = p.id[k];
    }
    return n;
}

}  // namespace stipple
