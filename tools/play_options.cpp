#include "tools/play_options.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

#include "platform/headless_context.h"
#include "runtime/particle_style.h"
#include "tools/cli_options.h"
#include "tools/play_usage.h"

namespace stipple::play {

namespace {

const std::string kUsage = stipple::play::usage();
stipple::cli::Parser g_parser("stipple-play", kUsage.c_str());

}  // namespace

stipple::cli::Parser& parser() {
    return g_parser;
}

[[noreturn]] void die(const std::string& message) {
    g_parser.fail(message);
}

namespace {

// Every name --style takes: the looks, then the particle styles.
std::string all_style_names() {
    std::string names = stipple::style_name_list();
    for (int i = 0; i < stipple::particle_style_count(); ++i)
        names += std::string("|") + stipple::particle_style_at(i).name;
    return names;
}

// --blend CLIP2:W and --crossfade CLIP2:S.
void parse_mix(const std::string& option, const std::string& v, Options* o) {
    const bool blend = option == "--blend";
    const size_t colon = v.rfind(':');
    if (colon == std::string::npos || colon == 0)
        die(option + " takes CLIP:" + (blend ? "WEIGHT" : "SECONDS") + ", got '" + v + "'");
    o->second_clip = v.substr(0, colon);
    o->mix = blend ? Options::Mix::blend : Options::Mix::crossfade;
    o->mix_amount =
        blend ? g_parser.number_value(option + " weight", v.substr(colon + 1), 0, 1)
              : g_parser.number_value(option + " seconds", v.substr(colon + 1), 0.001, 1e4);
}

// --stroke-tolerance THETA[,Z]: GI'98 tol_theta and tol_z in pixels (Z defaults to half THETA).
void parse_tolerance(const std::string& option, const std::string& v, Options* o) {
    const stipple::Setting<float>& t = kLimits.stroke_tol_theta;
    const size_t comma = v.find(',');
    o->stroke_tol_theta =
        g_parser.number_value(option + " tol_theta", v.substr(0, comma), t.min, t.max);
    o->stroke_tol_z =
        comma == std::string::npos
            ? std::max(0.5 * o->stroke_tol_theta, double(t.min))
            : g_parser.number_value(option + " tol_z", v.substr(comma + 1),
                                    kLimits.stroke_tol_z.min, kLimits.stroke_tol_z.max);
}

// --light X,Y,Z[,I], up to kMaxLights times.
void parse_light(const std::string& option, const std::string& v, Options* o) {
    if (o->light_count < 0) o->light_count = 0;
    if (o->light_count == stipple::kMaxLights)
        die(option + ": at most " + std::to_string(stipple::kMaxLights) + " lights");
    std::string parts[4];
    int n = 0;
    for (size_t at = 0;; ++n) {
        const size_t comma = v.find(',', at);
        if (n == 4) die(option + " takes X,Y,Z[,INTENSITY], got '" + v + "'");
        parts[n] = v.substr(at, comma == std::string::npos ? std::string::npos : comma - at);
        if (comma == std::string::npos) break;
        at = comma + 1;
    }
    if (++n < 3) die(option + " takes X,Y,Z[,INTENSITY], got '" + v + "'");
    double x[4] = {0, 0, 0, 1};
    for (int k = 0; k < n; ++k)
        x[k] = k == 3
                   ? g_parser.number_value(option + " intensity", parts[k],
                                           kLimits.light_intensity.min, kLimits.light_intensity.max)
                   : g_parser.number_value(option + " direction", parts[k], -1e6, 1e6);
    if (x[0] == 0 && x[1] == 0 && x[2] == 0) die(option + ": the direction must not be zero");
    stipple::Light& l = o->lights[o->light_count++];
    l.direction[0] = float(x[0]);
    l.direction[1] = float(x[1]);
    l.direction[2] = float(x[2]);
    l.intensity = float(x[3]);
}

// What is played and how the camera sees it.
void add_view_options(stipple::cli::Parser& p, Options& o) {
    p.text("--clip", &o.clip)
        .custom("--blend",
                [&o](const std::string& n, const std::string& v) { parse_mix(n, v, &o); })
        .custom("--crossfade",
                [&o](const std::string& n, const std::string& v) { parse_mix(n, v, &o); })
        .choice("--skinning", {std::pair<const char*, bool>{"lbs", false}, {"dqs", true}}, &o.dqs)
        .choice("--path", {std::pair<const char*, bool>{"cpu", false}, {"gpu", true}}, &o.gpu_path)
        .custom("--frames",
                [&o](const std::string& n, const std::string& v) {
                    o.frames = long(g_parser.integer_value(n, v, 1, 100000));
                    o.frames_given = true;
                })
        .number("--fps", 0.001, 1000, &o.fps)
        .number("--time", -1e6, 1e6, &o.time0)
        .custom("--size",
                [&o](const std::string& n, const std::string& v) {
                    const stipple::Setting<int>& w = kLimits.width;
                    if (!stipple::cli::parse_size(v, w.min, w.max, &o.width, &o.height))
                        g_parser.bad_value(n,
                                           "WxH with " + std::to_string(w.min) +
                                               " <= W, H <= " + std::to_string(w.max),
                                           v);
                })
        .number("--zoom", kLimits.zoom.min, kLimits.zoom.max, &o.zoom)
        .number("--zoom-to", kLimits.zoom.min, kLimits.zoom.max, &o.zoom_to)
        .integer("--zoom-period", 2, 100000, &o.zoom_period)
        .number("--yaw", kLimits.yaw_degrees.min, kLimits.yaw_degrees.max, &o.yaw)
        .number("--pitch", kLimits.pitch_degrees.min, kLimits.pitch_degrees.max, &o.pitch);
}

// How the frame is drawn and what is written.
void add_render_options(stipple::cli::Parser& p, Options& o) {
    p.number("--tone", kLimits.constant_tone.min, kLimits.constant_tone.max, &o.tone)
        .number("--point-size", kLimits.max_point_size.min, kLimits.max_point_size.max,
                &o.point_size)
        .custom("--background",
                [&o](const std::string& n, const std::string& v) {
                    long long rgb = 0;
                    if (v.size() != 6 ||
                        v.find_first_not_of("0123456789abcdefABCDEF") != std::string::npos)
                        g_parser.bad_value(n, "RRGGBB hex", v);
                    rgb = std::stoll(v, nullptr, 16);
                    for (int k = 0; k < 3; ++k)
                        o.background[k] = float((rgb >> (16 - 8 * k)) & 0xFF) / 255;
                })
        .flag("--no-relevance-update", &o.relevance_update, false)
        .flag("--no-lod", &o.lod, false)
        .flag("--no-occluder", &o.occluder, false)
        .integer("--threads", kLimits.threads.min, kLimits.threads.max, &o.threads)
        .integer("--raster-threads", 0, stipple::platform::kMaxRasterThreads, &o.raster_threads)
        .number("--dark-tone", kLimits.dark_tone.min, kLimits.dark_tone.max, &o.dark_tone)
        .integer("--refinement-budget", kLimits.refinement_budget.min,
                 kLimits.refinement_budget.max, &o.refinement_budget)
        .flag("--no-silhouettes", &o.silhouettes, false)
        .number("--line-width", kLimits.line_width.min, kLimits.line_width.max, &o.line_width)
        .custom("--light",
                [&o](const std::string& n, const std::string& v) { parse_light(n, v, &o); })
        .choice("--light-space", {std::pair<const char*, bool>{"camera", false}, {"world", true}},
                &o.world_lights)
        .number("--ambient", kLimits.ambient.min, kLimits.ambient.max, &o.ambient)
        .flag("--no-strokes", &o.strokes, false)
        .choice("--stroke-quality",
                {std::pair<const char*, int>{"auto", -1}, {"0", 0}, {"1", 1}, {"2", 2}},
                &o.stroke_quality)
        .custom("--stroke-tolerance",
                [&o](const std::string& n, const std::string& v) { parse_tolerance(n, v, &o); })
        .number("--stroke-lod", kLimits.stroke_lod_px.min, kLimits.stroke_lod_px.max, &o.stroke_lod)
        .integer("--stroke-budget", long(kLimits.stroke_vertex_budget.min),
                 long(kLimits.stroke_vertex_budget.max), &o.stroke_budget)
        .flag("--roots-out", &o.roots_out)
        .flag("--dots-out", &o.dots_out)
        .flag("--hidden-out", &o.hidden_out)
        .flag("--strokes-out", &o.strokes_out)
        .flag("--mask-out", &o.mask_out)
        .flag("--no-png", &o.png, false)
        .flag("--no-apng", &o.apng, false)
        .flag("--stats", &o.stats)
        .flag("--check-gl", &o.check_gl)
        .integer("--rss-every", 1, 100000, &o.rss_every)
        .choice("--backend",
                {std::pair<const char*, std::string>{"egl", "egl"}, {"osmesa", "osmesa"}},
                &o.backend);
}

// The looks (runtime/style.h): --style, toon and tone-curve settings, --no-creases.
void add_look_options(stipple::cli::Parser& p, Options& o) {
    p.custom("--style",
             [&o](const std::string& n, const std::string& v) {
                 // A stipple look (runtime/style.h) or a particle style (docs/particles.md).
                 o.style = std::max(stipple::find_style(v.c_str()), 0);
                 o.particle_style =
                     stipple::particle_style_index(stipple::find_particle_style(v.c_str()));
                 if (stipple::find_style(v.c_str()) < 0 && o.particle_style < 0)
                     g_parser.bad_value(n, all_style_names(), v);
             })
        .integer("--toon-bands", kLimits.toon_bands.min, kLimits.toon_bands.max, &o.toon_bands)
        .number("--toon-ink", kLimits.toon_ink.min, kLimits.toon_ink.max, &o.toon_ink)
        .custom("--fill",
                [&o](const std::string& n, const std::string& v) {
                    if (v.size() != 6 ||
                        v.find_first_not_of("0123456789abcdefABCDEF") != std::string::npos)
                        g_parser.bad_value(n, "RRGGBB hex", v);
                    const long long rgb = std::stoll(v, nullptr, 16);
                    for (int k = 0; k < 3; ++k)
                        o.fill[k] = float((rgb >> (16 - 8 * k)) & 0xFF) / 255;
                })
        .number("--tone-gamma", kLimits.tone_gamma.min, kLimits.tone_gamma.max, &o.tone_gamma)
        .number("--tone-contrast", kLimits.tone_contrast.min, kLimits.tone_contrast.max,
                &o.tone_contrast)
        .flag("--no-creases", &o.creases, false)
        .flag("--particle-fades", &o.particle_fades)
        .integer("--particle-budget", long(kLimits.particle_budget.min),
                 long(kLimits.particle_budget.max), &o.particle_budget);
}

}  // namespace

Options parse(int argc, char** argv) {
    Options o;
    g_parser.positional("asset", &o.asset).text("--out", &o.out);
    add_view_options(g_parser, o);
    add_render_options(g_parser, o);
    add_look_options(g_parser, o);
    stipple::play::add_window_options(g_parser, &o.win);
    g_parser.parse(argc, argv);
    if (o.asset.empty()) die("no asset given (see --help)");
    if (o.out.empty() && !o.win.window) die("no output directory: pass --out DIR");
    if (o.strokes_out && o.particle_style < 0)
        die("--strokes-out needs a particle style (--style painterly-long, ...)");
    if (o.hidden_out && !o.dots_out) die("--hidden-out needs --dots-out");
    if (o.particle_fades && o.particle_style < 0)
        die("--particle-fades needs a particle style (--style painterly-long, ...)");
    if (o.gpu_path && (o.dots_out || o.roots_out))
        die("--dots-out and --roots-out need --path cpu (the GPU path keeps its dots on the GPU)");
    if (!o.win.window && (o.win.fullscreen || o.win.fixed || !o.win.screenshot.empty()))
        die("--fullscreen, --fixed-time and --screenshot need --window");
    if (o.win.window && (o.mix != Options::Mix::none || o.zoom_to > 0 || o.backend == "osmesa"))
        die("--blend, --crossfade, --zoom-to and --backend osmesa do not work with --window");
    return o;
}

}  // namespace stipple::play
