// stipple-play's options: what the command line says (tools/play_options.cpp parses it).
#pragma once
#include <string>

#include "runtime/frame_config.h"
#include "runtime/style.h"
#include "tools/cli_options.h"
#include "tools/play_window.h"

namespace stipple::play {

// Frame-setting defaults and ranges in the help text come from the one table
// (runtime/frame_config.h) and the resolved zero config, never from literals here.
inline const stipple::FrameSettings& kLimits = stipple::kFrameSettings;
inline const stipple::FrameConfig kDefaults = stipple::default_frame_config();

struct Options {
    std::string asset, out, clip, backend, second_clip;
    enum class Mix { none, blend, crossfade } mix = Mix::none;
    double mix_amount = 0;  // blend weight, or crossfade seconds
    bool dqs = false;
    bool gpu_path = false;  // --path gpu: place, relevance and size on the GPU
    long frames = 30;
    double fps = 30, time0 = 0;
    // Frame settings start at the resolved zero config (runtime/frame_config.h).
    double zoom = kDefaults.zoom, yaw = kDefaults.yaw_degrees, pitch = kDefaults.pitch_degrees;
    double tone = kDefaults.constant_tone, point_size = kDefaults.max_point_size;
    double dark_tone = kDefaults.dark_tone;
    double zoom_to = 0;    // > 0: zoom moves geometrically from `zoom` to this over the frames
    long zoom_period = 0;  // > 0: ... and back, every zoom_period frames
    long refinement_budget = long(kDefaults.refinement_budget);
    int width = kDefaults.width, height = kDefaults.height;
    float background[3] = {kDefaults.background[0], kDefaults.background[1],
                           kDefaults.background[2]};
    double line_width = kDefaults.line_width;
    bool silhouettes = kDefaults.silhouettes;
    bool relevance_update = kDefaults.relevance_update;
    bool lod = kDefaults.lod;
    bool occluder = kDefaults.occluder;
    int threads = kDefaults.threads;  // --threads: the point stages' threads (0: hardware's)
    int raster_threads = -1;          // --raster-threads: llvmpipe's (-1: the driver's default)
    bool dots_out = false, png = true, apng = true, stats = false;
    bool mask_out = false;
    bool hidden_out = false;  // --hidden-out: hidden_NNNN.csv beside dots_NNNN.csv
    bool check_gl = false;
    bool strokes = kDefaults.strokes, roots_out = false;
    int stroke_quality = kDefaults.stroke_quality;
    double stroke_tol_theta = kDefaults.stroke_tol_theta, stroke_tol_z = kDefaults.stroke_tol_z;
    double stroke_lod = kDefaults.stroke_lod_px;
    long stroke_budget = long(kDefaults.stroke_vertex_budget);
    int light_count = -1;  // -1: the default list
    stipple::Light lights[stipple::kMaxLights];
    bool world_lights = false;
    double ambient = kDefaults.ambient;
    // Looks (runtime/style.h, docs/styles.md).
    int style = int(kDefaults.style);
    long toon_bands = kDefaults.toon_bands;
    double toon_ink = kDefaults.toon_ink;
    double tone_gamma = kDefaults.tone_gamma, tone_contrast = kDefaults.tone_contrast;
    float fill[3] = {kDefaults.fill[0], kDefaults.fill[1], kDefaults.fill[2]};
    bool creases = kDefaults.creases;
    int particle_style = -1;   // --style NAME of a particle style: its particle_style_at index
    bool strokes_out = false;  // --strokes-out: strokes_NNNN.csv per frame
    bool particle_fades = kDefaults.particle_fades;          // --particle-fades
    long particle_budget = long(kDefaults.particle_budget);  // --particle-budget N
    long rss_every = 0;                // > 0: DIR/rss.csv gets a row every rss_every frames
    stipple::play::WindowOptions win;  // --window (tools/play_window.h)
    bool frames_given = false;         // a window runs until Esc without --frames
};

// Parses the command line; exits with a one-line error (and status 1) on a bad one.
Options parse(int argc, char** argv);

// stipple-play's parser (its one-line errors, for the kiosk window).
stipple::cli::Parser& parser();

// Exits with `message` as stipple-play's one-line error.
[[noreturn]] void die(const std::string& message);

}  // namespace stipple::play
