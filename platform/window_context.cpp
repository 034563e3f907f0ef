#include "platform/window_context.h"

#define EGL_EGLEXT_PROTOTYPES
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES3/gl3.h>

#include <cstdio>
#include <cstdlib>
#include <utility>

#include "platform/raster_threads.h"

#ifdef STIPPLE_HAVE_X11
#include <X11/Xatom.h>
#include <X11/Xlib.h>
#include <X11/Xutil.h>
#include <X11/keysym.h>
#endif

namespace stipple::platform {

namespace {

ContextStatus failed(std::string why) {
    return {ContextError::no_context, std::move(why)};
}

void* egl_proc(const char* name) {
    return reinterpret_cast<void*>(eglGetProcAddress(name));
}

#ifdef STIPPLE_HAVE_X11

std::string egl_error(const char* what) {
    char buf[96];
    std::snprintf(buf, sizeof(buf), "%s failed (EGL error 0x%04x)", what, eglGetError());
    return buf;
}

Display* x_display(const WindowContext& c) {
    return static_cast<Display*>(c.x_display);
}

// An RGB8 window config that renders GLES 3; the window's visual must be the config's.
ContextStatus choose_config(EGLDisplay display, EGLConfig* config) {
    const EGLint attribs[] = {EGL_SURFACE_TYPE,
                              EGL_WINDOW_BIT,
                              EGL_RENDERABLE_TYPE,
                              EGL_OPENGL_ES3_BIT,
                              EGL_RED_SIZE,
                              8,
                              EGL_GREEN_SIZE,
                              8,
                              EGL_BLUE_SIZE,
                              8,
                              EGL_NONE};
    EGLint count = 0;
    if (!eglChooseConfig(display, attribs, config, 1, &count) || count == 0)
        return failed("no EGL config with GLES 3 and window support on this X display");
    return {};
}

// The X window, with the visual of `config`, mapped (waits for the server to map it).
ContextStatus open_x_window(const WindowConfig& wc, EGLDisplay egl, EGLConfig config,
                            WindowContext* out) {
    Display* dpy = x_display(*out);
    EGLint visual_id = 0;
    eglGetConfigAttrib(egl, config, EGL_NATIVE_VISUAL_ID, &visual_id);
    XVisualInfo want{};
    want.visualid = VisualID(visual_id);
    int found = 0;
    XVisualInfo* visual = XGetVisualInfo(dpy, VisualIDMask, &want, &found);
    if (!visual || found == 0) return failed("no X visual for the EGL window config");
    const int screen = DefaultScreen(dpy);
    const Window root = RootWindow(dpy, screen);
    XSetWindowAttributes attrs{};
    attrs.colormap = XCreateColormap(dpy, root, visual->visual, AllocNone);
    out->x_colormap = attrs.colormap;
    attrs.event_mask = KeyPressMask | StructureNotifyMask;
    attrs.border_pixel = 0;
    out->width = wc.fullscreen ? DisplayWidth(dpy, screen) : wc.width;
    out->height = wc.fullscreen ? DisplayHeight(dpy, screen) : wc.height;
    const Window window = XCreateWindow(
        dpy, root, 0, 0, unsigned(out->width), unsigned(out->height), 0, visual->depth, InputOutput,
        visual->visual, CWColormap | CWEventMask | CWBorderPixel, &attrs);
    XFree(visual);
    out->x_window = window;
    Atom wm_delete = XInternAtom(dpy, "WM_DELETE_WINDOW", False);
    XSetWMProtocols(dpy, window, &wm_delete, 1);
    out->wm_delete = wm_delete;
    if (wc.fullscreen) {  // EWMH: a window manager that honours it covers the screen
        Atom fullscreen = XInternAtom(dpy, "_NET_WM_STATE_FULLSCREEN", False);
        XChangeProperty(dpy, window, XInternAtom(dpy, "_NET_WM_STATE", False), XA_ATOM, 32,
                        PropModeReplace, reinterpret_cast<unsigned char*>(&fullscreen), 1);
    }
    set_window_title(out, wc.title);
    XMapWindow(dpy, window);
    XEvent event;
    do XWindowEvent(dpy, window, StructureNotifyMask, &event);
    while (event.type != MapNotify);
    return {};
}

// The EGL window surface and a current GLES 3 context on it.
ContextStatus make_window_context(const WindowConfig& wc, WindowContext* out) {
    const RasterThreads raster(wc.raster_threads);  // read in eglInitialize
    EGLDisplay egl = eglGetPlatformDisplay(EGL_PLATFORM_X11_KHR, out->x_display, nullptr);
    if (egl == EGL_NO_DISPLAY) return failed("EGL has no X11 platform display");
    EGLint major = 0, minor = 0;
    if (!eglInitialize(egl, &major, &minor)) return failed(egl_error("eglInitialize(X11)"));
    out->egl_display = egl;
    EGLConfig config = nullptr;
    ContextStatus st = choose_config(egl, &config);
    if (!st.ok()) return st;
    if (!eglBindAPI(EGL_OPENGL_ES_API)) return failed(egl_error("eglBindAPI(GLES)"));
    const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_NONE};
    out->egl_context = eglCreateContext(egl, config, EGL_NO_CONTEXT, context_attribs);
    if (out->egl_context == EGL_NO_CONTEXT) {
        out->egl_context = nullptr;
        return failed(egl_error("eglCreateContext(GLES 3)"));
    }
    st = open_x_window(wc, egl, config, out);
    if (!st.ok()) return st;
    Window window = out->x_window;
    out->egl_surface = eglCreatePlatformWindowSurface(egl, config, &window, nullptr);
    if (out->egl_surface == EGL_NO_SURFACE) {
        out->egl_surface = nullptr;
        return failed(egl_error("eglCreatePlatformWindowSurface"));
    }
    if (!eglMakeCurrent(egl, out->egl_surface, out->egl_surface, out->egl_context))
        return failed(egl_error("eglMakeCurrent(window)"));
    eglSwapInterval(egl, wc.vsync ? 1 : 0);
    return {};
}

Key key_of(KeySym sym) {
    switch (sym) {
        case XK_space:
            return Key::space;
        case XK_Left:
        case XK_KP_Left:
            return Key::left;
        case XK_Right:
        case XK_KP_Right:
            return Key::right;
        case XK_Up:
        case XK_KP_Up:
            return Key::up;
        case XK_Down:
        case XK_KP_Down:
            return Key::down;
        case XK_plus:
        case XK_equal:  // the unshifted + key on US layouts
        case XK_KP_Add:
            return Key::plus;
        case XK_minus:
        case XK_KP_Subtract:
            return Key::minus;
        case XK_l:
        case XK_L:
            return Key::l;
        case XK_s:
        case XK_S:
            return Key::s;
        case XK_Escape:
            return Key::escape;
        default:
            return Key::other;
    }
}

#endif  // STIPPLE_HAVE_X11

}  // namespace

ContextStatus create_window_context(const WindowConfig& config, WindowContext* out) {
    *out = WindowContext();
#ifdef STIPPLE_HAVE_X11
    Display* dpy = XOpenDisplay(nullptr);
    if (!dpy) {
        const char* name = std::getenv("DISPLAY");
        return failed(std::string("no X display: set DISPLAY or run under xvfb-run") +
                      (name && *name ? std::string(" (cannot open '") + name + "')" : ""));
    }
    out->x_display = dpy;
    const ContextStatus st = make_window_context(config, out);
    if (!st.ok()) {
        destroy_window_context(out);
        return st;
    }
    auto get_string = reinterpret_cast<PFNGLGETSTRINGPROC>(egl_proc("glGetString"));
    const char* renderer =
        get_string ? reinterpret_cast<const char*>(get_string(GL_RENDERER)) : nullptr;
    out->renderer = renderer ? renderer : "?";
    return {};
#else
    (void)config;
    return failed("built without X11 (install libx11-dev and reconfigure)");
#endif
}

ProcLoader window_proc_loader(const WindowContext& context) {
    (void)context;
    return egl_proc;
}

void swap_window(WindowContext* context) {
    if (context->egl_surface) eglSwapBuffers(context->egl_display, context->egl_surface);
}

void set_window_title(WindowContext* context, const std::string& title) {
#ifdef STIPPLE_HAVE_X11
    if (!context->x_display || !context->x_window) return;
    Display* dpy = x_display(*context);
    const Window window = context->x_window;
    XStoreName(dpy, window, title.c_str());  // old window managers: Latin-1
    XChangeProperty(dpy, window, XInternAtom(dpy, "_NET_WM_NAME", False),
                    XInternAtom(dpy, "UTF8_STRING", False), 8, PropModeReplace,
                    reinterpret_cast<const unsigned char*>(title.data()), int(title.size()));
    XFlush(dpy);
#else
    (void)context;
    (void)title;
#endif
}

int poll_window_events(WindowContext* context, WindowEvent* events, int capacity) {
    int n = 0;
#ifdef STIPPLE_HAVE_X11
    Display* dpy = x_display(*context);
    while (dpy && n < capacity && XPending(dpy) > 0) {
        XEvent event;
        XNextEvent(dpy, &event);
        WindowEvent& e = events[n];
        e = WindowEvent();
        if (event.type == KeyPress) {
            e.key = key_of(XLookupKeysym(&event.xkey, 0));
            e.shift = (event.xkey.state & ShiftMask) != 0;
            ++n;
        } else if (event.type == ClientMessage &&
                   Atom(event.xclient.data.l[0]) == Atom(context->wm_delete)) {
            e.type = WindowEvent::Type::close;
            ++n;
        } else if (event.type == ConfigureNotify && (event.xconfigure.width != context->width ||
                                                     event.xconfigure.height != context->height)) {
            e.type = WindowEvent::Type::resize;
            e.width = context->width = event.xconfigure.width;
            e.height = context->height = event.xconfigure.height;
            ++n;
        }
    }
#else
    (void)context;
    (void)events;
    (void)capacity;
#endif
    return n;
}

void destroy_window_context(WindowContext* context) {
    if (context->egl_display) {
        EGLDisplay egl = context->egl_display;
        eglMakeCurrent(egl, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (context->egl_surface) eglDestroySurface(egl, context->egl_surface);
        if (context->egl_context) eglDestroyContext(egl, context->egl_context);
        eglTerminate(egl);
    }
#ifdef STIPPLE_HAVE_X11
    if (context->x_display) {
        Display* dpy = x_display(*context);
        if (context->x_window) XDestroyWindow(dpy, context->x_window);
        if (context->x_colormap) XFreeColormap(dpy, context->x_colormap);
        XCloseDisplay(dpy);
    }
#endif
    *context = WindowContext();
}

}  // namespace stipple::platform
