// An on-screen window for the kiosk player (stipple-play --window): an X11 window with an EGL
// window surface and a GLES 3 context, vsync'd swaps, a title, and its input as a small
// platform-neutral event list. X11 and EGL stay inside platform/window_context.cpp; the
// renderer still draws into its own framebuffer, which the caller copies to the window's
// default framebuffer (renderer_blit_to_default) before swap_window.
#pragma once
#include <string>

#include "platform/headless_context.h"  // ContextStatus, ProcLoader

namespace stipple::platform {

// The keys the kiosk reacts to; every other key is `other`. Letter keys ignore case.
enum class Key { other, space, left, right, up, down, plus, minus, l, s, escape };

struct WindowEvent {
    enum class Type { key, close, resize } type = Type::key;
    Key key = Key::other;
    bool shift = false;         // key: a Shift key was held
    int width = 0, height = 0;  // resize: the window's new size
};

struct WindowConfig {
    int width = 640;  // ignored when fullscreen
    int height = 480;
    bool fullscreen = false;  // asks the window manager (_NET_WM_STATE_FULLSCREEN)
    std::string title = "stipple";
    bool vsync = true;  // eglSwapInterval 1
    // llvmpipe's rasterizer threads while the window's display is initialised: as
    // HeadlessConfig::raster_threads (-1: the driver's default; 0 .. kMaxRasterThreads).
    int raster_threads = -1;
};

struct WindowContext {
    void* x_display = nullptr;     // Display*
    unsigned long x_window = 0;    // Window
    unsigned long x_colormap = 0;  // Colormap of the window's visual
    unsigned long wm_delete = 0;   // Atom WM_DELETE_WINDOW
    void* egl_display = nullptr;
    void* egl_surface = nullptr;
    void* egl_context = nullptr;
    int width = 0, height = 0;  // the window's size now (resize events update it)
    std::string renderer;       // GL_RENDERER of the context
};

// Opens the window, creates the context and makes it current on this thread. Fails with
// no_context and a one-line message: "no X display: set DISPLAY or run under xvfb-run" when
// there is no X server, else the step that failed.
[[nodiscard]] ContextStatus create_window_context(const WindowConfig& config, WindowContext* out);

// The context's get-proc-address, for stipple::load_gl_api.
ProcLoader window_proc_loader(const WindowContext& context);

// Shows the back buffer (waits for vsync when asked for).
void swap_window(WindowContext* context);

void set_window_title(WindowContext* context, const std::string& title);

// Takes the window's pending events (does not wait), at most `capacity`, and returns how many
// were written. Resize events also update context->width/height.
int poll_window_events(WindowContext* context, WindowEvent* events, int capacity);

void destroy_window_context(WindowContext* context);

}  // namespace stipple::platform
