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
#include "tools/cli_args.h"
#include "tools/image_write.h"

namespace {

const char* kUsage =
    "usage: stipple-play ASSET.stip --out DIR [options]\n"
    "  --out DIR               where frame_NNNN.png and anim.png go (created if missing)\n"
    "  --clip NAME|INDEX       animation clip (default 0; the rest pose if the asset has none)\n"
    "  --blend CLIP2:W         layer a second clip with weight W in [0,1] (same clock)\n"
    "  --crossfade CLIP2:S     fade from --clip to CLIP2 over S seconds, starting at --time\n"
    "  --skinning lbs|dqs      linear blend (default) or dual-quaternion skinning\n"
    "  --frames N              frames to render (default 30, max 100000)\n"
    "  --fps F                 frames per second of animation time (default 30)\n"
    "  --time T0               start time in seconds (default 0); clips loop\n"
    "  --size WxH              image size (default 640x480, max 8192x8192)\n"
    "  --zoom Z                1 = every pose of the played clip(s) fits the view (no clip:\n"
    "                          the rest pose), 2 = twice as large (default 1)\n"
    "  --zoom-to Z2            zoom from Z to Z2 (geometrically) over the frames\n"
    "  --yaw DEG, --pitch DEG  camera orbit (default 0, 0: looking down -Z); pitch in [-90, 90]\n"
    "  --tone T                constant target tone in [0,1] instead of lighting\n"
    "  --point-size PX         maximum stipple diameter (default 3, in [0.5, 32])\n"
    "  --background RRGGBB     background colour (default ffffff)\n"
    "  --no-relevance-update   keep rest-pose relevance radii (thesis Alg. 6.3 without 6.4)\n"
    "  --dark-tone T           darkest tone lighting asks for, thesis §8.4 (default 0.6)\n"
    "  --refinement-budget N   extra points per frame where the baked hierarchy runs out\n"
    "                          (close-ups, stretch; default 262144, 0 = off, max 4194304)\n"
    "  --no-silhouettes        do not draw silhouette lines\n"
    "  --line-width PX         silhouette line width (default 1, in [0.5, 16])\n"
    "  --dots-out              also write dots_NNNN.csv (id,x,y,size per drawn dot)\n"
    "  --mask-out              also write mask_NNNN.png: white where the mesh covers the\n"
    "                          pixel, black elsewhere (the object mask of stipple-measure)\n"
    "  --no-png                do not write per-frame PNGs\n"
    "  --no-apng               do not write anim.png\n"
    "  --stats                 print a JSON object of counts and timings to stdout\n"
    "  --backend egl|osmesa    force a context backend (default: EGL, then OSMesa)\n"
    "  -h, --help              this text\n";

struct Options {
    std::string asset, out, clip, backend, second_clip;
    enum class Mix { none, blend, crossfade } mix = Mix::none;
    double mix_amount = 0;  // blend weight, or crossfade seconds
    bool dqs = false;
    long frames = 30;
    double fps = 30, time0 = 0, zoom = 1, yaw = 0, pitch = 0, tone = -1, point_size = 3;
    double dark_tone = 0.6;
    double zoom_to = 0;  // > 0: zoom moves geometrically from `zoom` to this over the frames
    long refinement_budget = 1L << 18;
    int width = 640, height = 480;
    float background[3] = {1, 1, 1};
    double line_width = 1;
    bool silhouettes = true;
    bool relevance_update = true, dots_out = false, png = true, apng = true, stats = false;
    bool mask_out = false;
};

stipple::cli::Args* g_args = nullptr;  // for die() outside parse()

[[noreturn]] void die(const std::string& message) {
    g_args->die(message);
}

Options parse(stipple::cli::Args& args) {
    Options o;
    std::string a;
    while (args.next(&a)) {
        auto value = [&]() { return args.value(a); };
        auto parse_double = [&](const std::string& option, const char* text, double lo, double hi) {
            return args.number(option, text, lo, hi);
        };
        if (a == "-h" || a == "--help") {
            std::fputs(kUsage, stdout);
            std::exit(0);
        } else if (a == "--out") {
            o.out = value();
        } else if (a == "--clip") {
            o.clip = value();
        } else if (a == "--blend" || a == "--crossfade") {
            std::string v = value();
            size_t colon = v.rfind(':');
            if (colon == std::string::npos || colon == 0)
                die(a + " takes CLIP:" + (a == "--blend" ? "WEIGHT" : "SECONDS") + ", got '" + v +
                    "'");
            o.second_clip = v.substr(0, colon);
            o.mix = a == "--blend" ? Options::Mix::blend : Options::Mix::crossfade;
            o.mix_amount = a == "--blend"
                               ? parse_double(a + " weight", v.c_str() + colon + 1, 0, 1)
                               : parse_double(a + " seconds", v.c_str() + colon + 1, 0.001, 1e4);
        } else if (a == "--skinning") {
            std::string v = value();
            if (v != "lbs" && v != "dqs") die("--skinning must be lbs or dqs, got '" + v + "'");
            o.dqs = v == "dqs";
        } else if (a == "--frames") {
            o.frames = long(parse_double(a, value(), 1, 100000));
        } else if (a == "--fps") {
            o.fps = parse_double(a, value(), 0.001, 1000);
        } else if (a == "--time") {
            o.time0 = parse_double(a, value(), -1e6, 1e6);
        } else if (a == "--size") {
            const char* s = value();
            if (std::sscanf(s, "%dx%d", &o.width, &o.height) != 2 || o.width < 16 ||
                o.height < 16 || o.width > 8192 || o.height > 8192)
                die(std::string("--size must be WxH with 16 <= W, H <= 8192, got '") + s + "'");
        } else if (a == "--zoom") {
            o.zoom = parse_double(a, value(), 0.01, 1000);
        } else if (a == "--zoom-to") {
            o.zoom_to = parse_double(a, value(), 0.01, 1000);
        } else if (a == "--yaw") {
            o.yaw = parse_double(a, value(), -3600, 3600);
        } else if (a == "--pitch") {
            o.pitch = parse_double(a, value(), -90, 90);
        } else if (a == "--tone") {
            o.tone = parse_double(a, value(), 0, 1);
        } else if (a == "--point-size") {
            o.point_size = parse_double(a, value(), 0.5, 32);
        } else if (a == "--background") {
            const char* s = value();
            unsigned rgb = 0;
            if (std::strlen(s) != 6 || std::sscanf(s, "%6x", &rgb) != 1)
                die(std::string("--background must be RRGGBB hex, got '") + s + "'");
            for (int k = 0; k < 3; ++k) o.background[k] = float((rgb >> (16 - 8 * k)) & 0xFF) / 255;
        } else if (a == "--no-relevance-update") {
            o.relevance_update = false;
        } else if (a == "--dark-tone") {
            o.dark_tone = parse_double(a, value(), 0, 1);
        } else if (a == "--refinement-budget") {
            o.refinement_budget = long(parse_double(a, value(), 0, 4194304));
        } else if (a == "--no-silhouettes") {
            o.silhouettes = false;
        } else if (a == "--line-width") {
            o.line_width = parse_double(a, value(), 0.5, 16);
        } else if (a == "--dots-out") {
            o.dots_out = true;
        } else if (a == "--mask-out") {
            o.mask_out = true;
        } else if (a == "--no-png") {
            o.png = false;
        } else if (a == "--no-apng") {
            o.apng = false;
        } else if (a == "--stats") {
            o.stats = true;
        } else if (a == "--backend") {
            o.backend = value();
            if (o.backend != "egl" && o.backend != "osmesa")
                die("--backend must be egl or osmesa, got '" + o.backend + "'");
        } else if (!a.empty() && a[0] == '-') {
            die("unknown option '" + a + "' (see --help)");
        } else if (o.asset.empty()) {
            o.asset = a;
        } else {
            die("more than one asset given ('" + o.asset + "', '" + a + "')");
        }
    }
    if (o.asset.empty()) die("no asset given (see --help)");
    if (o.out.empty()) die("no output directory: pass --out DIR");
    return o;
}

std::string frame_path(const Options& o, const char* stem, long frame, const char* ext) {
    char name[64];
    std::snprintf(name, sizeof(name), "/%s_%04ld.%s", stem, frame, ext);
    return o.out + name;
}

// Writes the dots the last frame shows (stipple::pipeline_visible_dots) as CSV.
bool write_dots(const stipple::Pipeline& p, const float* depth, stipple::VisibleDot* scratch,
                const std::string& path) {
    FILE* f = std::fopen(path.c_str(), "w");
    if (!f) return false;
    std::fputs("id,x,y,size\n", f);
    const uint32_t n = stipple::pipeline_visible_dots(p, depth, scratch, p.point_capacity);
    for (uint32_t i = 0; i < n; ++i)
        std::fprintf(f, "%llu,%.2f,%.2f,%.3f\n", static_cast<unsigned long long>(scratch[i].id),
                     double(scratch[i].x), double(scratch[i].y), double(scratch[i].size));
    return std::fclose(f) == 0;
}

// Writes the object mask of the last frame from the mesh pass's depth (bottom row first, 1 =
// background): white where depth < 1, black elsewhere, top row first like the frame PNGs.
// `rgba` is scratch of width * height * 4 bytes.
bool write_mask(const float* depth, int w, int h, uint8_t* rgba, const std::string& path,
                std::string* error) {
    const size_t pixels = size_t(w) * size_t(h);
    for (size_t i = 0; i < pixels; ++i) {
        const uint8_t v = depth[i] < 1.0f ? 255 : 0;
        rgba[i * 4] = rgba[i * 4 + 1] = rgba[i * 4 + 2] = v;
        rgba[i * 4 + 3] = 255;
    }
    return stipple::image::write_png(path.c_str(), w, h, rgba, /*bottom_up=*/true, error);
}

}  // namespace

int main(int argc, char** argv) {
    stipple::cli::Args args{"stipple-play", argc, argv};
    g_args = &args;
    Options o = parse(args);
    stipple::Asset asset;
    stipple::LoadStatus st = stipple::load_asset_file(o.asset.c_str(), &asset);
    if (!st.ok()) die(o.asset + ": " + st.message);
    int clip = asset.clip_count > 0 ? 0 : -1;
    if (!o.clip.empty()) {
        clip = stipple::find_clip(asset, o.clip.c_str());
        if (clip < 0) die("no clip '" + o.clip + "' in " + o.asset);
    }
    int second = -1;
    if (o.mix != Options::Mix::none) {
        second = stipple::find_clip(asset, o.second_clip.c_str());
        if (second < 0) die("no clip '" + o.second_clip + "' in " + o.asset);
    }
    mkdir(o.out.c_str(), 0755);
    struct stat info;
    if (stat(o.out.c_str(), &info) != 0 || !S_ISDIR(info.st_mode))
        die("cannot create output directory '" + o.out + "'");

    stipple::platform::HeadlessConfig hc;
    hc.width = o.width;
    hc.height = o.height;
    hc.allow_egl = o.backend != "osmesa";
    hc.allow_osmesa = o.backend != "egl";
    stipple::platform::HeadlessContext context;
    std::string error;
    if (!stipple::platform::create_headless_context(hc, &context, &error)) die(error);
    stipple::GlApi gl;
    if (const char* missing = stipple::load_gl_api(stipple::platform::proc_loader(context), &gl))
        die(std::string("GL function ") + missing + " unavailable");

    stipple::PipelineConfig pc;
    pc.width = o.width;
    pc.height = o.height;
    pc.zoom = float(o.zoom);
    pc.yaw_degrees = float(o.yaw);
    pc.pitch_degrees = float(o.pitch);
    pc.frame_clip = clip;  // zoom 1 frames every pose of the clips played
    pc.frame_blend_clip = second;
    pc.relevance_update = o.relevance_update;
    pc.dark_tone = float(o.dark_tone);
    pc.refinement_budget = uint32_t(o.refinement_budget);
    pc.constant_tone = float(o.tone);
    pc.max_point_size = float(o.point_size);
    pc.silhouettes = o.silhouettes;
    pc.depth_readback = o.dots_out || o.mask_out;
    pc.skinning = o.dqs ? stipple::anim::Skinning::dqs : stipple::anim::Skinning::lbs;
    pc.line_width = float(o.line_width);
    std::memcpy(pc.background, o.background, sizeof(pc.background));
    std::unique_ptr<stipple::Pipeline> pipeline(new stipple::Pipeline());
    char message[256] = {};
    if (!stipple::pipeline_init(pipeline.get(), asset, gl, pc, message, sizeof(message)))
        die(std::string("renderer: ") + message);

    const size_t pixels = size_t(o.width) * size_t(o.height);
    std::unique_ptr<uint8_t[]> rgba(new uint8_t[pixels * 4]);
    std::unique_ptr<float[]> depth_scratch, depth;
    std::unique_ptr<stipple::VisibleDot[]> dot_scratch;
    std::unique_ptr<uint8_t[]> mask_rgba;
    if (o.dots_out || o.mask_out) {
        depth_scratch.reset(new float[pixels * 4]);
        depth.reset(new float[pixels]);
        if (o.dots_out) dot_scratch.reset(new stipple::VisibleDot[pipeline->point_capacity]);
    }
    if (o.mask_out) mask_rgba.reset(new uint8_t[pixels * 4]);
    stipple::image::ApngWriter apng;
    int fps_num = int(std::lround(o.fps * 1000)), fps_den = 1000;
    while (fps_num > 65535) fps_num /= 10, fps_den /= 10;
    if (o.apng && !apng.open((o.out + "/anim.png").c_str(), std::max(fps_num, 1), fps_den, &error))
        die(error);

    stipple::StageTimes times;
    double frame_ms = 0, drawn = 0, refined = 0, budget_scale = 1;
    for (long f = 0; f < o.frames; ++f) {
        // Clips loop (the sampler wraps the time); a crossfade starts CLIP2 at its time 0.
        const double elapsed = double(f) / o.fps;
        stipple::AnimationState state;
        state.clip = clip;
        state.time = float(o.time0 + elapsed);
        state.blend_clip = second;
        state.blend_time = float(o.mix == Options::Mix::crossfade ? elapsed : o.time0 + elapsed);
        state.blend_weight =
            float(o.mix == Options::Mix::crossfade ? std::min(elapsed / o.mix_amount, 1.0)
                                                   : o.mix_amount);
        auto start = std::chrono::steady_clock::now();
        if (o.zoom_to > 0 && o.frames > 1) {
            stipple::PipelineConfig view = pipeline->config;
            view.zoom = float(o.zoom * std::pow(o.zoom_to / o.zoom, double(f) / double(o.frames - 1)));
            stipple::pipeline_set_view(pipeline.get(), view);
        }
        stipple::pipeline_frame(pipeline.get(), state, &times);
        auto readback_start = std::chrono::steady_clock::now();
        stipple::renderer_read_color(&pipeline->renderer, rgba.get());
        auto end = std::chrono::steady_clock::now();
        times.readback += std::chrono::duration<double, std::milli>(end - readback_start).count();
        frame_ms += std::chrono::duration<double, std::milli>(end - start).count();
        drawn += pipeline->points_drawn;
        refined += pipeline->refined_count;
        budget_scale = std::min(budget_scale, double(pipeline->refinement_stats.budget_scale));
        if (o.png && !stipple::image::write_png(frame_path(o, "frame", f, "png").c_str(), o.width,
                                                o.height, rgba.get(), true, &error))
            die(error);
        if (o.apng && !apng.add_frame(o.width, o.height, rgba.get(), true, &error)) die(error);
        if (o.dots_out || o.mask_out)
            stipple::renderer_read_depth(&pipeline->renderer, depth_scratch.get(), depth.get());
        if (o.dots_out &&
            !write_dots(*pipeline, depth.get(), dot_scratch.get(), frame_path(o, "dots", f, "csv")))
            die("cannot write dots file in '" + o.out + "'");
        if (o.mask_out && !write_mask(depth.get(), o.width, o.height, mask_rgba.get(),
                                      frame_path(o, "mask", f, "png"), &error))
            die(error);
    }
    if (o.apng && !apng.finish(&error)) die(error);

    if (o.stats) {
        const double n = double(o.frames);
        std::printf(
            "{\"asset\": \"%s\", \"backend\": \"%s\", \"renderer\": \"%s\", \"clip\": \"%s\", "
            "\"frames\": %ld, \"width\": %d, \"height\": %d, \"points_total\": %u, "
            "\"points_drawn\": %.1f, \"points_refined\": %.1f, \"refinement_budget_scale\": %.3f, "
            "\"ms_per_frame\": %.3f, \"ms_per_stage\": {\"sample\": %.3f, "
            "\"skin\": %.3f, \"place\": %.3f, \"relevance\": %.3f, \"refine\": %.3f, \"size\": %.3f, "
            "\"silhouette\": %.3f, \"draw\": %.3f, \"readback\": %.3f}}\n",
            o.asset.c_str(), stipple::platform::backend_name(context.backend),
            context.renderer.c_str(), clip >= 0 ? asset.clips[clip].name : "(rest pose)", o.frames,
            o.width, o.height, asset.points.point_count, drawn / n, refined / n, budget_scale,
            frame_ms / n, times.sample / n, times.skin / n, times.place / n, times.relevance / n,
            times.refine / n, times.size / n,
            times.silhouette / n, times.draw / n, times.readback / n);
    }
    stipple::pipeline_destroy(pipeline.get());
    stipple::platform::destroy_headless_context(&context);
    return 0;
}
