#include "runtime/particle_renderer.h"

#include <cstddef>
#include <memory>

#include "runtime/gl_program.h"

namespace stipple {

namespace {

const char* kStrokeVs = R"(#version 300 es
layout(location = 0) in vec4 a_centre;  // x, y (pixels, top-left origin), depth, angle
layout(location = 1) in vec4 a_shape;   // length, width (pixels), brush, alpha
layout(location = 2) in vec4 a_colour;
layout(location = 3) in vec4 a_fill;
uniform vec4 u_viewport;  // width, height in pixels
uniform highp sampler2D u_depth;
uniform int u_test_depth;
out vec2 v_uv;
out float v_alpha;
flat out vec3 v_colour;
flat out vec3 v_fill;
void main() {
    vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1)) * 2.0 - 1.0;
    v_uv = vec2((a_shape.z + 0.5 + 0.5 * corner.x * (1.0 - 1.0 / 64.0)) / 5.0,
                0.5 + 0.5 * corner.y);
    v_alpha = a_shape.w;
    v_colour = a_colour.rgb;
    v_fill = a_fill.rgb;
    bool hidden = a_centre.z > 1.0;
    if (u_test_depth == 1 && !hidden) {
        ivec2 size = textureSize(u_depth, 0);
        ivec2 pixel = clamp(ivec2(a_centre.x, u_viewport.y - a_centre.y), ivec2(0), size - 1);
        float mesh = texelFetch(u_depth, pixel, 0).r;
        hidden = mesh < 1.0 && a_centre.z > mesh + 1e-5;
    }
    if (hidden) {
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // outside the clip volume
        return;
    }
    float c = cos(a_centre.w), s = sin(a_centre.w);
    vec2 along = vec2(c, s) * (0.5 * a_shape.x), across = vec2(-s, c) * (0.5 * a_shape.y);
    vec2 pixel = a_centre.xy + corner.x * along + corner.y * across;
    gl_Position = vec4(pixel.x / u_viewport.x * 2.0 - 1.0, 1.0 - pixel.y / u_viewport.y * 2.0,
                       0.0, 1.0);
}
)";

const char* kStrokeFs = R"(#version 300 es
precision mediump float;
in vec2 v_uv;
in float v_alpha;
flat in vec3 v_colour;
flat in vec3 v_fill;
uniform sampler2D u_atlas;
layout(location = 0) out vec4 o_color;
void main() {
    vec2 texel = texture(u_atlas, v_uv).rg;  // coverage, ink
    float a = texel.r * v_alpha;
    if (a <= 0.0) discard;
    o_color = vec4(mix(v_fill, v_colour, texel.g), a);
}
)";

void instance_attribute(const GlApi& gl, GLuint location, GLint components, GLenum type,
                        GLboolean normalised, size_t offset) {
    gl.EnableVertexAttribArray(location);
    gl.VertexAttribPointer(location, components, type, normalised, sizeof(StrokeInstance),
                           reinterpret_cast<const void*>(offset));
    gl.VertexAttribDivisor(location, 1);
}

GLuint make_atlas(const GlApi& gl) {
    std::unique_ptr<uint8_t[]> texels(new (std::nothrow) uint8_t[brush_atlas_bytes()]);
    if (!texels) return 0;
    make_brush_atlas(texels.get());
    GLuint t = 0;
    gl.GenTextures(1, &t);
    gl.BindTexture(GL_TEXTURE_2D, t);
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RG8, kBrushCount * kBrushTile, kBrushTile, 0, GL_RG,
                  GL_UNSIGNED_BYTE, texels.get());
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl.BindTexture(GL_TEXTURE_2D, 0);
    return t;
}

}  // namespace

Status particle_renderer_init(ParticleRenderer* r, const GlApi& gl, uint32_t capacity) {
    *r = ParticleRenderer();
    r->gl = gl;
    Status st;
    r->program = link_gl_program(gl, kStrokeVs, kStrokeFs, "particle stroke", &st);
    if (!r->program) return st;
    r->u_viewport = gl.GetUniformLocation(r->program, "u_viewport");
    r->u_depth = gl.GetUniformLocation(r->program, "u_depth");
    r->u_atlas = gl.GetUniformLocation(r->program, "u_atlas");
    r->u_test_depth = gl.GetUniformLocation(r->program, "u_test_depth");
    r->atlas = make_atlas(gl);
    if (!r->atlas) {
        particle_renderer_destroy(r);
        return make_status(StatusCode::out_of_memory, "out of memory for the brush atlas");
    }
    gl.GenVertexArrays(1, &r->vao);
    gl.BindVertexArray(r->vao);
    gl.GenBuffers(1, &r->vbo);
    gl.BindBuffer(GL_ARRAY_BUFFER, r->vbo);
    gl.BufferData(GL_ARRAY_BUFFER, GLsizeiptr(size_t(capacity) * sizeof(StrokeInstance)), nullptr,
                  GL_DYNAMIC_DRAW);
    instance_attribute(gl, 0, 4, GL_FLOAT, GL_FALSE, offsetof(StrokeInstance, x));
    instance_attribute(gl, 1, 4, GL_FLOAT, GL_FALSE, offsetof(StrokeInstance, length));
    instance_attribute(gl, 2, 4, GL_UNSIGNED_BYTE, GL_TRUE, offsetof(StrokeInstance, colour));
    instance_attribute(gl, 3, 4, GL_UNSIGNED_BYTE, GL_TRUE, offsetof(StrokeInstance, fill));
    gl.BindVertexArray(0);
    gl.BindBuffer(GL_ARRAY_BUFFER, 0);
    r->capacity = capacity;
    if (gl.GetError() != GL_NO_ERROR) {
        particle_renderer_destroy(r);
        return make_status(StatusCode::gl_error, "particle stroke buffers: a GL error");
    }
    return {};
}

void particle_renderer_draw(ParticleRenderer* r, GLuint framebuffer, GLuint depth_texture,
                            int width, int height, const StrokeInstance* strokes, uint32_t count,
                            int x0, int y0) {
    if (count > r->capacity) count = r->capacity;
    if (count == 0) return;
    const GlApi& gl = r->gl;
    gl.BindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    gl.Viewport(x0, y0, width, height);
    gl.UseProgram(r->program);
    gl.Uniform4f(r->u_viewport, float(width), float(height), 0.0f, 0.0f);
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D, depth_texture);
    gl.Uniform1i(r->u_depth, 0);
    gl.Uniform1i(r->u_test_depth, depth_texture ? 1 : 0);
    gl.ActiveTexture(GL_TEXTURE1);
    gl.BindTexture(GL_TEXTURE_2D, r->atlas);
    gl.Uniform1i(r->u_atlas, 1);
    gl.Disable(GL_DEPTH_TEST);
    gl.Enable(GL_BLEND);
    gl.BlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    gl.BindVertexArray(r->vao);
    gl.BindBuffer(GL_ARRAY_BUFFER, r->vbo);
    gl.BufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(size_t(count) * sizeof(StrokeInstance)),
                     strokes);
    gl.DrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, GLsizei(count));
    gl.BindVertexArray(0);
    gl.BindBuffer(GL_ARRAY_BUFFER, 0);
    gl.Disable(GL_BLEND);
    gl.BindTexture(GL_TEXTURE_2D, 0);
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D, 0);
}

void particle_renderer_destroy(ParticleRenderer* r) {
    const GlApi& gl = r->gl;
    if (r->vbo) gl.DeleteBuffers(1, &r->vbo);
    if (r->vao) gl.DeleteVertexArrays(1, &r->vao);
    if (r->atlas) gl.DeleteTextures(1, &r->atlas);
    if (r->program) gl.DeleteProgram(r->program);
    *r = ParticleRenderer();
}

}  // namespace stipple
