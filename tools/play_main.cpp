// stipple-play: plays an animation clip of a .stip asset headless and writes PNG frames,
// an animated PNG, optional per-frame dot lists and timing stats.
#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>

#include "platform/headless_context.h"
#include "runtime/asset.h"
#include "runtime/frame_pipeline.h"
#include "tools/cli_options.h"
#include "tools/image_write.h"
#include "tools/json_line.h"
#include "tools/play_options.h"
#include "tools/play_outputs.h"
#include "tools/play_usage.h"
#include "tools/play_window.h"

namespace {

using stipple::play::die;
using stipple::play::kDefaults;
using stipple::play::kLimits;
using stipple::play::Options;

std::string frame_path(const Options& o, const char* stem, long frame, const char* ext) {
    char name[64];
    std::snprintf(name, sizeof(name), "/%s_%04ld.%s", stem, frame, ext);
    return o.out + name;
}

// The played clip (-1: the rest pose) and the second clip of --blend / --crossfade (-1: none).
struct Clips {
    int clip = -1, second = -1;
};

Clips find_clips(const stipple::Asset& asset, const Options& o) {
    Clips c;
    c.clip = asset.clip_count > 0 ? 0 : -1;
    if (!o.clip.empty()) {
        c.clip = stipple::find_clip(asset, o.clip.c_str());
        if (c.clip < 0) die("no clip '" + o.clip + "' in " + o.asset);
    }
    if (o.mix != Options::Mix::none) {
        c.second = stipple::find_clip(asset, o.second_clip.c_str());
        if (c.second < 0) die("no clip '" + o.second_clip + "' in " + o.asset);
    }
    return c;
}

void make_output_dir(const std::string& dir) {
    mkdir(dir.c_str(), 0755);
    struct stat info;
    if (stat(dir.c_str(), &info) != 0 || !S_ISDIR(info.st_mode))
        die("cannot create output directory '" + dir + "'");
}

stipple::FrameConfig pipeline_config(const Options& o, const Clips& clips) {
    stipple::FrameConfig pc;
    pc.width = o.width;
    pc.height = o.height;
    pc.zoom = float(o.zoom);
    pc.yaw_degrees = float(o.yaw);
    pc.pitch_degrees = float(o.pitch);
    pc.frame_clip = clips.clip;  // zoom 1 frames every pose of the clips played
    pc.frame_blend_clip = clips.second;
    pc.relevance_update = o.relevance_update;
    pc.lod = o.lod;
    pc.occluder = o.occluder;
    pc.threads = o.threads;
    pc.dark_tone = float(o.dark_tone);
    pc.refinement_budget = uint32_t(o.refinement_budget);
    pc.constant_tone = float(o.tone);
    pc.max_point_size = float(o.point_size);
    pc.silhouettes = o.silhouettes;
    pc.depth_readback = o.dots_out || o.mask_out || o.strokes_out;
    pc.skinning = o.dqs ? stipple::anim::Skinning::dqs : stipple::anim::Skinning::lbs;
    pc.path = o.gpu_path ? stipple::FramePath::gpu : stipple::FramePath::cpu;
    pc.line_width = float(o.line_width);
    pc.check_gl_errors = o.check_gl;
    pc.strokes = o.strokes;
    pc.stroke_quality = o.stroke_quality;
    pc.stroke_tol_theta = float(o.stroke_tol_theta);
    pc.stroke_tol_z = float(o.stroke_tol_z);
    pc.stroke_lod_px = float(o.stroke_lod);
    pc.stroke_vertex_budget = uint32_t(o.stroke_budget);
    pc.ambient = float(o.ambient);
    if (o.light_count >= 0) {
        pc.light_count = o.light_count;
        for (int i = 0; i < o.light_count; ++i) {
            pc.lights[i] = o.lights[i];
            pc.lights[i].camera_space = !o.world_lights;
        }
    }
    std::memcpy(pc.background, o.background, sizeof(pc.background));
    pc.style = stipple::Style(o.style);  // looks: runtime/style.h
    if (o.particle_style >= 0)           // strokes instead of stipples: docs/particles.md
        pc.particle_style = &stipple::particle_style_at(o.particle_style);
    pc.particle_fades = o.particle_fades;
    pc.particle_budget = uint32_t(o.particle_budget);
    pc.toon_bands = int(o.toon_bands);
    pc.toon_ink = float(o.toon_ink);
    pc.tone_gamma = float(o.tone_gamma);
    pc.tone_contrast = float(o.tone_contrast);
    std::memcpy(pc.fill, o.fill, sizeof(pc.fill));
    pc.creases = o.creases;
    return pc;
}

// The frame buffers and the animated PNG the frames go to.
struct Outputs {
    std::unique_ptr<uint8_t[]> rgba;
    std::unique_ptr<float[]> depth_scratch, depth;
    std::unique_ptr<stipple::VisibleDot[]> dot_scratch;
    std::unique_ptr<stipple::StrokeRootSample[]> root_scratch;
    std::unique_ptr<uint8_t[]> mask_rgba;
    stipple::image::ApngWriter apng;
};

void open_outputs(const Options& o, const stipple::Pipeline& pipeline, Outputs* out) {
    const size_t pixels = size_t(o.width) * size_t(o.height);
    out->rgba.reset(new uint8_t[pixels * 4]);
    if (o.dots_out || o.mask_out || o.strokes_out) {
        out->depth_scratch.reset(new float[pixels * 4]);
        out->depth.reset(new float[pixels]);
        if (o.dots_out) out->dot_scratch.reset(new stipple::VisibleDot[pipeline.point_capacity]);
    }
    if (o.mask_out) out->mask_rgba.reset(new uint8_t[pixels * 4]);
    if (o.roots_out)
        out->root_scratch.reset(
            new stipple::StrokeRootSample[std::max(pipeline.asset->strokes.stroke_count, 1u)]);
    int fps_num = int(std::lround(o.fps * 1000)), fps_den = 1000;
    while (fps_num > 65535) fps_num /= 10, fps_den /= 10;
    std::string error;
    if (o.apng &&
        !out->apng.open((o.out + "/anim.png").c_str(), std::max(fps_num, 1), fps_den, &error))
        die(error);
}

// Writes frame f (already read back into out->rgba) as PNG, APNG frame, dots and mask.
void write_frame(const Options& o, long f, stipple::Pipeline* pipeline, Outputs* out) {
    std::string error;
    if (o.png && !stipple::image::write_png(frame_path(o, "frame", f, "png").c_str(), o.width,
                                            o.height, out->rgba.get(), true, &error))
        die(error);
    if (o.apng && !out->apng.add_frame(o.width, o.height, out->rgba.get(), true, &error))
        die(error);
    if (o.dots_out || o.mask_out || o.strokes_out)
        stipple::renderer_read_depth(&pipeline->renderer, out->depth_scratch.get(),
                                     out->depth.get());
    if (o.dots_out &&
        !stipple::play::write_dots(*pipeline, out->depth.get(), out->dot_scratch.get(),
                                   frame_path(o, "dots", f, "csv")))
        die("cannot write dots file in '" + o.out + "'");
    if (o.hidden_out &&
        !stipple::play::write_hidden_dots(*pipeline, out->depth.get(), out->dot_scratch.get(),
                                          frame_path(o, "hidden", f, "csv")))
        die("cannot write hidden dots file in '" + o.out + "'");
    if (o.strokes_out && !stipple::play::write_strokes(*pipeline, out->depth.get(),
                                                       frame_path(o, "strokes", f, "csv")))
        die("cannot write strokes file in '" + o.out + "'");
    if (o.roots_out && !stipple::play::write_roots(*pipeline, out->root_scratch.get(),
                                                   frame_path(o, "roots", f, "csv")))
        die("cannot write roots file in '" + o.out + "'");
    if (o.mask_out &&
        !stipple::play::write_mask(out->depth.get(), o.width, o.height, out->mask_rgba.get(),
                                   frame_path(o, "mask", f, "png"), &error))
        die(error);
}

// The process's resident set size in KiB (VmRSS of /proc/self/status), or -1.
long resident_kb() {
    FILE* f = std::fopen("/proc/self/status", "r");
    if (!f) return -1;
    char line[256];
    long kb = -1;
    while (kb < 0 && std::fgets(line, sizeof(line), f))
        if (std::strncmp(line, "VmRSS:", 6) == 0) kb = std::strtol(line + 6, nullptr, 10);
    std::fclose(f);
    return kb;
}

// --rss-every: DIR/rss.csv, one row per N frames (the soak test's memory curve).
struct RssLog {
    FILE* file = nullptr;
    double last_ms = 0;  // Totals::frame_ms at the last row
    long last_frame = 0;
};

struct Totals {
    stipple::StageTimes times;
    double frame_ms = 0, drawn = 0, refined = 0, budget_scale = 1;
    double run = 0, placed = 0, culled_frustum = 0, culled_back = 0;  // level of detail
};

// --zoom-to: the zoom of frame f, geometric between --zoom and --zoom-to; once over all
// frames, or there and back every --zoom-period frames.
double zoom_at(const Options& o, long f) {
    double s = double(f) / double(o.frames - 1);
    if (o.zoom_period > 0) {
        const double phase = double(f % o.zoom_period) / double(o.zoom_period);
        s = phase < 0.5 ? 2 * phase : 2 - 2 * phase;
    }
    return o.zoom * std::pow(o.zoom_to / o.zoom, s);
}

// Draws frame f and reads its colour back into out->rgba.
void render_frame(const Options& o, const Clips& clips, long f, stipple::Pipeline* pipeline,
                  Outputs* out, Totals* totals) {
    // Clips loop (the sampler wraps the time); a crossfade starts CLIP2 at its time 0.
    const double elapsed = double(f) / o.fps;
    const bool crossfade = o.mix == Options::Mix::crossfade;
    stipple::AnimationState state;
    state.clip = clips.clip;
    state.time = float(o.time0 + elapsed);
    state.blend_clip = clips.second;
    state.blend_time = float(crossfade ? elapsed : o.time0 + elapsed);
    state.blend_weight = float(crossfade ? std::min(elapsed / o.mix_amount, 1.0) : o.mix_amount);
    auto start = std::chrono::steady_clock::now();
    if (o.zoom_to > 0 && o.frames > 1) {
        stipple::FrameConfig view = pipeline->config;
        view.zoom = float(zoom_at(o, f));
        const stipple::Status set = stipple::pipeline_set_view(pipeline, view);
        if (!set.ok()) die(std::string("--zoom-to: ") + set.message);
    }
    stipple::pipeline_frame(pipeline, state, &totals->times);
    auto readback_start = std::chrono::steady_clock::now();
    stipple::renderer_read_color(&pipeline->renderer, out->rgba.get());
    auto end = std::chrono::steady_clock::now();
    totals->times.readback +=
        std::chrono::duration<double, std::milli>(end - readback_start).count();
    totals->frame_ms += std::chrono::duration<double, std::milli>(end - start).count();
    totals->drawn += pipeline->points_drawn;
    totals->refined += pipeline->refined_count;
    const bool lod = pipeline->config.lod && pipeline->clusters.cluster_count > 0;
    const stipple::LodStats& lod_stats = pipeline->clusters.stats;
    totals->run += lod ? lod_stats.points_run : pipeline->asset->points.point_count;
    totals->placed += lod ? lod_stats.points_placed : pipeline->asset->points.point_count;
    totals->culled_frustum += lod ? lod_stats.culled_frustum : 0;
    totals->culled_back += lod ? lod_stats.culled_back : 0;
    totals->budget_scale =
        std::min(totals->budget_scale, double(pipeline->refinement_stats.budget_scale));
}

void open_rss_log(const Options& o, RssLog* log) {
    if (o.rss_every <= 0) return;
    const std::string path = o.out + "/rss.csv";
    log->file = std::fopen(path.c_str(), "w");
    if (!log->file) die("cannot write '" + path + "'");
    std::fputs("frame,rss_kb,ms_per_frame\n", log->file);
}

// After frame f (0-based): a row when f + 1 is a multiple of --rss-every.
void log_rss(const Options& o, long f, const Totals& t, RssLog* log) {
    if (!log->file || (f + 1) % o.rss_every != 0) return;
    const long frames = f + 1 - log->last_frame;
    std::fprintf(log->file, "%ld,%ld,%.3f\n", f + 1, resident_kb(),
                 (t.frame_ms - log->last_ms) / double(frames));
    std::fflush(log->file);
    log->last_ms = t.frame_ms;
    log->last_frame = f + 1;
}

// --check-gl: 0, or 1 after a one-line message naming the first GL error and its pass.
int report_gl_errors(const Options& o, const stipple::Pipeline& p) {
    const stipple::GlErrorLog& e = stipple::pipeline_gl_errors(p);
    if (!o.check_gl || e.count == 0) return 0;
    std::fprintf(stderr,
                 "stipple-play: GL error %s after the %s pass (%u GL errors in %ld frames)\n",
                 stipple::gl_error_name(e.first_error), e.first_pass ? e.first_pass : "?", e.count,
                 o.frames);
    return 1;
}

// --stats: one JSON object of counts and mean timings per frame.
void print_stats(const Options& o, const stipple::Asset& asset, const Clips& clips,
                 const stipple::platform::HeadlessContext& context, const Totals& t,
                 const stipple::Pipeline& pipeline) {
    using stipple::cli::fixed;
    const double n = double(o.frames);
    stipple::cli::Json j;
    j["asset"] = o.asset;
    j["backend"] = stipple::platform::backend_name(context.backend);
    j["renderer"] = context.renderer;
    j["clip"] = clips.clip >= 0 ? asset.clips[clips.clip].name : "(rest pose)";
    j["frames"] = o.frames;
    j["width"] = o.width;
    j["height"] = o.height;
    j["points_total"] = asset.points.point_count;
    j["points_drawn"] = fixed(t.drawn / n, 1);
    j["points_refined"] = fixed(t.refined / n, 1);
    j["points_run"] = fixed(t.run / n, 1);  // placed, relevance, sized (LOD: docs/lod.md)
    j["points_placed"] = fixed(t.placed / n, 1);
    j["clusters"] = pipeline.clusters.cluster_count;
    j["clusters_culled_frustum"] = fixed(t.culled_frustum / n, 1);
    j["clusters_culled_back"] = fixed(t.culled_back / n, 1);
    j["refinement_budget_scale"] = fixed(t.budget_scale, 3);
    if (pipeline.particles.enabled) {  // the last frame's particles (docs/particles.md)
        const stipple::ParticleStageStats& ps = pipeline.particles.stats;
        j["particle_style"] = pipeline.particles.style.name;
        j["particles_active"] = ps.active;
        j["particle_strokes"] = ps.strokes;
    }
    j["ms_per_frame"] = fixed(t.frame_ms / n, 3);
    const std::pair<const char*, double> stages[] = {
        {"sample", t.times.sample},       {"skin", t.times.skin},
        {"select", t.times.select},       {"place", t.times.place},
        {"relevance", t.times.relevance}, {"refine", t.times.refine},
        {"size", t.times.size},           {"silhouette", t.times.silhouette},
        {"strokes", t.times.strokes},     {"draw", t.times.draw},
        {"readback", t.times.readback}};
    stipple::cli::Json per_stage;
    for (const auto& stage : stages) per_stage[stage.first] = fixed(stage.second / n, 3);
    j["ms_per_stage"] = per_stage;
    if (asset.strokes.stroke_count > 0) {
        const stipple::StrokeStage& s = pipeline.strokes;
        j["strokes_total"] = asset.strokes.stroke_count;
        j["strokes_drawn"] = s.strokes_drawn;  // these three: the last frame
        j["stroke_segments"] = s.stats.segments;
        j["stroke_triangles"] = s.stats.triangles;
        j["stroke_budget_full"] = s.mesh.overflow;  // strokes were left out: raise the budget
    }
    if (o.check_gl) j["gl_errors"] = stipple::pipeline_gl_errors(pipeline).count;
    stipple::cli::print_json(j);
}

}  // namespace

int main(int argc, char** argv) {
    const Options o = stipple::play::parse(argc, argv);
    stipple::Asset asset;
    stipple::Status st = stipple::load_asset_file(o.asset.c_str(), &asset);
    if (!st.ok()) die(o.asset + ": " + st.message);
    const Clips clips = find_clips(asset, o);
    if (o.win.window)
        return stipple::play::run_kiosk({&asset, pipeline_config(o, clips), clips.clip, o.time0,
                                         o.frames_given ? o.frames : 0, o.out, o.raster_threads},
                                        o.win, stipple::play::parser());
    make_output_dir(o.out);

    stipple::platform::HeadlessConfig hc;
    hc.width = o.width;
    hc.height = o.height;
    hc.allow_egl = o.backend != "osmesa";
    hc.allow_osmesa = o.backend != "egl";
    hc.raster_threads = o.raster_threads;
    stipple::platform::HeadlessContext context;
    std::string error;
    const stipple::platform::ContextStatus created =
        stipple::platform::create_headless_context(hc, &context);
    if (!created.ok()) die(created.message);
    stipple::GlApi gl;
    const stipple::Status loaded =
        stipple::load_gl_api(stipple::platform::proc_loader(context), &gl);
    if (!loaded.ok()) die(loaded.message);

    const stipple::FrameConfig pc = pipeline_config(o, clips);
    std::unique_ptr<stipple::Pipeline> pipeline(new stipple::Pipeline());
    const stipple::Status init = stipple::pipeline_init(pipeline.get(), asset, gl, pc);
    if (!init.ok()) die(std::string("renderer: ") + init.message);

    Outputs out;
    open_outputs(o, *pipeline, &out);
    Totals totals;
    RssLog rss;
    open_rss_log(o, &rss);
    for (long f = 0; f < o.frames; ++f) {
        render_frame(o, clips, f, pipeline.get(), &out, &totals);
        write_frame(o, f, pipeline.get(), &out);
        log_rss(o, f, totals, &rss);
    }
    if (rss.file && std::fclose(rss.file) != 0) die("cannot write '" + o.out + "/rss.csv'");
    if (o.apng && !out.apng.finish(&error)) die(error);
    if (o.stats) print_stats(o, asset, clips, context, totals, *pipeline);
    const int gl_failed = report_gl_errors(o, *pipeline);
    stipple::pipeline_destroy(pipeline.get());
    stipple::platform::destroy_headless_context(&context);
    return gl_failed;
}
