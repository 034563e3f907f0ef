#include "window.h"

#include <GLES3/gl3.h>
#include <string.h>

#ifdef HAVE_X11
#include <EGL/eglext.h>
#include <X11/Xlib.h>

int window_open(window* w, int width, int height, const char* title) {
    memset(w, 0, sizeof(*w));
    Display* x = XOpenDisplay(NULL);
    if (!x) return -1;
    w->x_display = x;
    Window win = XCreateSimpleWindow(x, DefaultRootWindow(x), 0, 0, (unsigned)width,
                                     (unsigned)height, 0, 0, 0);
    XStoreName(x, win, title);
    XMapWindow(x, win);
    XFlush(x);
    w->x_window = win;
    w->display = eglGetPlatformDisplay(EGL_PLATFORM_X11_KHR, x, NULL);
    if (w->display == EGL_NO_DISPLAY || !eglInitialize(w->display, NULL, NULL)) return -1;
    const EGLint config_attribs[] = {EGL_SURFACE_TYPE,
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
    EGLConfig config;
    EGLint count = 0;
    if (!eglChooseConfig(w->display, config_attribs, &config, 1, &count) || count == 0) return -1;
    eglBindAPI(EGL_OPENGL_ES_API);
    const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_NONE};
    w->context = eglCreateContext(w->display, config, EGL_NO_CONTEXT, context_attribs);
    w->surface = eglCreatePlatformWindowSurface(w->display, config, &win, NULL);
    if (w->context == EGL_NO_CONTEXT || w->surface == EGL_NO_SURFACE) return -1;
    if (!eglMakeCurrent(w->display, w->surface, w->surface, w->context)) return -1;
    eglSwapInterval(w->display, 1);
    return 0;
}

void window_present(window* w, unsigned fbo, int width, int height) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    eglSwapBuffers(w->display, w->surface);
}

void window_close(window* w) {
    eglMakeCurrent(w->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroySurface(w->display, w->surface);
    eglDestroyContext(w->display, w->context);
    eglTerminate(w->display);
    XDestroyWindow((Display*)w->x_display, (Window)w->x_window);
    XCloseDisplay((Display*)w->x_display);
}

#else

int window_open(window* w, int width, int height, const char* title) {
    (void)w, (void)width, (void)height, (void)title;
    return -1; /* built without X11 */
}
void window_present(window* w, unsigned fbo, int width, int height) {
    (void)w, (void)fbo, (void)width, (void)height;
}
void window_close(window* w) {
    (void)w;
}

#endif
