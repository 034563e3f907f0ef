// Headless OpenGL contexts for offscreen rendering and CI frame checks: EGL on Mesa
// (surfaceless platform, then the device platform), with OSMesa as the fallback for stacks
// whose EGL cannot give a GLES 3 context. The only module that includes EGL/OSMesa headers.
#pragma once
#include <string>

namespace stipple::platform {

enum class Backend { none, egl_surfaceless, egl_device, osmesa };

struct HeadlessConfig {
    int width = 640;            // OSMesa needs a buffer; EGL renders to the caller's FBO
    int height = 480;
    bool allow_egl = true;
    bool allow_osmesa = true;
};

struct HeadlessContext {
    Backend backend = Backend::none;
    void* egl_display = nullptr;
    void* egl_context = nullptr;
    void* osmesa_context = nullptr;
    unsigned char* osmesa_buffer = nullptr;
    std::string renderer;       // GL_RENDERER of the context
    std::string version;        // GL_VERSION
};

// Creates a context and makes it current on this thread. On failure returns false and
// explains every backend that was tried.
bool create_headless_context(const HeadlessConfig& config, HeadlessContext* out,
                             std::string* error);

// The context's get-proc-address, for stipple::load_gl_api.
using ProcLoader = void* (*)(const char* name);
ProcLoader proc_loader(const HeadlessContext& context);

void destroy_headless_context(HeadlessContext* context);

const char* backend_name(Backend backend);

}  // namespace stipple::platform
