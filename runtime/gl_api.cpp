#include "runtime/gl_api.h"

#include <cstring>

namespace stipple {

Status load_gl_api(GetProcAddress get_proc, GlApi* gl) {
#define STIPPLE_GL_LOAD(type, name)                          \
    gl->name = reinterpret_cast<type>(get_proc("gl" #name)); \
    if (!gl->name)                                           \
        return make_status(StatusCode::gl_error, "GL entry point gl" #name " unavailable");
    STIPPLE_GL_FUNCTIONS(STIPPLE_GL_LOAD)
#undef STIPPLE_GL_LOAD
    const char* version = reinterpret_cast<const char*>(gl->GetString(GL_VERSION));
    gl->desktop = version && std::strncmp(version, "OpenGL ES", 9) != 0;
    return {};
}

}  // namespace stipple
