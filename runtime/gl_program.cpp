#include "runtime/gl_program.h"

namespace stipple {
namespace {

GLuint compile(const GlApi& gl, GLenum type, const char* source, const char* what, Status* error) {
    GLuint s = gl.CreateShader(type);
    gl.ShaderSource(s, 1, &source, nullptr);
    gl.CompileShader(s);
    GLint ok = 0;
    gl.GetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[512] = {};
        gl.GetShaderInfoLog(s, sizeof(log), nullptr, log);
        *error = make_status(StatusCode::gl_error, "%s shader compile failed: %s", what, log);
        gl.DeleteShader(s);
        return 0;
    }
    return s;
}

}  // namespace

GLuint link_gl_program(const GlApi& gl, const char* vertex_source, const char* fragment_source,
                       const char* what, Status* error) {
    GLuint v = compile(gl, GL_VERTEX_SHADER, vertex_source, what, error);
    GLuint f = v ? compile(gl, GL_FRAGMENT_SHADER, fragment_source, what, error) : 0;
    if (!f) {
        if (v) gl.DeleteShader(v);
        return 0;
    }
    GLuint p = gl.CreateProgram();
    gl.AttachShader(p, v);
    gl.AttachShader(p, f);
    gl.LinkProgram(p);
    gl.DeleteShader(v);
    gl.DeleteShader(f);
    GLint ok = 0;
    gl.GetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[512] = {};
        gl.GetProgramInfoLog(p, sizeof(log), nullptr, log);
        *error = make_status(StatusCode::gl_error, "%s program link failed: %s", what, log);
        gl.DeleteProgram(p);
        return 0;
    }
    return p;
}

void gl_uniform_locations(const GlApi& gl, GLuint program,
                          std::initializer_list<GlUniform> uniforms) {
    for (const GlUniform& u : uniforms) *u.location = gl.GetUniformLocation(program, u.name);
}

}  // namespace stipple
