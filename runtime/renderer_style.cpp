// The looks' mesh pass (runtime/style.h, docs/styles.md): toon bands of the lights filled in
// the part or fill colour (thesis §7.2, the crocodile) and the transparent style's fill of the
// opaque parts only (§7.4). Classic and colour (§8.6: dots over the paper) use
// renderer_draw_mesh, untouched.
#include <cstring>

#include "runtime/gl_program.h"
#include "runtime/renderer.h"

namespace stipple {

namespace {

const char* kStyleVs = R"(#version 300 es
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec4 a_colour;
uniform mat4 u_view_projection;
uniform float u_depth_bias;
out vec3 v_normal;
out vec4 v_colour;
void main() {
    gl_Position = u_view_projection * vec4(a_position, 1.0);
    gl_Position.z += u_depth_bias * gl_Position.w;
    v_normal = a_normal;
    v_colour = a_colour;
}
)";

// u_fill: rgb, and a = 1 to take the vertex (part) colour instead; u_toon: the band count (0:
// a flat fill); u_cut 1: fragments of transparent parts (vertex alpha 0) are discarded, so they
// write neither colour nor depth. Without a vertex colour buffer a_colour reads (0, 0, 0, 1).
#define STIPPLE_STYLE_FS_BODY                                                                 \
    "precision highp float;\n"                                                                \
    "in vec3 v_normal;\n"                                                                     \
    "in vec4 v_colour;\n"                                                                     \
    "uniform vec4 u_fill;\n"                                                                  \
    "uniform int u_toon;\n"                                                                   \
    "uniform float u_shade;\n"                                                                \
    "uniform vec4 u_lights[4];\n"                                                             \
    "uniform int u_light_count;\n"                                                            \
    "uniform float u_ambient;\n"                                                              \
    "uniform int u_cut;\n"                                                                    \
    "layout(location = 0) out vec4 o_color;\n"                                                \
    "#if DEPTH_COPY\n"                                                                        \
    "layout(location = 1) out vec4 o_depth;\n"                                                \
    "#endif\n"                                                                                \
    "void main() {\n"                                                                         \
    "    if (u_cut == 1 && v_colour.a < 0.5) discard;\n"                                      \
    "    vec3 base = u_fill.a > 0.5 ? v_colour.rgb : u_fill.rgb;\n"                           \
    "    float level = 1.0;\n"                                                                \
    "    if (u_toon > 1) {\n"                                                                 \
    "        vec3 n = normalize(v_normal);\n"                                                 \
    "        if (!gl_FrontFacing) n = -n;\n"                                                  \
    "        float lit = u_ambient;\n"                                                        \
    "        for (int k = 0; k < 4; ++k)\n"                                                   \
    "            if (k < u_light_count) lit += u_lights[k].w * max(dot(n, u_lights[k].xyz), " \
    "0.0);\n"                                                                                 \
    "        float bands = float(u_toon);\n"                                                  \
    "        float band = min(floor(min(lit, 1.0) * bands), bands - 1.0);\n"                  \
    "        level = mix(u_shade, 1.0, band / (bands - 1.0));\n"                              \
    "    }\n"                                                                                 \
    "    o_color = vec4(base * level, 1.0);\n"                                                \
    "#if DEPTH_COPY\n"                                                                        \
    "    o_depth = vec4(gl_FragCoord.z);\n"                                                   \
    "#endif\n"                                                                                \
    "}\n"

const char* kStyleFs = "#version 300 es\n#define DEPTH_COPY 1\n" STIPPLE_STYLE_FS_BODY;
const char* kStyleFsNoCopy = "#version 300 es\n#define DEPTH_COPY 0\n" STIPPLE_STYLE_FS_BODY;

// A vertex buffer of `bytes` bound to `location` of the bound vertex array.
GLuint attribute_buffer(const GlApi& gl, GLuint location, GLint components, GLenum type,
                        GLboolean normalised, size_t bytes, const void* data, GLenum usage) {
    GLuint b = 0;
    gl.GenBuffers(1, &b);
    gl.BindBuffer(GL_ARRAY_BUFFER, b);
    gl.BufferData(GL_ARRAY_BUFFER, GLsizeiptr(bytes), data, usage);
    gl.EnableVertexAttribArray(location);
    gl.VertexAttribPointer(location, components, type, normalised, 0, nullptr);
    return b;
}

// Uniforms of the styled mesh pass for r->look.
void set_style_uniforms(Renderer* r, const glm::mat4& view_projection, bool toon) {
    const GlApi& gl = r->gl;
    const RendererLook& look = r->look;
    const RendererConfig& c = r->config;
    gl.UseProgram(r->style_program);
    gl.UniformMatrix4fv(r->style_vp, 1, GL_FALSE, &view_projection[0][0]);
    gl.Uniform1f(r->style_bias, c.depth_bias);
    // toon fills with the part colours when the asset has them, else the fill colour; the
    // other styles with the paper.
    const bool parts = toon && c.part_colours && r->mesh_colour_vbo;
    const float* rgb = toon ? look.fill : c.paper;
    gl.Uniform4f(r->style_fill, rgb[0], rgb[1], rgb[2], parts ? 1.0f : 0.0f);
    gl.Uniform1i(r->style_toon, toon ? look.toon_bands : 0);
    gl.Uniform1f(r->style_shade, look.toon_shade);
    gl.Uniform4fv(r->style_lights, kMaxLights, &look.lights[0][0]);
    gl.Uniform1i(r->style_light_count, look.light_count);
    gl.Uniform1f(r->style_ambient, look.ambient);
    gl.Uniform1i(r->style_cut, look.style == Style::transparent ? 1 : 0);
}

}  // namespace

Status renderer_init_looks(Renderer* r) {
    const GlApi& gl = r->gl;
    const RendererConfig& c = r->config;
    Status st;
    r->style_program =
        link_gl_program(gl, kStyleVs, c.depth_copy ? kStyleFs : kStyleFsNoCopy, "style mesh", &st);
    if (!r->style_program) return st;
    const GLuint p = r->style_program;
    gl_uniform_locations(gl, p,
                         {{&r->style_vp, "u_view_projection"},
                          {&r->style_bias, "u_depth_bias"},
                          {&r->style_fill, "u_fill"},
                          {&r->style_toon, "u_toon"},
                          {&r->style_shade, "u_shade"},
                          {&r->style_lights, "u_lights"},
                          {&r->style_light_count, "u_light_count"},
                          {&r->style_ambient, "u_ambient"},
                          {&r->style_cut, "u_cut"}});
    gl.BindVertexArray(r->mesh_vao);
    r->mesh_normal_vbo = attribute_buffer(gl, 1, 3, GL_FLOAT, GL_FALSE, size_t(c.vertex_count) * 12,
                                          nullptr, GL_DYNAMIC_DRAW);
    if (c.vertex_colours)
        r->mesh_colour_vbo =
            attribute_buffer(gl, 2, 4, GL_UNSIGNED_BYTE, GL_TRUE, size_t(c.vertex_count) * 4,
                             c.vertex_colours, GL_STATIC_DRAW);
    if (c.dot_colours) {
        gl.BindVertexArray(r->point_vao);
        r->point_colour_vbo = attribute_buffer(gl, 2, 4, GL_UNSIGNED_BYTE, GL_TRUE,
                                               size_t(c.max_points) * 4, nullptr, GL_DYNAMIC_DRAW);
    }
    gl.BindVertexArray(0);
    return {};
}

void renderer_set_look(Renderer* r, const FrameConfig& c, const glm::vec3* light_directions,
                       bool transparent_parts) {
    RendererLook& look = r->look;
    look.style = c.style;
    look.toon_bands = c.toon_bands;
    look.toon_shade = c.toon_shade;
    look.toon_ink = c.toon_ink;
    std::memcpy(look.fill, c.fill, sizeof(look.fill));
    look.transparent_parts = transparent_parts;
    look.light_count = c.light_count;
    for (int k = 0; k < kMaxLights; ++k) {
        const bool on = k < c.light_count;
        for (int i = 0; i < 3; ++i) look.lights[k][i] = on ? light_directions[k][i] : 0.0f;
        look.lights[k][3] = on ? c.lights[k].intensity : 0.0f;
    }
    look.ambient = c.ambient;
}

void renderer_destroy_looks(Renderer* r) {
    const GlApi& gl = r->gl;
    GLuint buffers[3] = {r->mesh_normal_vbo, r->mesh_colour_vbo, r->point_colour_vbo};
    gl.DeleteBuffers(3, buffers);
    if (r->style_program) gl.DeleteProgram(r->style_program);
    r->style_program = r->mesh_normal_vbo = r->mesh_colour_vbo = r->point_colour_vbo = 0;
}

void renderer_draw_fill(Renderer* r, const glm::mat4& view_projection, const float* positions,
                        const float* normals, uint32_t vertex_count) {
    const Style style = r->look.style;
    // colour fills with the paper like classic: the same pass (depth only on white paper).
    if (style == Style::classic || style == Style::colour) {
        renderer_draw_mesh(r, view_projection, positions, vertex_count);
        return;
    }
    const GlApi& gl = r->gl;
    renderer_clear_frame(r);
    // Thesis §7.4: with no part marked transparent the whole mesh is; nothing to fill.
    if (style == Style::transparent && !(r->look.transparent_parts && r->mesh_colour_vbo)) {
        renderer_check_errors(r, "depth");
        return;
    }
    const bool toon = style == Style::toon;
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_LESS);
    gl.Disable(GL_BLEND);
    set_style_uniforms(r, view_projection, toon);
    gl.BindVertexArray(r->mesh_vao);
    gl.BindBuffer(GL_ARRAY_BUFFER, r->mesh_vbo);
    gl.BufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(size_t(vertex_count) * 12), positions);
    if (toon && normals) {
        gl.BindBuffer(GL_ARRAY_BUFFER, r->mesh_normal_vbo);
        gl.BufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(size_t(vertex_count) * 12), normals);
    }
    renderer_draw_triangles(r, view_projection);
    gl.BindVertexArray(0);
    renderer_check_errors(r, "depth");
}

}  // namespace stipple
