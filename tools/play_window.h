// stipple-play --window: the kiosk player. Plays an asset in an X11 window (platform/
// window_context.h) in real time against the wall clock, looping, with vsync; the keys are
// tools/kiosk_keys.h's; the title shows the frame rate and the dots drawn. The frame is drawn
// into the renderer's offscreen framebuffer as headless, then blitted to the window.
// For checks: --frames N stops after N frames, --fixed-time T draws every frame at clip time T
// (no clock) and --screenshot FILE.png writes the window's back buffer after the last frame.
#pragma once
#include <string>

#include "runtime/asset.h"
#include "runtime/frame_config.h"
#include "tools/cli_options.h"

namespace stipple::play {

struct WindowOptions {
    bool window = false, fullscreen = false;
    std::string screenshot;  // --screenshot FILE.png
    bool fixed = false;      // --fixed-time given
    double fixed_time = 0;
};

// The usage lines of the options below, for the player's --help.
extern const char* const kWindowUsage;

// Registers --window, --fullscreen, --fixed-time and --screenshot.
void add_window_options(cli::Parser& parser, WindowOptions* options);

// What the kiosk plays.
struct KioskPlay {
    const Asset* asset = nullptr;
    FrameConfig config;       // as headless (size, camera, tone...): the first frame's settings
    int clip = -1;            // -1: the rest pose
    double time0 = 0;         // clip time of the first frame (seconds)
    long frames = 0;          // > 0: quit after this many frames; 0: run until Esc or close
    std::string out;          // where S saves PNGs ("": the current directory)
    int raster_threads = -1;  // --raster-threads (platform::WindowConfig::raster_threads)
};

// Opens the window and plays until Esc, the window's close button or `play.frames`. Returns
// the process's exit status (1 after a --check-gl error); fails through `parser` (one line,
// exit 1) when the window, the GL API or the pipeline cannot be set up.
int run_kiosk(const KioskPlay& play, const WindowOptions& options, const cli::Parser& parser);

}  // namespace stipple::play
