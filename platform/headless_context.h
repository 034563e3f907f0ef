// Headless OpenGL contexts for offscreen rendering and CI frame checks: EGL on Mesa
// (surfaceless platform, then the device platform), with OSMesa as the fallback for stacks
// whose EGL cannot give a GLES 3 context. The only module that includes EGL/OSMesa headers.
#pragma once
#include <string>

namespace stipple::platform {

enum class Backend { none, egl_surfaceless, egl_device, osmesa };

// The platform layer's one error type.
enum class ContextError {
    ok = 0,
    no_backend_allowed,  // HeadlessConfig allows neither EGL nor OSMesa
    no_context,          // every allowed backend was tried and none gave a context
};

struct ContextStatus {
    ContextError code = ContextError::ok;
    std::string message;  // one line; for no_context, why each backend failed
    bool ok() const { return code == ContextError::ok; }
};

struct HeadlessConfig {
    int width = 640;  // OSMesa needs a buffer; EGL renders to the caller's FBO
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
    std::string renderer;  // GL_RENDERER of the context
    std::string version;   // GL_VERSION
};

// Creates a context and makes it current on this thread. On failure the message explains
// every backend that was tried.
[[nodiscard]] ContextStatus create_headless_context(const HeadlessConfig& config,
                                                    HeadlessContext* out);

// The context's get-proc-address, for stipple::load_gl_api.
using ProcLoader = void* (*)(const char* name);
ProcLoader proc_loader(const HeadlessContext& context);

void destroy_headless_context(HeadlessContext* context);

const char* backend_name(Backend backend);

}  // namespace stipple::platform
