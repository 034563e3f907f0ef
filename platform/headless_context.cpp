#include "platform/headless_context.h"

#define EGL_EGLEXT_PROTOTYPES
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES3/gl3.h>
#ifdef STIPPLE_HAVE_OSMESA
#include <GL/osmesa.h>
#endif

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <utility>

#include "platform/raster_threads.h"

namespace stipple::platform {

namespace {

void* egl_proc(const char* name) {
    return reinterpret_cast<void*>(eglGetProcAddress(name));
}

#ifdef STIPPLE_HAVE_OSMESA
void* osmesa_proc(const char* name) {
    return reinterpret_cast<void*>(OSMesaGetProcAddress(name));
}
#endif

ContextStatus failed(std::string why) {
    return {ContextError::no_context, std::move(why)};
}

std::string egl_error(const char* what) {
    char buf[96];
    std::snprintf(buf, sizeof(buf), "%s failed (EGL error 0x%04x)", what, eglGetError());
    return buf;
}

// Initialises `display` and makes a GLES 3 context current without any surface
// (EGL_KHR_surfaceless_context); the renderer draws into its own framebuffer object.
ContextStatus make_es3_context(EGLDisplay display, HeadlessContext* out) {
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor)) return failed(egl_error("eglInitialize"));
    const EGLint config_attribs[] = {EGL_SURFACE_TYPE,
                                     EGL_PBUFFER_BIT,
                                     EGL_RENDERABLE_TYPE,
                                     EGL_OPENGL_ES3_BIT,
                                     EGL_RED_SIZE,
                                     8,
                                     EGL_GREEN_SIZE,
                                     8,
                                     EGL_BLUE_SIZE,
                                     8,
                                     EGL_DEPTH_SIZE,
                                     24,
                                     EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    if (!eglChooseConfig(display, config_attribs, &config, 1, &count) || count == 0) {
        const ContextStatus st = failed("no EGL config with GLES 3 and pbuffer support");
        eglTerminate(display);
        return st;
    }
    if (!eglBindAPI(EGL_OPENGL_ES_API)) {
        const ContextStatus st = failed(egl_error("eglBindAPI(GLES)"));
        eglTerminate(display);
        return st;
    }
    const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_NONE};
    EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attribs);
    if (context == EGL_NO_CONTEXT) {
        const ContextStatus st = failed(egl_error("eglCreateContext(GLES 3)"));
        eglTerminate(display);
        return st;
    }
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
        const ContextStatus st = failed(egl_error("eglMakeCurrent(surfaceless)"));
        eglDestroyContext(display, context);
        eglTerminate(display);
        return st;
    }
    out->egl_display = display;
    out->egl_context = context;
    return {};
}

ContextStatus try_egl_surfaceless(HeadlessContext* out) {
    EGLDisplay display =
        eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display == EGL_NO_DISPLAY) return failed("EGL surfaceless platform unavailable");
    return make_es3_context(display, out);
}

ContextStatus try_egl_device(HeadlessContext* out) {
    auto query_devices =
        reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    if (!query_devices) return failed("EGL_EXT_device_enumeration unavailable");
    EGLDeviceEXT devices[8];
    EGLint count = 0;
    if (!query_devices(8, devices, &count) || count == 0) return failed("no EGL devices");
    ContextStatus st = failed("no EGL device gave a GLES 3 context");
    for (EGLint i = 0; i < count; ++i) {
        EGLDisplay display = eglGetPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        if (display == EGL_NO_DISPLAY) continue;
        st = make_es3_context(display, out);
        if (st.ok()) return st;
    }
    return st;
}

ContextStatus try_osmesa(const HeadlessConfig& config, HeadlessContext* out) {
#ifdef STIPPLE_HAVE_OSMESA
    OSMesaContext context = OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, nullptr);
    if (!context) return failed("OSMesaCreateContextExt failed");
    size_t bytes = size_t(config.width) * size_t(config.height) * 4;
    out->osmesa_buffer = static_cast<unsigned char*>(std::malloc(bytes));
    if (!out->osmesa_buffer || !OSMesaMakeCurrent(context, out->osmesa_buffer, GL_UNSIGNED_BYTE,
                                                  config.width, config.height)) {
        const ContextStatus st = failed("OSMesaMakeCurrent failed");
        OSMesaDestroyContext(context);
        std::free(out->osmesa_buffer);
        out->osmesa_buffer = nullptr;
        return st;
    }
    out->osmesa_context = context;
    return {};
#else
    (void)config;
    (void)out;
    return failed("built without OSMesa");
#endif
}

}  // namespace

ContextStatus create_headless_context(const HeadlessConfig& config, HeadlessContext* out) {
    *out = HeadlessContext();
    if (!config.allow_egl && !config.allow_osmesa)
        return {ContextError::no_backend_allowed,
                "no headless backend allowed (EGL and OSMesa off)"};
    const RasterThreads raster(config.raster_threads);
    std::string tried;  // why each backend failed
    if (config.allow_egl) {
        ContextStatus st = try_egl_surfaceless(out);
        if (st.ok()) {
            out->backend = Backend::egl_surfaceless;
        } else {
            tried += "EGL surfaceless: " + st.message + "; ";
            st = try_egl_device(out);
            if (st.ok())
                out->backend = Backend::egl_device;
            else
                tried += "EGL device: " + st.message + "; ";
        }
    }
    if (out->backend == Backend::none && config.allow_osmesa) {
        const ContextStatus st = try_osmesa(config, out);
        if (st.ok())
            out->backend = Backend::osmesa;
        else
            tried += "OSMesa: " + st.message + "; ";
    }
    if (out->backend == Backend::none)
        return {ContextError::no_context, "no headless OpenGL context could be created (" +
                                              tried.substr(0, tried.size() - 2) + ")"};
    auto get_string = reinterpret_cast<PFNGLGETSTRINGPROC>(proc_loader(*out)("glGetString"));
    const char* renderer =
        get_string ? reinterpret_cast<const char*>(get_string(GL_RENDERER)) : nullptr;
    const char* version =
        get_string ? reinterpret_cast<const char*>(get_string(GL_VERSION)) : nullptr;
    out->renderer = renderer ? renderer : "?";
    out->version = version ? version : "?";
    return {};
}

ProcLoader proc_loader(const HeadlessContext& context) {
#ifdef STIPPLE_HAVE_OSMESA
    if (context.backend == Backend::osmesa) return osmesa_proc;
#endif
    (void)context;
    return egl_proc;
}

void destroy_headless_context(HeadlessContext* context) {
    if (context->egl_display) {
        EGLDisplay display = context->egl_display;
        eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(display, context->egl_context);
        eglTerminate(display);
    }
#ifdef STIPPLE_HAVE_OSMESA
    if (context->osmesa_context)
        OSMesaDestroyContext(static_cast<OSMesaContext>(context->osmesa_context));
#endif
    std::free(context->osmesa_buffer);
    *context = HeadlessContext();
}

const char* backend_name(Backend backend) {
    switch (backend) {
        case Backend::none:
            return "none";
        case Backend::egl_surfaceless:
            return "egl-surfaceless";
        case Backend::egl_device:
            return "egl-device";
        case Backend::osmesa:
            return "osmesa";
    }
    return "?";
}

}  // namespace stipple::platform
