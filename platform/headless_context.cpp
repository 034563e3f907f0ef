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

namespace stipple::platform {

namespace {

void* egl_proc(const char* name) { return reinterpret_cast<void*>(eglGetProcAddress(name)); }

#ifdef STIPPLE_HAVE_OSMESA
void* osmesa_proc(const char* name) {
    return reinterpret_cast<void*>(OSMesaGetProcAddress(name));
}
#endif

std::string egl_error(const char* what) {
    char buf[96];
    std::snprintf(buf, sizeof(buf), "%s failed (EGL error 0x%04x)", what, eglGetError());
    return buf;
}

// Initialises `display` and makes a GLES 3 context current without any surface
// (EGL_KHR_surfaceless_context); the renderer draws into its own framebuffer object.
bool make_es3_context(EGLDisplay display, HeadlessContext* out, std::string* error) {
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor)) {
        *error = egl_error("eglInitialize");
        return false;
    }
    const EGLint config_attribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE,
                                     EGL_OPENGL_ES3_BIT, EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8,
                                     EGL_BLUE_SIZE, 8, EGL_DEPTH_SIZE, 24, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    if (!eglChooseConfig(display, config_attribs, &config, 1, &count) || count == 0) {
        *error = "no EGL config with GLES 3 and pbuffer support";
        eglTerminate(display);
        return false;
    }
    if (!eglBindAPI(EGL_OPENGL_ES_API)) {
        *error = egl_error("eglBindAPI(GLES)");
        eglTerminate(display);
        return false;
    }
    const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_NONE};
    EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, context_attribs);
    if (context == EGL_NO_CONTEXT) {
        *error = egl_error("eglCreateContext(GLES 3)");
        eglTerminate(display);
        return false;
    }
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
        *error = egl_error("eglMakeCurrent(surfaceless)");
        eglDestroyContext(display, context);
        eglTerminate(display);
        return false;
    }
    out->egl_display = display;
    out->egl_context = context;
    return true;
}

bool try_egl_surfaceless(HeadlessContext* out, std::string* error) {
    EGLDisplay display =
        eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display == EGL_NO_DISPLAY) {
        *error = "EGL surfaceless platform unavailable";
        return false;
    }
    return make_es3_context(display, out, error);
}

bool try_egl_device(HeadlessContext* out, std::string* error) {
    auto query_devices =
        reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    if (!query_devices) {
        *error = "EGL_EXT_device_enumeration unavailable";
        return false;
    }
    EGLDeviceEXT devices[8];
    EGLint count = 0;
    if (!query_devices(8, devices, &count) || count == 0) {
        *error = "no EGL devices";
        return false;
    }
    for (EGLint i = 0; i < count; ++i) {
        EGLDisplay display = eglGetPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        if (display != EGL_NO_DISPLAY && make_es3_context(display, out, error)) return true;
    }
    if (error->empty()) *error = "no EGL device gave a GLES 3 context";
    return false;
}

bool try_osmesa(const HeadlessConfig& config, HeadlessContext* out, std::string* error) {
#ifdef STIPPLE_HAVE_OSMESA
    OSMesaContext context = OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, nullptr);
    if (!context) {
        *error = "OSMesaCreateContextExt failed";
        return false;
    }
    size_t bytes = size_t(config.width) * size_t(config.height) * 4;
    out->osmesa_buffer = static_cast<unsigned char*>(std::malloc(bytes));
    if (!out->osmesa_buffer ||
        !OSMesaMakeCurrent(context, out->osmesa_buffer, GL_UNSIGNED_BYTE, config.width,
                           config.height)) {
        *error = "OSMesaMakeCurrent failed";
        OSMesaDestroyContext(context);
        std::free(out->osmesa_buffer);
        out->osmesa_buffer = nullptr;
        return false;
    }
    out->osmesa_context = context;
    return true;
#else
    (void)config;
    (void)out;
    *error = "built without OSMesa";
    return false;
#endif
}

}  // namespace

bool create_headless_context(const HeadlessConfig& config, HeadlessContext* out,
                             std::string* error) {
    *out = HeadlessContext();
    std::string tried;
    std::string why;
    if (config.allow_egl) {
        if (try_egl_surfaceless(out, &why)) {
            out->backend = Backend::egl_surfaceless;
        } else {
            tried += "EGL surfaceless: " + why + "; ";
            why.clear();
            if (try_egl_device(out, &why))
                out->backend = Backend::egl_device;
            else
                tried += "EGL device: " + why + "; ";
        }
    }
    if (out->backend == Backend::none && config.allow_osmesa) {
        why.clear();
        if (try_osmesa(config, out, &why))
            out->backend = Backend::osmesa;
        else
            tried += "OSMesa: " + why + "; ";
    }
    if (out->backend == Backend::none) {
        *error = "no headless OpenGL context could be created (" +
                 tried.substr(0, tried.size() - 2) + ")";
        return false;
    }
    auto get_string =
        reinterpret_cast<PFNGLGETSTRINGPROC>(proc_loader(*out)("glGetString"));
    const char* renderer = get_string ? reinterpret_cast<const char*>(get_string(GL_RENDERER)) : nullptr;
    const char* version = get_string ? reinterpret_cast<const char*>(get_string(GL_VERSION)) : nullptr;
    out->renderer = renderer ? renderer : "?";
    out->version = version ? version : "?";
    return true;
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
        case Backend::none: return "none";
        case Backend::egl_surfaceless: return "egl-surfaceless";
        case Backend::egl_device: return "egl-device";
        case Backend::osmesa: return "osmesa";
    }
    return "?";
}

}  // namespace stipple::platform
