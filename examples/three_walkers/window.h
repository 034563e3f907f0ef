/* An X11 window with an EGL window surface and a GLES 3 context, for showing the example's
 * frames (three_walkers --window). Without X11 at build time, window_open fails. */
#ifndef WINDOW_H
#define WINDOW_H

#include <EGL/egl.h>

typedef struct window {
    void* x_display;
    unsigned long x_window;
    EGLDisplay display;
    EGLSurface surface;
    EGLContext context;
} window;

int window_open(window* w, int width, int height, const char* title); /* 0 on success */
/* Copies the application's framebuffer to the window and swaps. */
void window_present(window* w, unsigned fbo, int width, int height);
void window_close(window* w);

#endif
