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

// The most rasterizer threads HeadlessConfig::raster_threads asks for (llvmpipe's own limit).
constexpr int kMaxRasterThreads = 32;

struct HeadlessConfig {
    int width = 640;  // OSMesa needs a buffer; EGL renders to the caller's FBO
    int height = 480;
    bool allow_egl = true;
    bool allow_osmesa = true;
    // Rasterizer threads of Mesa's software driver (llvmpipe's LP_NUM_THREADS, read as the
    // context's screen is made): -1 leaves the driver's default, a thread per core; 0 to
    // kMaxRasterThreads (clamped) sets it. 0 rasterizes on the calling thread, inside glFlush and
    // glFinish: on a 2-core machine the other core is then free for the point stages' worker
    // (FrameConfig::threads 2), which llvmpipe's own threads otherwise contend with
    // (docs/performance.md, seventeenth round). Mesa reads it when the display is initialised:
    // it holds for the process's first headless context (or the first after every earlier one
    // was destroyed); later ones share that display and its setting. Applied only where the
    // environment does not set LP_NUM_THREADS itself, for this context's creation alone (the
    // environment is restored after it: call from one thread, as for any setenv). Hardware
    // drivers ignore it.
    int raster_threads = -1;
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
