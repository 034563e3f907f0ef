// Frame settings: what a player draws (image size, camera, tone, budgets), with every
// default and limit in one table, kFrameSettings (sokol's _sg_def habit). The C API
// (stipple_player_create, stipple_player_desc_resolve), the C++ API (pipeline_init,
// pipeline_set_view) and the CLIs all go through resolve_frame_config; the renderer's and the
// size rule's parameters are filled from its result. No other file writes a default or a
// limit of a frame setting.
#pragma once
#include <cstdint>

#include "anim/anim.h"
#include "runtime/status.h"
#include "runtime/style.h"
#include "runtime/thread_pool.h"

namespace stipple {

struct ParticleStyle;  // runtime/particle_style.h

// Default and allowed range (inclusive) of one numeric frame setting.
template <typename T>
struct Setting {
    T fallback;  // the default
    T min, max;
    constexpr bool contains(T v) const { return v >= min && v <= max; }  // false for NaN
};

// constant_tone's "no constant tone": Lambert lighting decides each point's tone.
inline constexpr float kLightingTone = -1.0f;

// Directional lights the tone follows (thesis §3.1: tone from Lambert lighting): each point's
// lighting is ambient + the sum of intensity * max(N.L, 0) over the lights, clamped to [0, 1],
// mapped from dark_tone (0) to white (1).
inline constexpr int kMaxLights = 4;
struct Light {
    float direction[3] = {-0.5f, 0.6f, 0.6f};  // toward the light; normalised when resolved
    float intensity = 1.0f;                    // in [0, 16]
    // true: the direction is in camera space (it turns with the camera: the CLI's key light
    // from the upper left); false: in world space.
    bool camera_space = true;
};

// Where a frame's point stages (place, relevance, size) run: on the CPU, or in a GLES 3.0
// vertex shader with transform feedback (runtime/gpu_stages.h, docs/gpu-path.md).
enum class FramePath : uint8_t { cpu, gpu };

// The one table of frame-setting defaults and limits.
struct FrameSettings {
    Setting<int> width{640, 16, 16384};  // pixels
    Setting<int> height{480, 16, 16384};
    Setting<float> zoom{1.0f, 0.01f, 1000.0f};
    Setting<float> yaw_degrees{0.0f, -3600.0f, 3600.0f};
    Setting<float> pitch_degrees{0.0f, -90.0f, 90.0f};
    Setting<float> fov_degrees{30.0f, 1.0f, 170.0f};
    // kLightingTone (lighting decides the tone) by default; a constant tone is in [min, max].
    Setting<float> constant_tone{kLightingTone, 0.0f, 1.0f};
    Setting<float> max_point_size{3.0f, 0.5f, 32.0f};             // pixels
    Setting<float> smooth_slope{2.0f, 1.01f, 16.0f};              // Alg. 3.2's smoothSlope, > 1
    Setting<float> line_width{1.0f, 0.5f, 16.0f};                 // pixels
    Setting<float> dark_tone{0.6f, 0.0f, 1.0f};                   // thesis §8.4
    Setting<uint32_t> refinement_budget{1u << 18, 0u, 1u << 22};  // extra points per frame
    // Paintstrokes (GI'98, runtime/paintstroke.h): quality -1 = auto, tolerances in pixels,
    // vertices per frame (StrokeVertex, 48 bytes each; taken only when the asset has strokes),
    // and the LOD cut (a stroke draws when its root point's relevance radius projects to at
    // least this many pixels; 0 draws every stroke).
    Setting<int> stroke_quality{-1, -1, 2};
    Setting<float> stroke_tol_theta{1.0f, 0.05f, 64.0f};
    Setting<float> stroke_tol_z{0.5f, 0.05f, 64.0f};
    Setting<uint32_t> stroke_vertex_budget{1u << 18, 1024u, 1u << 23};
    Setting<float> stroke_lod_px{0.0f, 0.0f, 256.0f};
    Setting<float> stroke_nudge{0.5f, 0.0f, 1.0f};  // GI'98 §4.4 quality-0 normal nudge
    Setting<int> light_count{1, 0, kMaxLights};
    Setting<float> light_intensity{1.0f, 0.0f, 16.0f};
    Setting<float> ambient{0.0f, 0.0f, 1.0f};
    float background[3] = {1.0f, 1.0f, 1.0f};  // white paper; each channel in [0, 1]
    float paper[3] = {1.0f, 1.0f, 1.0f};       // the body's colour
    float ink[3] = {0.0f, 0.0f, 0.0f};         // dots and silhouettes
    // Looks (runtime/style.h, docs/styles.md): the style; toon bands, the level of the darkest
    // band, toon dots' colour as a fraction of the fill's; the tone curve on the target tone
    // before the size rule (gamma, then contrast about 0.5; 1, 1: the identity).
    Setting<int> style{int(Style::classic), 0, kStyleTotal - 1};
    Setting<int> toon_bands{3, 2, 3};
    Setting<float> toon_shade{0.6f, 0.0f, 1.0f};
    Setting<float> toon_ink{0.4f, 0.0f, 1.0f};
    Setting<float> tone_gamma{1.0f, 0.1f, 10.0f};
    Setting<float> tone_contrast{1.0f, 0.1f, 10.0f};
    float fill[3] = {0.55f, 0.8f, 0.35f};  // toon fill and colour dots without LOOK colours
    // Threads for the CPU point stages (runtime/point_stages.h); 0: the hardware's, at most
    // kMaxAutoThreads.
    Setting<int> threads{1, 0, kMaxPoolThreads};
    // View-dependent particles (docs/particles.md): the particle tree's size, baked and
    // temporary particles together (GI'01 §5, runtime/particle_temporary.h); at most the
    // asset's points: the bake alone. Every per-particle buffer is sized for it at init.
    Setting<uint32_t> particle_budget{262144u, 0u, 1u << 22};
};
inline constexpr FrameSettings kFrameSettings{};

// Everything about how a frame is drawn. Member initialisers are the table's defaults; in
// addition, a zero width, height, zoom, fov_degrees, max_point_size, smooth_slope,
// line_width, stroke_tol_theta, stroke_tol_z or stroke_vertex_budget means "the default" (zero is
// not a meaningful value for them). resolve_frame_config applies both and checks every limit.
struct FrameConfig {
    int width = kFrameSettings.width.fallback;
    int height = kFrameSettings.height.fallback;
    // 1: the framed bounds fit the view; 2: twice as large.
    float zoom = kFrameSettings.zoom.fallback;
    float yaw_degrees = kFrameSettings.yaw_degrees.fallback;      // orbit around the vertical axis
    float pitch_degrees = kFrameSettings.pitch_degrees.fallback;  // elevation (90: looking down)
    // What zoom 1 frames: the union of the baked bounds (BNDS) of these clips, so an animated
    // character stays in the picture; both -1 (or an asset without BNDS): the rest pose.
    int frame_clip = -1;
    int frame_blend_clip = -1;
    float fov_degrees = kFrameSettings.fov_degrees.fallback;  // vertical field of view at zoom 1
    bool relevance_update = true;  // Alg. 6.4; false keeps rest-pose radii (Alg. 6.3 only)
    float constant_tone = kFrameSettings.constant_tone.fallback;  // kLightingTone or in [0, 1]
    float max_point_size = kFrameSettings.max_point_size.fallback;
    float smooth_slope = kFrameSettings.smooth_slope.fallback;
    float background[3] = {kFrameSettings.background[0], kFrameSettings.background[1],
                           kFrameSettings.background[2]};
    float paper[3] = {kFrameSettings.paper[0], kFrameSettings.paper[1], kFrameSettings.paper[2]};
    float ink[3] = {kFrameSettings.ink[0], kFrameSettings.ink[1], kFrameSettings.ink[2]};
    // Lights (lights[0 .. light_count)); the default is one camera-space key light.
    int light_count = kFrameSettings.light_count.fallback;
    Light lights[kMaxLights];
    float ambient = kFrameSettings.ambient.fallback;
    anim::Skinning skinning = anim::Skinning::lbs;  // or dual quaternions (no candy wrapper)
    // Where place, relevance and size run (fixed at init; runtime/gpu_stages.h).
    FramePath path = FramePath::cpu;
    bool silhouettes = true;  // draw silhouette lines (needs the asset's EDGE section)
    // Level of detail (thesis §9.1.1, runtime/point_clusters.h): place, relevance and size run
    // only on clusters in view and front-facing, cut where no dot can be drawn. The dots are
    // the same as without (docs/lod.md); false runs every point.
    bool lod = true;
    // The asset's simplified occluder (OCCL section, stipple-bake --occluder; runtime/
    // renderer_occluder.cpp): a depth-only mesh pass (paper the background's colour) draws it,
    // pushed back along the view by its measured deviation, instead of the full mesh. No
    // effect on an asset without the section.
    bool occluder = true;
    float line_width = kFrameSettings.line_width.fallback;  // silhouette width in pixels
    bool depth_readback = false;  // keep the mesh depth for renderer_read_depth (dot lists)
    // Run-time refinement (runtime/point_refinement.h): extra points generated per frame where
    // the baked hierarchy runs out (close-ups, stretch). 0 turns it off.
    uint32_t refinement_budget = kFrameSettings.refinement_budget.fallback;
    float dark_tone = kFrameSettings.dark_tone.fallback;  // darkest tone lighting asks for
    // Paintstrokes: drawn when the asset has a STRK section and `strokes` is on; they share the
    // depth pass with the stipples and compose into the same image.
    bool strokes = true;
    int stroke_quality = kFrameSettings.stroke_quality.fallback;        // -1 auto, or 0, 1, 2
    float stroke_tol_theta = kFrameSettings.stroke_tol_theta.fallback;  // GI'98 tol_theta, px
    float stroke_tol_z = kFrameSettings.stroke_tol_z.fallback;          // GI'98 tol_z, px
    uint32_t stroke_vertex_budget = kFrameSettings.stroke_vertex_budget.fallback;
    float stroke_lod_px = kFrameSettings.stroke_lod_px.fallback;
    float stroke_nudge = kFrameSettings.stroke_nudge.fallback;
    // Debug: call glGetError after the depth, lines and dots passes and each readback, and
    // record the errors in the renderer (pipeline_gl_errors). Off: no check costs a frame.
    bool check_gl_errors = false;
    // View-dependent particles (GI'01; runtime/particle_frame.h, docs/particles.md): draw this
    // style's strokes instead of stipples (find_particle_style). nullptr: stipples. The style
    // must outlive the pipeline.
    const ParticleStyle* particle_style = nullptr;
    // Looks (runtime/style.h): zero toon_bands, tone_gamma or tone_contrast means the default.
    Style style = Style(kFrameSettings.style.fallback);
    int toon_bands = kFrameSettings.toon_bands.fallback;
    float toon_shade = kFrameSettings.toon_shade.fallback;
    float toon_ink = kFrameSettings.toon_ink.fallback;
    float tone_gamma = kFrameSettings.tone_gamma.fallback;
    float tone_contrast = kFrameSettings.tone_contrast.fallback;
    float fill[3] = {kFrameSettings.fill[0], kFrameSettings.fill[1], kFrameSettings.fill[2]};
    bool creases = true;  // crease lines (thesis §8.2's sharp edges) when the asset has them
    // Threads of the pool (fixed at init; runtime/thread_pool.h). From 2 on, a frame runs its
    // point part (selection, place, relevance, refinement, size) on a worker beside the line
    // stages and the mesh pass; the point stages' own split over contiguous point ranges
    // (runtime/point_stages.h) is for callers of the stages. The output is byte-identical for
    // any count. 0 resolves to the hardware's thread count, at most kMaxAutoThreads.
    int threads = kFrameSettings.threads.fallback;
    // Particle styles (docs/particles.md): the particle tree's size (fixed at init), and
    // visibility fades: the polygon pass's depth is read back each frame so strokes it hides
    // fade out instead of popping (runtime/particle_visibility.h; turns on depth_readback).
    uint32_t particle_budget = kFrameSettings.particle_budget.fallback;
    bool particle_fades = false;
};

// Writes `in` with defaults in its zero fields (see FrameConfig) to *out. Fails with
// StatusCode::invalid_argument, naming the field and its range, if a value lies outside its
// kFrameSettings range (NaN included); *out is then unchanged. `out` may be `&in`.
[[nodiscard]] Status resolve_frame_config(const FrameConfig& in, FrameConfig* out);

// Every default: the resolved zero config. CLIs print their defaults from it.
FrameConfig default_frame_config();

}  // namespace stipple
