#include "runtime/renderer.h"

#include <cstdio>
#include <cstring>

#include "runtime/gl_program.h"
#include "runtime/renderer_shaders.h"

namespace stipple {

namespace {

using namespace shaders;

GLuint renderbuffer(const GlApi& gl, GLenum format, int w, int h) {
    GLuint rb = 0;
    gl.GenRenderbuffers(1, &rb);
    gl.BindRenderbuffer(GL_RENDERBUFFER, rb);
    gl.RenderbufferStorage(GL_RENDERBUFFER, format, w, h);
    return rb;
}

GLuint dynamic_buffer(const GlApi& gl, GLuint location, GLint components, size_t bytes) {
    GLuint b = 0;
    gl.GenBuffers(1, &b);
    gl.BindBuffer(GL_ARRAY_BUFFER, b);
    gl.BufferData(GL_ARRAY_BUFFER, GLsizeiptr(bytes), nullptr, GL_DYNAMIC_DRAW);
    gl.EnableVertexAttribArray(location);
    gl.VertexAttribPointer(location, components, GL_FLOAT, GL_FALSE, 0, nullptr);
    return b;
}

// With config.check_errors, reads every pending GL error flag (glGetError returns one per
// call; at most a few are set at once) and records them against `pass`.
void check_pass(Renderer* r, const char* pass) {
    if (!r->config.check_errors) return;
    for (int i = 0; i < 8; ++i) {
        const GLenum e = r->gl.GetError();
        if (e == GL_NO_ERROR) return;
        if (r->gl_errors.count == 0) {
            r->gl_errors.first_pass = pass;
            r->gl_errors.first_error = e;
        }
        ++r->gl_errors.count;
    }
}

// State shared by the passes that lay ink over the mesh pass: colour attachment only,
// depth-tested against the (biased) mesh without writing depth, no blending.
void set_dot_ink(Renderer* r, bool own_colours);

void begin_ink_pass(Renderer* r, GLuint program, GLint vp, GLint ink,
                    const glm::mat4& view_projection) {
    const GlApi& gl = r->gl;
    const GLenum first[1] = {GL_COLOR_ATTACHMENT0};
    gl.DrawBuffers(1, first);
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_LEQUAL);
    gl.DepthMask(GL_FALSE);
    gl.Disable(GL_BLEND);
    gl.UseProgram(program);
    gl.UniformMatrix4fv(vp, 1, GL_FALSE, &view_projection[0][0]);
    gl.Uniform4f(ink, r->config.ink[0], r->config.ink[1], r->config.ink[2], 1.0f);
    // Dots in the look's ink, GPU-path dots included (renderer_draw_points_from).
    if (program == r->point_program) set_dot_ink(r, false);
}

// The dots' colour for r->look (after begin_ink_pass set the classic ink): the style's ink or
// each dot's own colour, and whether dots off the opaque parts are drawn (transparent style).
void set_dot_ink(Renderer* r, bool own_colours) {
    const GlApi& gl = r->gl;
    const RendererLook& look = r->look;
    const float* fill = look.fill;
    if (look.style == Style::colour) {
        float rgb[3] = {fill[0], fill[1], fill[2]};
        colour_dot_rgb(rgb);
        gl.Uniform4f(r->point_ink, rgb[0], rgb[1], rgb[2], 1.0f);
    }
    if (look.style == Style::toon)
        gl.Uniform4f(r->point_ink, fill[0] * look.toon_ink, fill[1] * look.toon_ink,
                     fill[2] * look.toon_ink, 1.0f);
    gl.Uniform1i(r->point_use_colour, own_colours ? 1 : 0);
    gl.Uniform1i(r->point_see_through, look.style == Style::transparent ? 1 : 0);
}

// The offscreen framebuffer (colour, optional depth copy, depth texture) and the ink
// framebuffer that shares its colour.
Status create_framebuffers(Renderer* r) {
    const GlApi& gl = r->gl;
    const int w = r->config.width, h = r->config.height;
    gl.GenFramebuffers(1, &r->fbo);
    gl.BindFramebuffer(GL_FRAMEBUFFER, r->fbo);
    r->color_rb = renderbuffer(gl, GL_RGBA8, w, h);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, r->color_rb);
    if (r->config.depth_copy) {
        r->depth_copy_rb = renderbuffer(gl, GL_R32F, w, h);
        gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_RENDERBUFFER,
                                   r->depth_copy_rb);
    }
    gl.GenTextures(1, &r->depth_tex);
    gl.BindTexture(GL_TEXTURE_2D, r->depth_tex);
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, w, h, 0, GL_DEPTH_COMPONENT,
                  GL_UNSIGNED_INT, nullptr);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    gl.BindTexture(GL_TEXTURE_2D, 0);
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, r->depth_tex, 0);
    GLenum status = gl.CheckFramebufferStatus(GL_FRAMEBUFFER);
    // The dots pass samples the depth texture, so it draws into a second framebuffer that
    // holds only the colour: no attachment is read and written at once.
    gl.GenFramebuffers(1, &r->ink_fbo);
    gl.BindFramebuffer(GL_FRAMEBUFFER, r->ink_fbo);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, r->color_rb);
    const GLenum ink_status = gl.CheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE || ink_status != GL_FRAMEBUFFER_COMPLETE)
        return make_status(StatusCode::gl_error, "framebuffer %dx%d incomplete (status 0x%x, 0x%x)",
                           w, h, status, ink_status);
    return {};
}

// The mesh, dots and lines programs and their uniform locations.
Status create_programs(Renderer* r) {
    const GlApi& gl = r->gl;
    Status st;
    r->mesh_program =
        link_gl_program(gl, kMeshVs, r->config.depth_copy ? kMeshFs : kMeshFsNoCopy, "mesh", &st);
    r->point_program = r->mesh_program ? link_gl_program(gl, kPointVs, kPointFs, "dot", &st) : 0;
    r->line_program = r->point_program ? link_gl_program(gl, kLineVs, kLineFs, "line", &st) : 0;
    if (!r->line_program) return st;
    gl_uniform_locations(gl, r->mesh_program,
                         {{&r->mesh_vp, "u_view_projection"},
                          {&r->mesh_bias, "u_depth_bias"},
                          {&r->mesh_paper, "u_paper"}});
    gl_uniform_locations(gl, r->point_program,
                         {{&r->point_vp, "u_view_projection"},
                          {&r->point_ink, "u_ink"},
                          {&r->point_depth, "u_depth"},
                          {&r->point_use_colour, "u_use_colour"},
                          {&r->point_see_through, "u_see_through"}});
    gl_uniform_locations(gl, r->line_program,
                         {{&r->line_vp, "u_view_projection"}, {&r->line_ink, "u_ink"}});
    return {};
}

// Uploads the triangle list into the bound element buffer, single-sided triangles first and
// then the double-sided ones (each group in its original order), through a fixed block on
// the stack: nothing is allocated. Returns the number of single-sided triangles.
uint32_t upload_indices(const GlApi& gl, const RendererConfig& c) {
    const GLsizeiptr bytes = GLsizeiptr(size_t(c.triangle_count) * 12);
    if (!c.triangle_double_sided) {
        gl.BufferData(GL_ELEMENT_ARRAY_BUFFER, bytes, c.indices, GL_STATIC_DRAW);
        return c.triangle_count;
    }
    gl.BufferData(GL_ELEMENT_ARRAY_BUFFER, bytes, nullptr, GL_STATIC_DRAW);
    constexpr uint32_t kBlock = 1024;  // triangles per upload
    uint32_t block[kBlock * 3];
    uint32_t written = 0, single = 0;
    for (uint8_t sided = 0; sided < 2; ++sided) {  // 0: single-sided, 1: double-sided
        uint32_t n = 0;
        for (uint32_t t = 0; t <= c.triangle_count; ++t) {
            const bool end = t == c.triangle_count;
            if (!end && (c.triangle_double_sided[t] != 0) == (sided != 0)) {
                std::memcpy(block + size_t(n) * 3, c.indices + size_t(t) * 3, 12);
                ++n;
            }
            if (n == kBlock || (end && n > 0)) {
                gl.BufferSubData(GL_ELEMENT_ARRAY_BUFFER, GLintptr(size_t(written) * 12),
                                 GLsizeiptr(size_t(n) * 12), block);
                written += n;
                n = 0;
            }
        }
        if (sided == 0) single = written;
    }
    return single;
}

// Vertex arrays and buffers at their capacities; the triangle list is uploaded once.
void create_buffers(Renderer* r) {
    const GlApi& gl = r->gl;
    const RendererConfig& config = r->config;
    gl.GenVertexArrays(1, &r->mesh_vao);
    gl.BindVertexArray(r->mesh_vao);
    r->mesh_vbo = dynamic_buffer(gl, 0, 3, size_t(config.vertex_count) * 12);
    gl.GenBuffers(1, &r->mesh_ibo);
    gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, r->mesh_ibo);
    r->single_sided_count = upload_indices(gl, config);

    gl.GenVertexArrays(1, &r->point_vao);
    gl.BindVertexArray(r->point_vao);
    r->point_pos_vbo = dynamic_buffer(gl, 0, 3, size_t(config.max_points) * 12);
    r->point_size_vbo = dynamic_buffer(gl, 1, 1, size_t(config.max_points) * 4);

    gl.GenVertexArrays(1, &r->line_vao);
    gl.BindVertexArray(r->line_vao);
    r->line_vbo =
        dynamic_buffer(gl, 0, 3, (size_t(config.max_lines) + size_t(config.max_creases)) * 24);
    gl.BindVertexArray(0);
}

}  // namespace

const char* gl_error_name(GLenum error) {
    switch (error) {
        case GL_NO_ERROR:
            return "GL_NO_ERROR";
        case GL_INVALID_ENUM:
            return "GL_INVALID_ENUM";
        case GL_INVALID_VALUE:
            return "GL_INVALID_VALUE";
        case GL_INVALID_OPERATION:
            return "GL_INVALID_OPERATION";
        case GL_INVALID_FRAMEBUFFER_OPERATION:
            return "GL_INVALID_FRAMEBUFFER_OPERATION";
        case GL_OUT_OF_MEMORY:
            return "GL_OUT_OF_MEMORY";
        default:
            return "GL_UNKNOWN_ERROR";
    }
}

Status renderer_init(Renderer* r, const GlApi& gl, const RendererConfig& config) {
    *r = Renderer();
    r->gl = gl;
    r->config = config;
    Status st = create_framebuffers(r);
    if (st.ok()) st = create_programs(r);
    if (st.ok()) {
        create_buffers(r);
        renderer_init_front(r);
        st = renderer_init_looks(r);
        if (st.ok()) st = renderer_init_occluder(r);
    }
    if (st.ok()) {
        if (gl.desktop) {
            gl.Enable(0x8642);  // GL_PROGRAM_POINT_SIZE: desktop GL ignores gl_PointSize without it
            gl.Enable(0x8861);  // GL_POINT_SPRITE: gl_PointCoord in compatibility profiles
        }
        if (gl.GetError() != GL_NO_ERROR)
            st = make_status(StatusCode::gl_error, "GL error while creating renderer resources");
    }
    if (!st.ok()) renderer_destroy(r);
    return st;
}

void renderer_clear_frame(Renderer* r) {
    const GlApi& gl = r->gl;
    const RendererConfig& c = r->config;
    gl.BindFramebuffer(GL_FRAMEBUFFER, r->fbo);
    const GLenum both[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    gl.DrawBuffers(c.depth_copy ? 2 : 1, both);
    gl.Viewport(0, 0, c.width, c.height);
    const float background[4] = {c.background[0], c.background[1], c.background[2], 1.0f};
    const float far_depth[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    const bool scissored = renderer_scissor_dirty(r);  // runtime/renderer_dirty.cpp
    gl.ClearBufferfv(GL_COLOR, 0, background);
    if (c.depth_copy) gl.ClearBufferfv(GL_COLOR, 1, far_depth);
    gl.DepthMask(GL_TRUE);  // the points pass leaves depth writes off; glClear obeys the mask
    gl.Clear(GL_DEPTH_BUFFER_BIT);
    if (scissored) gl.Disable(GL_SCISSOR_TEST);
}

void renderer_draw_mesh(Renderer* r, const glm::mat4& view_projection, const float* positions,
                        uint32_t vertex_count) {
    const GlApi& gl = r->gl;
    const RendererConfig& c = r->config;
    renderer_clear_frame(r);
    // Paper the colour of the background (the default): the clear already painted the body,
    // so the pass writes depth only (and the depth copy, which needs colour writes).
    const bool depth_only =
        !c.depth_copy && std::memcmp(c.paper, c.background, sizeof(c.paper)) == 0;
    if (depth_only) gl.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);

    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_LESS);
    gl.Disable(GL_BLEND);
    gl.UseProgram(r->mesh_program);
    gl.UniformMatrix4fv(r->mesh_vp, 1, GL_FALSE, &view_projection[0][0]);
    gl.Uniform1f(r->mesh_bias, c.depth_bias);
    gl.Uniform4f(r->mesh_paper, c.paper[0], c.paper[1], c.paper[2], 1.0f);
    gl.BindVertexArray(r->mesh_vao);
    gl.BindBuffer(GL_ARRAY_BUFFER, r->mesh_vbo);
    gl.BufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(size_t(vertex_count) * 12), positions);
    if (!renderer_draw_occluder(r, view_projection)) renderer_draw_triangles(r, view_projection);
    if (depth_only) gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    check_pass(r, "depth");
}

void renderer_draw_triangles(Renderer* r, const glm::mat4& view_projection) {
    const GlApi& gl = r->gl;
    const uint32_t total = r->config.triangle_count, single = r->single_sided_count;
    gl.Disable(GL_CULL_FACE);
    if (single > 0) {
        // The mesh's front faces (counter-clockwise, glTF's winding) stay counter-clockwise on
        // screen under a camera's view-projection (determinant < 0) and turn clockwise under a
        // mirrored one (determinant > 0, e.g. a negative-scale model matrix).
        const float det = glm::determinant(view_projection);
        if (det != 0.0f) {
            gl.FrontFace(det < 0.0f ? GL_CCW : GL_CW);
            gl.CullFace(GL_BACK);
            gl.Enable(GL_CULL_FACE);
        }
        uint32_t front = 0;  // the GPU is handed only the triangles it would not cull
        if (det != 0.0f && renderer_front_triangles(r, view_projection, &front)) {
            gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, r->front_ibo);
            gl.DrawElements(GL_TRIANGLES, GLsizei(front * 3), GL_UNSIGNED_INT, nullptr);
            gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, r->mesh_ibo);  // mesh_vao's own again
        } else {
            gl.DrawElements(GL_TRIANGLES, GLsizei(single * 3), GL_UNSIGNED_INT, nullptr);
        }
        gl.Disable(GL_CULL_FACE);
    }
    if (total > single)
        gl.DrawElements(GL_TRIANGLES, GLsizei((total - single) * 3), GL_UNSIGNED_INT,
                        reinterpret_cast<const void*>(size_t(single) * 12));
}

void renderer_begin_overlay(Renderer* r) {
    const GlApi& gl = r->gl;
    renderer_mark_dirty(r);
    gl.BindFramebuffer(GL_FRAMEBUFFER, r->fbo);
    const GLenum first[1] = {GL_COLOR_ATTACHMENT0};
    gl.DrawBuffers(1, first);
    gl.Viewport(0, 0, r->config.width, r->config.height);
}

void renderer_draw_points(Renderer* r, const glm::mat4& view_projection, const float* positions,
                          const float* sizes, uint32_t point_count) {
    renderer_draw_dots(r, view_projection, positions, sizes, nullptr, point_count);
}

void renderer_draw_dots(Renderer* r, const glm::mat4& view_projection, const float* positions,
                        const float* sizes, const uint8_t* colours, uint32_t point_count) {
    const GlApi& gl = r->gl;
    renderer_mark_dirty(r);
    gl.BindFramebuffer(GL_FRAMEBUFFER, r->ink_fbo);
    begin_ink_pass(r, r->point_program, r->point_vp, r->point_ink, view_projection);
    const bool own_colours = colours && r->point_colour_vbo;
    if (own_colours) gl.Uniform1i(r->point_use_colour, 1);
    gl.Disable(GL_DEPTH_TEST);  // each dot's visibility: kPointVs
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D, r->depth_tex);
    gl.Uniform1i(r->point_depth, 0);
    gl.Enable(GL_BLEND);  // antialiased dot edges
    gl.BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    gl.BindVertexArray(r->point_vao);
    gl.BindBuffer(GL_ARRAY_BUFFER, r->point_pos_vbo);
    gl.BufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(size_t(point_count) * 12), positions);
    gl.BindBuffer(GL_ARRAY_BUFFER, r->point_size_vbo);
    gl.BufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(size_t(point_count) * 4), sizes);
    if (own_colours) {
        gl.BindBuffer(GL_ARRAY_BUFFER, r->point_colour_vbo);
        gl.BufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(size_t(point_count) * 4), colours);
    }
    gl.DrawArrays(GL_POINTS, 0, GLsizei(point_count));
    // Back to the classic uniforms: app frames (runtime/app_frame.cpp) draw with this program.
    gl.Uniform1i(r->point_use_colour, 0);
    gl.Uniform1i(r->point_see_through, 0);
    gl.BindVertexArray(0);
    gl.BindTexture(GL_TEXTURE_2D, 0);
    gl.BindFramebuffer(GL_FRAMEBUFFER, r->fbo);
    check_pass(r, "dots");
}

void renderer_draw_lines(Renderer* r, const glm::mat4& view_projection, const float* lines,
                         uint32_t line_count) {
    renderer_draw_line_sets(r, view_projection, lines, line_count, nullptr, 0);
}

void renderer_draw_line_sets(Renderer* r, const glm::mat4& view_projection, const float* lines,
                             uint32_t line_count, const float* more, uint32_t more_count) {
    const GlApi& gl = r->gl;
    if (line_count + more_count == 0) return;
    renderer_mark_dirty(r);
    float range[2] = {1.0f, 1.0f};
    gl.GetFloatv(GL_ALIASED_LINE_WIDTH_RANGE, range);
    float width = r->config.line_width;
    gl.LineWidth(width < range[0] ? range[0] : (width > range[1] ? range[1] : width));
    begin_ink_pass(r, r->line_program, r->line_vp, r->line_ink, view_projection);
    gl.BindVertexArray(r->line_vao);
    gl.BindBuffer(GL_ARRAY_BUFFER, r->line_vbo);
    if (line_count > 0)
        gl.BufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(size_t(line_count) * 24), lines);
    if (more_count > 0)
        gl.BufferSubData(GL_ARRAY_BUFFER, GLintptr(size_t(line_count) * 24),
                         GLsizeiptr(size_t(more_count) * 24), more);
    gl.DrawArrays(GL_LINES, 0, GLsizei((line_count + more_count) * 2));
    gl.BindVertexArray(0);
    check_pass(r, "lines");
}

void renderer_check_errors(Renderer* r, const char* pass) {
    check_pass(r, pass);
}

void renderer_read_color(Renderer* r, uint8_t* rgba) {
    const GlApi& gl = r->gl;
    gl.BindFramebuffer(GL_FRAMEBUFFER, r->fbo);
    gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl.ReadPixels(0, 0, r->config.width, r->config.height, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    check_pass(r, "readback");
}

void renderer_read_depth(Renderer* r, float* scratch, float* depth) {
    const GlApi& gl = r->gl;
    if (!r->config.depth_copy) return;
    gl.BindFramebuffer(GL_FRAMEBUFFER, r->fbo);
    gl.ReadBuffer(GL_COLOR_ATTACHMENT1);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
    gl.ReadPixels(0, 0, r->config.width, r->config.height, GL_RGBA, GL_FLOAT, scratch);
    const size_t n = size_t(r->config.width) * size_t(r->config.height);
    for (size_t i = 0; i < n; ++i) depth[i] = scratch[i * 4];
    gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
    check_pass(r, "depth readback");
}

void renderer_destroy(Renderer* r) {
    const GlApi& gl = r->gl;
    if (!gl.DeleteBuffers) return;
    renderer_destroy_looks(r);
    renderer_destroy_front(r);
    renderer_destroy_occluder(r);
    GLuint buffers[5] = {r->mesh_vbo, r->mesh_ibo, r->point_pos_vbo, r->point_size_vbo,
                         r->line_vbo};
    gl.DeleteBuffers(5, buffers);
    GLuint vaos[3] = {r->mesh_vao, r->point_vao, r->line_vao};
    gl.DeleteVertexArrays(3, vaos);
    if (r->mesh_program) gl.DeleteProgram(r->mesh_program);
    if (r->point_program) gl.DeleteProgram(r->point_program);
    if (r->line_program) gl.DeleteProgram(r->line_program);
    GLuint rbs[2] = {r->color_rb, r->depth_copy_rb};
    gl.DeleteRenderbuffers(2, rbs);
    if (r->depth_tex) gl.DeleteTextures(1, &r->depth_tex);
    if (r->fbo) gl.DeleteFramebuffers(1, &r->fbo);
    if (r->ink_fbo) gl.DeleteFramebuffers(1, &r->ink_fbo);
    *r = Renderer();
}

void renderer_blit_to_default(Renderer* r, int width, int height) {
    const GlApi& gl = r->gl;
    const RendererConfig& c = r->config;
    // The largest rectangle of the frame's aspect that fits, centred.
    int w = width, h = int(int64_t(width) * c.height / c.width);
    if (h > height) h = height, w = int(int64_t(height) * c.width / c.height);
    const int x = (width - w) / 2, y = (height - h) / 2;
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl.Viewport(0, 0, width, height);
    if (w != width || h != height) {
        const float background[4] = {c.background[0], c.background[1], c.background[2], 1.0f};
        gl.ClearBufferfv(GL_COLOR, 0, background);
    }
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, r->fbo);
    gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
    const bool same = w == c.width && h == c.height;
    gl.BlitFramebuffer(0, 0, c.width, c.height, x, y, x + w, y + h, GL_COLOR_BUFFER_BIT,
                       same ? GL_NEAREST : GL_LINEAR);
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl.ReadBuffer(GL_BACK);
    check_pass(r, "blit");
}

void renderer_draw_points_from(Renderer* r, const glm::mat4& view_projection, GLuint vao,
                               uint32_t point_count) {
    const GlApi& gl = r->gl;
    renderer_mark_dirty(r);
    gl.BindFramebuffer(GL_FRAMEBUFFER, r->ink_fbo);
    begin_ink_pass(r, r->point_program, r->point_vp, r->point_ink, view_projection);
    gl.Disable(GL_DEPTH_TEST);  // each dot's visibility: kPointVs
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D, r->depth_tex);
    gl.Uniform1i(r->point_depth, 0);
    gl.Enable(GL_BLEND);
    gl.BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    gl.BindVertexArray(vao);
    gl.DrawArrays(GL_POINTS, 0, GLsizei(point_count));
    gl.Uniform1i(r->point_see_through, 0);  // the classic uniforms again (looks: set_dot_ink)
    gl.BindVertexArray(0);
    gl.BindTexture(GL_TEXTURE_2D, 0);
    gl.BindFramebuffer(GL_FRAMEBUFFER, r->fbo);
    check_pass(r, "dots");
}

}  // namespace stipple
