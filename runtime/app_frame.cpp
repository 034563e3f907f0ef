#include "runtime/app_frame.h"

#include <chrono>

#include "runtime/gl_state.h"
#include "runtime/particle_frame.h"

namespace stipple {
namespace {

// The body in the paper colour, into the application's framebuffer (its vertices were
// uploaded by renderer_draw_mesh this frame). GL_CULL_FACE is left off (restored later by
// gl_state_restore).
void draw_body(Renderer* r, const glm::mat4& vp) {
    const GlApi& gl = r->gl;
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_LESS);
    gl.DepthMask(GL_TRUE);
    gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl.Disable(GL_BLEND);
    gl.UseProgram(r->mesh_program);
    gl.UniformMatrix4fv(r->mesh_vp, 1, GL_FALSE, &vp[0][0]);
    gl.Uniform1f(r->mesh_bias, r->config.depth_bias);
    const float* paper = r->config.paper;
    gl.Uniform4f(r->mesh_paper, paper[0], paper[1], paper[2], 1.0f);
    gl.BindVertexArray(r->mesh_vao);
    renderer_draw_triangles(r, vp);  // culled as offscreen
    renderer_check_errors(r, "app depth");
}

// Ink over the body: tested against the framebuffer's depth, not writing it.
void begin_app_ink(Renderer* r, GLuint program, GLint vp_location, GLint ink_location,
                   const glm::mat4& vp) {
    const GlApi& gl = r->gl;
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_LEQUAL);
    gl.DepthMask(GL_FALSE);
    gl.UseProgram(program);
    gl.UniformMatrix4fv(vp_location, 1, GL_FALSE, &vp[0][0]);
    const float* ink = r->config.ink;
    gl.Uniform4f(ink_location, ink[0], ink[1], ink[2], 1.0f);
}

void draw_lines(Renderer* r, const glm::mat4& vp, const float* lines, uint32_t count) {
    if (count == 0) return;
    const GlApi& gl = r->gl;
    float range[2] = {1.0f, 1.0f};
    gl.GetFloatv(GL_ALIASED_LINE_WIDTH_RANGE, range);
    const float width = r->config.line_width;
    gl.LineWidth(width < range[0] ? range[0] : (width > range[1] ? range[1] : width));
    begin_app_ink(r, r->line_program, r->line_vp, r->line_ink, vp);
    gl.Disable(GL_BLEND);
    gl.BindVertexArray(r->line_vao);
    gl.BindBuffer(GL_ARRAY_BUFFER, r->line_vbo);
    gl.BufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(size_t(count) * 24), lines);
    gl.DrawArrays(GL_LINES, 0, GLsizei(count * 2));
    renderer_check_errors(r, "app lines");
}

// Dots: the visibility test (centre pixel, else the depth interpolated around it; runtime/
// renderer_shaders.h) against the body's depth in the pipeline's own framebuffer (vertex
// shader), then the per-pixel depth test against the application's framebuffer.
void draw_dots(Renderer* r, const glm::mat4& vp, const float* positions, const float* sizes,
               uint32_t count) {
    const GlApi& gl = r->gl;
    begin_app_ink(r, r->point_program, r->point_vp, r->point_ink, vp);
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D, r->depth_tex);
    gl.Uniform1i(r->point_depth, 0);
    gl.Enable(GL_BLEND);
    gl.BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    gl.BindVertexArray(r->point_vao);
    gl.BindBuffer(GL_ARRAY_BUFFER, r->point_pos_vbo);
    gl.BufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(size_t(count) * 12), positions);
    gl.BindBuffer(GL_ARRAY_BUFFER, r->point_size_vbo);
    gl.BufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(size_t(count) * 4), sizes);
    gl.DrawArrays(GL_POINTS, 0, GLsizei(count));
    renderer_check_errors(r, "app dots");
}

}  // namespace

void pipeline_draw_into(Pipeline* p, const AnimationState& state, const AppView& view,
                        StageTimes* t) {
    Renderer* r = &p->renderer;
    const GlApi& gl = r->gl;
    const GlStateSnapshot saved = gl_state_save(gl);
    pipeline_set_camera(p, view.view * view.model, view.projection, view.viewport[2],
                        view.viewport[3], view.model);
    pipeline_update(p, state, t);
    if (p->particles.enabled)  // GI'01 strokes instead of dots (runtime/particle_frame.h)
        particle_stage_update(&p->particles, pipeline_particle_input(*p));
    const auto start = std::chrono::steady_clock::now();
    const glm::mat4& vp = p->view_projection;
    renderer_draw_mesh(r, vp, p->vertex_positions.get(), p->asset->mesh.vertex_count);
    const GLuint target =
        view.framebuffer >= 0 ? GLuint(view.framebuffer) : GLuint(saved.draw_framebuffer);
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, target);
    gl.Viewport(view.viewport[0], view.viewport[1], view.viewport[2], view.viewport[3]);
    draw_body(r, vp);
    if (p->strokes.enabled) stroke_stage_draw(&p->strokes, pipeline_stroke_input(*p));
    draw_lines(r, vp, p->lines.get(), p->lines_drawn);
    const ParticleStage& s = p->particles;
    if (s.enabled)  // each stroke whole by its centre's depth, as in the own frame
        particle_renderer_draw(&p->particles.renderer, target, r->depth_tex, view.viewport[2],
                               view.viewport[3], s.strokes.get(), s.stroke_count, view.viewport[0],
                               view.viewport[1]);
    else
        draw_dots(r, vp, p->draw_positions.get(), p->draw_sizes.get(), p->points_drawn);
    gl_state_restore(gl, saved);
    if (t)
        t->draw +=
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
}

}  // namespace stipple
