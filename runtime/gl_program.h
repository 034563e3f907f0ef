// Compiling and linking a GLSL ES program from a vertex and a fragment shader: the one place
// the renderers (runtime/renderer.cpp, runtime/stroke_renderer.cpp) and tools build programs.
#pragma once
#include <initializer_list>

#include "runtime/gl_api.h"
#include "runtime/status.h"

namespace stipple {

// The linked program, or 0 with *error set (gl_error naming `what` and the driver's log).
// The shaders are deleted either way.
GLuint link_gl_program(const GlApi& gl, const char* vertex_source, const char* fragment_source,
                       const char* what, Status* error);

// A uniform's name and where its location goes (gl_uniform_locations).
struct GlUniform {
    GLint* location;
    const char* name;
};

// Looks up each uniform's location in `program` (-1 where the program has no such uniform).
void gl_uniform_locations(const GlApi& gl, GLuint program,
                          std::initializer_list<GlUniform> uniforms);

}  // namespace stipple
