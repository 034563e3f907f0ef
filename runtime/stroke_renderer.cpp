#include "runtime/stroke_renderer.h"

#include <cstddef>

#include "runtime/gl_program.h"

namespace stipple {

namespace {

// Eye-space StrokeVertex attributes: position, normal, rgba, (reflectance, shade).
const char* kStrokeVs = R"(#version 300 es
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec4 a_colour;
layout(location = 3) in vec2 a_reflectance_shade;
uniform mat4 u_projection;
out vec3 v_position;
out vec3 v_normal;
out vec4 v_colour;
out vec2 v_reflectance_shade;
void main() {
    v_position = a_position;
    v_normal = a_normal;
    v_colour = a_colour;
    v_reflectance_shade = a_reflectance_shade;
    gl_Position = u_projection * vec4(a_position, 1.0);
}
)";

// Lambert diffuse (times the global shading factor) plus white Blinn-Phong specular weighted
// by the reflectance. Normals face the viewer (GI'98 draws the viewer's side only): one-sided.
const char* kStrokeFs = R"(#version 300 es
precision highp float;
in vec3 v_position;
in vec3 v_normal;
in vec4 v_colour;
in vec2 v_reflectance_shade;
uniform vec4 u_light;
uniform float u_ambient;
uniform float u_diffuse;
uniform float u_shininess;
layout(location = 0) out vec4 o_color;
void main() {
    float len = length(v_normal);
    vec3 n = len > 0.0 ? v_normal / len : vec3(0.0, 0.0, 1.0);
    vec3 l = u_light.xyz;
    float plen = length(v_position);
    vec3 v = plen > 0.0 ? -v_position / plen : vec3(0.0, 0.0, 1.0);
    vec3 h = normalize(l + v + vec3(0.0, 0.0, 1e-6));
    float lambert = max(dot(n, l), 0.0);
    float spec = lambert > 0.0 ? pow(max(dot(n, h), 0.0), u_shininess) : 0.0;
    vec3 rgb = v_colour.rgb * (u_ambient + u_diffuse * v_reflectance_shade.y * lambert) +
               vec3(v_reflectance_shade.x * spec);
    o_color = vec4(rgb, v_colour.a);
}
)";

void attribute(const GlApi& gl, GLuint location, GLint components, size_t offset_floats) {
    gl.EnableVertexAttribArray(location);
    gl.VertexAttribPointer(location, components, GL_FLOAT, GL_FALSE, GLsizei(sizeof(StrokeVertex)),
                           reinterpret_cast<const void*>(offset_floats * sizeof(float)));
}

// The vertex array with its two buffers, each given its whole capacity once.
void create_buffers(StrokeRenderer* r) {
    const GlApi& gl = r->gl;
    gl.GenVertexArrays(1, &r->vao);
    gl.BindVertexArray(r->vao);
    gl.GenBuffers(1, &r->vbo);
    gl.BindBuffer(GL_ARRAY_BUFFER, r->vbo);
    gl.BufferData(GL_ARRAY_BUFFER,
                  GLsizeiptr(size_t(r->config.max_vertices) * sizeof(StrokeVertex)), nullptr,
                  GL_DYNAMIC_DRAW);
    attribute(gl, 0, 3, offsetof(StrokeVertex, position) / sizeof(float));
    attribute(gl, 1, 3, offsetof(StrokeVertex, normal) / sizeof(float));
    attribute(gl, 2, 4, offsetof(StrokeVertex, colour) / sizeof(float));
    attribute(gl, 3, 2, offsetof(StrokeVertex, reflectance) / sizeof(float));
    gl.GenBuffers(1, &r->ibo);
    gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, r->ibo);  // recorded in the vertex array
    gl.BufferData(GL_ELEMENT_ARRAY_BUFFER,
                  GLsizeiptr(size_t(r->config.max_indices) * sizeof(uint32_t)), nullptr,
                  GL_DYNAMIC_DRAW);
    gl.BindVertexArray(0);
    gl.BindBuffer(GL_ARRAY_BUFFER, 0);
}

void record_errors(StrokeRenderer* r) {
    if (!r->config.check_errors) return;
    for (int i = 0; i < 8; ++i) {
        const GLenum e = r->gl.GetError();
        if (e == GL_NO_ERROR) return;
        if (r->gl_error_count == 0) r->first_gl_error = e;
        ++r->gl_error_count;
    }
}

}  // namespace

Status stroke_renderer_init(StrokeRenderer* r, const GlApi& gl,
                            const StrokeRendererConfig& config) {
    *r = StrokeRenderer();
    r->gl = gl;
    r->config = config;
    Status st;
    r->program = link_gl_program(gl, kStrokeVs, kStrokeFs, "stroke", &st);
    if (!r->program) return st;
    r->u_projection = gl.GetUniformLocation(r->program, "u_projection");
    r->u_light = gl.GetUniformLocation(r->program, "u_light");
    r->u_ambient = gl.GetUniformLocation(r->program, "u_ambient");
    r->u_diffuse = gl.GetUniformLocation(r->program, "u_diffuse");
    r->u_shininess = gl.GetUniformLocation(r->program, "u_shininess");
    while (gl.GetError() != GL_NO_ERROR) {
    }
    create_buffers(r);
    const GLenum e = gl.GetError();
    if (e != GL_NO_ERROR) {
        stroke_renderer_destroy(r);
        return make_status(StatusCode::gl_error, "stroke buffers (%u vertices, %u indices): 0x%x",
                           config.max_vertices, config.max_indices, e);
    }
    return {};
}

void stroke_renderer_draw(StrokeRenderer* r, const glm::mat4& projection,
                          const StrokeLighting& lighting, const StrokeVertex* vertices,
                          uint32_t vertex_count, const uint32_t* indices, uint32_t index_count) {
    const GlApi& gl = r->gl;
    if (vertex_count > r->config.max_vertices) vertex_count = r->config.max_vertices;
    if (index_count > r->config.max_indices) index_count = r->config.max_indices;
    index_count -= index_count % 3;
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_LEQUAL);
    gl.DepthMask(GL_TRUE);
    gl.Enable(GL_BLEND);
    gl.BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    gl.Disable(GL_CULL_FACE);
    if (vertex_count == 0 || index_count == 0 || !vertices || !indices) {
        record_errors(r);
        return;
    }
    gl.UseProgram(r->program);
    gl.UniformMatrix4fv(r->u_projection, 1, GL_FALSE, &projection[0][0]);
    const glm::vec3 l = glm::normalize(lighting.light_eye);
    gl.Uniform4f(r->u_light, l.x, l.y, l.z, 0.0f);
    gl.Uniform1f(r->u_ambient, lighting.ambient);
    gl.Uniform1f(r->u_diffuse, lighting.diffuse);
    gl.Uniform1f(r->u_shininess, lighting.specular_exponent);
    gl.BindVertexArray(r->vao);
    gl.BindBuffer(GL_ARRAY_BUFFER, r->vbo);
    gl.BufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(size_t(vertex_count) * sizeof(StrokeVertex)),
                     vertices);
    gl.BufferSubData(GL_ELEMENT_ARRAY_BUFFER, 0, GLsizeiptr(size_t(index_count) * sizeof(uint32_t)),
                     indices);
    gl.DrawElements(GL_TRIANGLES, GLsizei(index_count), GL_UNSIGNED_INT, nullptr);
    gl.BindVertexArray(0);
    gl.BindBuffer(GL_ARRAY_BUFFER, 0);
    record_errors(r);
}

void stroke_renderer_destroy(StrokeRenderer* r) {
    const GlApi& gl = r->gl;
    if (r->vao) gl.DeleteVertexArrays(1, &r->vao);
    if (r->vbo) gl.DeleteBuffers(1, &r->vbo);
    if (r->ibo) gl.DeleteBuffers(1, &r->ibo);
    if (r->program) gl.DeleteProgram(r->program);
    r->vao = r->vbo = r->ibo = r->program = 0;
}

}  // namespace stipple
