/* three_walkers: a tiny application that owns its GL context, framebuffer, camera and scene,
 * and draws three stippled CesiumMan instances into its own frame through the stipple C API
 * (runtime/stipple.h, docs/integration.md). It renders into its own framebuffer and writes
 * the frame as a PPM; with --window it also shows the frames in an X11 window (EGL; runs under
 * xvfb-run), else it needs no display at all (EGL surfaceless: CI).
 *   three_walkers OUT.ppm [TIME_SECONDS] [--window FRAMES] */
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES3/gl3.h>
#include <runtime/stipple.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene.h"
#include "window.h"

enum { kWidth = 640, kHeight = 480, kWalkers = 3 };

/* A GLES 3 context with no surface: the application renders into its own framebuffer. */
static int open_context(EGLDisplay* display) {
    *display = eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
    if (*display == EGL_NO_DISPLAY || !eglInitialize(*display, NULL, NULL)) return -1;
    const EGLint config_attribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE,
                                     EGL_OPENGL_ES3_BIT, EGL_NONE};
    EGLConfig config;
    EGLint count = 0;
    if (!eglChooseConfig(*display, config_attribs, &config, 1, &count) || count == 0) return -1;
    eglBindAPI(EGL_OPENGL_ES_API);
    const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_NONE};
    EGLContext context = eglCreateContext(*display, config, EGL_NO_CONTEXT, context_attribs);
    if (context == EGL_NO_CONTEXT) return -1;
    return eglMakeCurrent(*display, EGL_NO_SURFACE, EGL_NO_SURFACE, context) ? 0 : -1;
}

/* The application's framebuffer: colour and depth renderbuffers. */
static GLuint make_framebuffer(void) {
    GLuint fbo, rb[2];
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glGenRenderbuffers(2, rb);
    glBindRenderbuffer(GL_RENDERBUFFER, rb[0]);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, kWidth, kHeight);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb[0]);
    glBindRenderbuffer(GL_RENDERBUFFER, rb[1]);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, kWidth, kHeight);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, rb[1]);
    return glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE ? fbo : 0;
}

/* The application's frame: its own clear and scene with depth, then the three walkers. */
static void draw_frame(GLuint fbo, const scene* scene, stipple_app_view* view,
                       const float view_projection[16], stipple_player* const* walkers,
                       float time) {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, kWidth, kHeight);
    glDepthMask(GL_TRUE);
    glClearColor(0.93f, 0.91f, 0.86f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    scene_draw(scene, view_projection);
    for (int i = 0; i < kWalkers; ++i) {
        mat4_translate(view->model, -1.2f + 1.2f * (float)i, 0.0f, 0.0f);
        /* Different phases of the walk; the third crossfades toward another phase. */
        const float t = time + 0.66f * (float)i;
        if (i < 2)
            stipple_player_draw_into(walkers[i], view, 0, t, -1, 0.0f, 0.0f);
        else
            stipple_player_draw_into(walkers[i], view, 0, t, 0, t + 1.0f, 0.5f);
    }
}

static int fail(const char* what) {
    fprintf(stderr, "three_walkers: %s: %s\n", what, stipple_last_error());
    return 1;
}

int main(int argc, char** argv) {
    if (argc < 2) {
        fprintf(stderr, "usage: three_walkers OUT.ppm [TIME_SECONDS]\n");
        return 2;
    }
    const float time = argc > 2 ? (float)atof(argv[2]) : 0.5f;
    const int window_frames = argc > 4 && strcmp(argv[3], "--window") == 0 ? atoi(argv[4]) : 0;
    EGLDisplay display;
    window win = {0};
    if (window_frames > 0) {
        if (window_open(&win, kWidth, kHeight, "three walkers") != 0)
            return fprintf(stderr, "three_walkers: no window (DISPLAY? xvfb-run)\n"), 1;
        display = win.display;
    } else if (open_context(&display) != 0) {
        return fprintf(stderr, "three_walkers: no EGL context\n"), 1;
    }
    GLuint fbo = make_framebuffer();
    scene scene;
    if (!fbo || scene_init(&scene) != 0) return fprintf(stderr, "three_walkers: GL setup\n"), 1;

    stipple_asset* asset;
    if (stipple_asset_load_file(WALKER_ASSET, &asset) != STIPPLE_OK) return fail(WALKER_ASSET);
    stipple_player_desc desc = {0};
    desc.width = kWidth;
    desc.height = kHeight;
    desc.get_proc_address = (stipple_get_proc_fn)eglGetProcAddress;
    stipple_player* walkers[kWalkers]; /* three instances of one loaded asset */
    for (int i = 0; i < kWalkers; ++i)
        if (stipple_player_create(asset, &desc, &walkers[i]) != STIPPLE_OK) return fail("create");

    stipple_app_view view = {0};
    const float eye[3] = {0.0f, 1.4f, 5.0f}, target[3] = {0.0f, 0.75f, 0.0f};
    mat4_look_at(view.view, eye, target);
    mat4_perspective(view.projection, 0.75f, (float)kWidth / kHeight, 0.1f, 50.0f);
    view.viewport[0] = view.viewport[1] = 0;
    view.viewport[2] = kWidth;
    view.viewport[3] = kHeight;
    float view_projection[16];
    mat4_multiply(view_projection, view.projection, view.view);

    const int frames = window_frames > 0 ? window_frames : 1;
    for (int f = 0; f < frames; ++f) {
        draw_frame(fbo, &scene, &view, view_projection, walkers, time + (float)f / 30.0f);
        if (window_frames > 0) window_present(&win, fbo, kWidth, kHeight);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    unsigned char* rgba = malloc((size_t)kWidth * kHeight * 4);
    glReadPixels(0, 0, kWidth, kHeight, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    const int written = write_ppm(argv[1], kWidth, kHeight, rgba);
    free(rgba);
    for (int i = 0; i < kWalkers; ++i) stipple_player_destroy(walkers[i]);
    stipple_asset_destroy(asset);
    scene_destroy(&scene);
    if (window_frames > 0)
        window_close(&win);
    else
        eglTerminate(display);
    if (written != 0) return fprintf(stderr, "three_walkers: cannot write %s\n", argv[1]), 1;
    printf("three_walkers: wrote %s\n", argv[1]);
    return 0;
}
