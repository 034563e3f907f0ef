// Particle styles (GI'01 §4): what each of the four stages does, as parameters plus optional
// callbacks. The eight built-in styles are the paper's: painterly-long, painterly-dab (§4.3),
// sketch (§4.4), cartoon and graftals (§4.5), charcoal (§4.6), two-tone (§4.7), ink (§4.8).
// A user style fills the same struct, and may replace the adjust criterion and the stroke rule
// with its own functions (GI'01 §2: "a user-supplied callback function decides whether to
// fold, unfold, or leave unchanged each particle").
#pragma once
#include <cstdint>

#include "runtime/brush_textures.h"
#include "runtime/particle_transform.h"

namespace stipple {

// Stage 2, the polygon pass.
enum class FillMode : uint8_t {
    depth_only = 0,  // depth for hiding strokes on the far side, no colour (GI'01 §4.3, §4.7)
    solid = 1,       // one flat colour, no lighting (cartoon, GI'01 §4.5)
};

// How stage 4 colours a particle's stroke.
enum class ToneRule : uint8_t {
    ink = 0,        // every stroke in the ink colour
    lit = 1,        // grey (or the ink colour) from the particle's lighting: painterly
    threshold = 2,  // ink where intensity < dark_below, light where > light_above, else none
};

// One stroke as stage 4 hands it to the GPU: an instanced quad (runtime/particle_renderer.h).
struct StrokeInstance {
    float x, y, depth, angle;  // centre in pixels (origin top-left), window depth, radians
    float length, width;       // pixels, along and across the stroke
    float brush;               // Brush index
    float alpha;               // opacity times the particle's fade
    uint8_t colour[4];         // the stroke's colour (RGB) and unused
    uint8_t fill[4];           // graftal fill colour
};
static_assert(sizeof(StrokeInstance) == 40, "instance layout");

struct ParticleStyle;

// Stage 1 criterion over transformed particles: unfold[k] = 1 to show particle k's children.
using ParticleAdjustFn = void (*)(const ParticleStyle& style, const ParticleSamples& particles,
                                  uint8_t* unfold, void* user);
// Stage 4 rule: writes at most `capacity` strokes for the particles and, for each, the id of
// the particle it belongs to (out_id); returns the count.
using ParticleStrokeFn = uint32_t (*)(const ParticleStyle& style, const ParticleSamples& particles,
                                      StrokeInstance* out, uint32_t* out_id, uint32_t capacity,
                                      void* user);

struct ParticleStyle {
    const char* name = "painterly-long";
    // Stage 1: a node unfolds while its children, half its projected relevance radius, would
    // be farther apart than spacing_px on screen (the screen-space density target; 15%
    // hysteresis).
    float spacing_px = 7.0f;
    // Particles with |N.V| below silhouette_band are near the silhouette: they unfold down to
    // silhouette_spacing_px; with silhouette_only the others stay folded and draw nothing.
    float silhouette_band = 0.0f;
    float silhouette_spacing_px = 7.0f;
    bool silhouette_only = false;
    // Stage 2.
    FillMode fill = FillMode::depth_only;
    float fill_colour[3] = {1.0f, 1.0f, 1.0f};
    float background[3] = {1.0f, 1.0f, 1.0f};
    // Stage 3.
    OrientationField field = OrientationField::random;
    float angle_jitter = 0.0f;  // radians, fixed per particle
    // Stage 4: strokes of length x width spacing_px units (the length foreshortened with the
    // orientation vector), binned so no bin of bin_size spacing_px units holds more than
    // bin_cap strokes (GI'01 Figure 6; 0: no binning: the tree alone sets the density).
    Brush brush = Brush::long_thin;
    float length = 3.0f, width = 0.9f;
    float min_width_px = 1.0f;
    ToneRule tone = ToneRule::lit;
    float ink[3] = {0.05f, 0.05f, 0.08f};
    float light[3] = {1.0f, 1.0f, 1.0f};
    float dark_below = 0.35f, light_above = 0.75f;  // ToneRule::threshold
    float opacity = 0.85f;
    float bin_size = 2.0f;
    int bin_cap = 0;
    // Frames a fade in or out takes (GI'01 §5).
    int fade_frames = 4;
    // Optional replacements of the built-in rules (nullptr: built in) and their user pointer.
    ParticleAdjustFn adjust = nullptr;
    ParticleStrokeFn strokes = nullptr;
    void* user = nullptr;
};

// The styles by name: the built-in ones, then those registered; nullptr for an unknown name.
const ParticleStyle* find_particle_style(const char* name);
// The i-th style (built-in ones first; i < particle_style_count()), for listings and the C
// API's style numbers.
const ParticleStyle& particle_style_at(int i);
int particle_style_count();
// Index of a style in that order, or -1.
int particle_style_index(const ParticleStyle* style);

// Registers a copy of `style` under its name (copied; 1-31 characters of [a-z0-9_-], not a
// name already taken) so find_particle_style and the C API find it. Returns its index, or -1
// (bad or taken name, or kMaxUserParticleStyles registered). Not thread-safe: register before
// creating the players that use it; a registered style lives until the process ends.
constexpr int kMaxUserParticleStyles = 16;
int register_particle_style(const ParticleStyle& style);

// The built-in stage 1 criterion (ParticleStyle::adjust == nullptr).
void particle_style_adjust(const ParticleStyle& style, const ParticleSamples& particles,
                           uint8_t* unfold);

// The built-in stage 4 rule: strokes for the particles in list order (coarse first), skipping
// those behind the camera or off the image, dropped by the tone rule or the silhouette band,
// or over their bin's cap. `bins` is scratch of particle_bin_count(width, height, style)
// counters. Writes each stroke's particle id to out_id. Returns the count written (at most
// `capacity`).
uint32_t particle_style_strokes(const ParticleStyle& style, const ParticleSamples& particles,
                                int width, int height, uint16_t* bins, StrokeInstance* out,
                                uint32_t* out_id, uint32_t capacity);

// Bins of the screen-space binning for an image of width x height pixels (at most 2^20).
uint32_t particle_bin_count(int width, int height, const ParticleStyle& style);

}  // namespace stipple
