#include "tools/play_window.h"

#include <sys/stat.h>

#include <chrono>
#include <cstdio>
#include <memory>
#include <vector>

#include "platform/window_context.h"
#include "runtime/frame_pipeline.h"
#include "tools/image_write.h"
#include "tools/kiosk_keys.h"

namespace stipple::play {

const char* const kWindowUsage =
    "  --window                play in an X11 window in real time, looping, until Esc or the\n"
    "                          window closes (needs DISPLAY; without a screen: xvfb-run); keys:\n"
    "                          space pause, left/right clip, Shift+left/right yaw, up/down\n"
    "                          pitch, +/- zoom, L key light, S save kiosk_NNNN.png (to --out\n"
    "                          DIR, else .), Esc quit. --out is optional, --frames N stops\n"
    "                          after N frames; --fps and the per-frame files are unused\n"
    "  --fullscreen            with --window: cover the screen (the frame is scaled to fit)\n"
    "  --fixed-time T          with --window: draw every frame at clip time T (no clock)\n"
    "  --screenshot FILE.png   with --window: after the last frame, write the window's back\n"
    "                          buffer (read before the swap) as PNG\n";

void add_window_options(cli::Parser& parser, WindowOptions* o) {
    parser.flag("--window", &o->window)
        .flag("--fullscreen", &o->fullscreen)
        .custom("--fixed-time",
                [&parser, o](const std::string& name, const std::string& v) {
                    o->fixed_time = parser.number_value(name, v, -1e6, 1e6);
                    o->fixed = true;
                })
        .text("--screenshot", &o->screenshot);
}

namespace {

// Key-light directions L cycles through (eye space, toward the light). Preset 0 is the
// pipeline's own light (upper left, in front); the runtime has no light setting, so the kiosk
// writes the Pipeline's light fields, which pipeline_set_view recomputes (see set_light).
const glm::vec3 kLightPresets[] = {
    {0.0f, 0.0f, 0.0f},      // 0: the pipeline's default, kept as pipeline_init set it
    {0.5f, 0.6f, 0.6f},      // upper right
    {0.0f, 0.0f, 1.0f},      // head-on (flat)
    {0.0f, 1.0f, 0.15f},     // from above
    {-0.9f, -0.1f, 0.45f}};  // low from the left (raking)
constexpr int kLightCount = int(sizeof(kLightPresets) / sizeof(kLightPresets[0]));

struct Kiosk {
    platform::WindowContext window;
    GlApi gl;
    std::unique_ptr<Pipeline> pipeline;
    KioskState state, shown;  // wanted, and what the pipeline's view is now
    KioskLimits limits;
    glm::vec3 default_light{0.0f, 0.0f, 1.0f};
};

// One camera-space key light along `eye_dir` (FrameConfig::lights, set between frames).
void set_light(Pipeline* p, glm::vec3 eye_dir) {
    FrameConfig view = p->config;
    view.light_count = 1;
    view.lights[0] = Light{{eye_dir.x, eye_dir.y, eye_dir.z}, 1.0f, true};
    (void)pipeline_set_view(p, view);  // a unit direction and intensity 1: always in range
}

// Brings the pipeline's camera and light to k->state.
void apply_view(Kiosk* k, const cli::Parser& parser) {
    KioskState& s = k->state;
    const bool camera =
        s.zoom != k->shown.zoom || s.yaw != k->shown.yaw || s.pitch != k->shown.pitch;
    if (camera) {
        FrameConfig view = k->pipeline->config;
        view.zoom = s.zoom;
        view.yaw_degrees = s.yaw;
        view.pitch_degrees = s.pitch;
        const Status st = pipeline_set_view(k->pipeline.get(), view);
        if (!st.ok()) parser.fail(std::string("--window view: ") + st.message);
    }
    if (camera || s.light != k->shown.light)
        set_light(k->pipeline.get(), s.light == 0 ? k->default_light : kLightPresets[s.light]);
    k->shown = s;
}

// Opens the window and the pipeline; fails through the parser.
void open_kiosk(const KioskPlay& play, const WindowOptions& o, const cli::Parser& parser,
                Kiosk* k) {
    platform::WindowConfig wc;
    wc.width = play.config.width;
    wc.height = play.config.height;
    wc.fullscreen = o.fullscreen;
    wc.title = "stipple";
    wc.raster_threads = play.raster_threads;
    const platform::ContextStatus created = platform::create_window_context(wc, &k->window);
    if (!created.ok()) parser.fail(created.message);
    const Status loaded = load_gl_api(platform::window_proc_loader(k->window), &k->gl);
    if (!loaded.ok()) parser.fail(loaded.message);
    k->pipeline.reset(new Pipeline());
    const Status init = pipeline_init(k->pipeline.get(), *play.asset, k->gl, play.config);
    if (!init.ok()) parser.fail(std::string("renderer: ") + init.message);
    k->default_light = k->pipeline->light_eye;
    const FrameConfig& c = k->pipeline->config;  // resolved
    k->state.clip = play.clip;
    k->state.zoom = c.zoom;
    k->state.yaw = c.yaw_degrees;
    k->state.pitch = c.pitch_degrees;
    k->shown = k->state;
    k->limits.clip_count = int(play.asset->clip_count);
    k->limits.light_count = kLightCount;
}

bool write_rgba(const std::string& path, int w, int h, const uint8_t* rgba,
                const cli::Parser& parser) {
    std::string error;
    if (!image::write_png(path.c_str(), w, h, rgba, true, &error)) parser.fail(error);
    return true;
}

// S: the offscreen frame (the picture at its own size, as headless) as kiosk_NNNN.png.
void save_frame(Kiosk* k, const std::string& dir, long frame, const cli::Parser& parser) {
    const RendererConfig& c = k->pipeline->renderer.config;
    std::vector<uint8_t> rgba(size_t(c.width) * size_t(c.height) * 4);
    renderer_read_color(&k->pipeline->renderer, rgba.data());
    char name[32];
    std::snprintf(name, sizeof(name), "kiosk_%04ld.png", frame);
    const std::string path = (dir.empty() ? std::string(".") : dir) + "/" + name;
    write_rgba(path, c.width, c.height, rgba.data(), parser);
    std::printf("saved %s\n", path.c_str());
    std::fflush(stdout);
}

// --screenshot: the window's back buffer (after the blit, before the swap).
void write_screenshot(Kiosk* k, const std::string& path, const cli::Parser& parser) {
    const int w = k->window.width, h = k->window.height;
    std::vector<uint8_t> rgba(size_t(w) * size_t(h) * 4);
    k->gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    k->gl.ReadBuffer(GL_BACK);
    k->gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    k->gl.ReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    write_rgba(path, w, h, rgba.data(), parser);
}

void handle_events(Kiosk* k) {
    platform::WindowEvent events[32];
    const int n = platform::poll_window_events(&k->window, events, 32);
    for (int i = 0; i < n; ++i) {
        if (events[i].type == platform::WindowEvent::Type::close) k->state.quit = true;
        if (events[i].type == platform::WindowEvent::Type::key)
            k->state = apply_key(k->state, events[i].key, k->limits, events[i].shift);
    }
}

// The title every half second: "stipple — <fps> fps, <dots> dots".
struct TitleClock {
    std::chrono::steady_clock::time_point since = std::chrono::steady_clock::now();
    long frames = 0;
};

void update_title(Kiosk* k, TitleClock* t) {
    ++t->frames;
    const auto now = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(now - t->since).count();
    if (seconds < 0.5) return;
    char title[96];
    std::snprintf(title, sizeof(title), "stipple \xE2\x80\x94 %.1f fps, %u dots",
                  double(t->frames) / seconds, k->pipeline->points_drawn);
    platform::set_window_title(&k->window, title);
    *t = TitleClock();
}

}  // namespace

int run_kiosk(const KioskPlay& play, const WindowOptions& o, const cli::Parser& parser) {
    if (!play.out.empty()) mkdir(play.out.c_str(), 0755);
    Kiosk k;
    open_kiosk(play, o, parser, &k);
    TitleClock title;
    double clock = 0;  // animation seconds played (stops while paused)
    auto before = std::chrono::steady_clock::now();
    for (long frame = 0;; ++frame) {
        handle_events(&k);
        const bool last_frame = k.state.quit || (play.frames > 0 && frame + 1 >= play.frames);
        const auto now = std::chrono::steady_clock::now();
        if (!k.state.paused) clock += std::chrono::duration<double>(now - before).count();
        before = now;
        apply_view(&k, parser);
        const double time = o.fixed ? o.fixed_time : play.time0 + clock;
        pipeline_frame(k.pipeline.get(), k.state.clip, float(time), nullptr);
        if (k.state.save) save_frame(&k, play.out, frame, parser);
        k.state.save = false;
        renderer_blit_to_default(&k.pipeline->renderer, k.window.width, k.window.height);
        if (last_frame && !o.screenshot.empty()) write_screenshot(&k, o.screenshot, parser);
        platform::swap_window(&k.window);
        update_title(&k, &title);
        if (last_frame) break;
    }
    const GlErrorLog& errors = pipeline_gl_errors(*k.pipeline);
    if (errors.count > 0)
        std::fprintf(stderr, "stipple-play: GL error %s after the %s pass (%u GL errors)\n",
                     gl_error_name(errors.first_error), errors.first_pass ? errors.first_pass : "?",
                     errors.count);
    pipeline_destroy(k.pipeline.get());
    platform::destroy_window_context(&k.window);
    return errors.count > 0 ? 1 : 0;
}

}  // namespace stipple::play
