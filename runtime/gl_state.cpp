#include "runtime/gl_state.h"

namespace stipple {
namespace {

void set_enabled(const GlApi& gl, GLenum cap, GLboolean on) {
    if (on)
        gl.Enable(cap);
    else
        gl.Disable(cap);
}

}  // namespace

GlStateSnapshot gl_state_save(const GlApi& gl) {
    GlStateSnapshot s;
    gl.GetIntegerv(GL_CURRENT_PROGRAM, &s.program);
    gl.GetIntegerv(GL_VERTEX_ARRAY_BINDING, &s.vertex_array);
    gl.GetIntegerv(GL_ARRAY_BUFFER_BINDING, &s.array_buffer);
    gl.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &s.draw_framebuffer);
    gl.GetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &s.read_framebuffer);
    gl.GetIntegerv(GL_ACTIVE_TEXTURE, &s.active_texture);
    gl.ActiveTexture(GL_TEXTURE0);
    gl.GetIntegerv(GL_TEXTURE_BINDING_2D, &s.texture_2d_unit0);
    gl.ActiveTexture(GLenum(s.active_texture));
    gl.GetIntegerv(GL_VIEWPORT, s.viewport);
    gl.GetIntegerv(GL_DEPTH_FUNC, &s.depth_func);
    gl.GetIntegerv(GL_CULL_FACE_MODE, &s.cull_face_mode);
    gl.GetIntegerv(GL_FRONT_FACE, &s.front_face);
    gl.GetIntegerv(GL_BLEND_SRC_RGB, &s.blend_src_rgb);
    gl.GetIntegerv(GL_BLEND_DST_RGB, &s.blend_dst_rgb);
    gl.GetIntegerv(GL_BLEND_SRC_ALPHA, &s.blend_src_alpha);
    gl.GetIntegerv(GL_BLEND_DST_ALPHA, &s.blend_dst_alpha);
    s.blend = gl.IsEnabled(GL_BLEND);
    s.depth_test = gl.IsEnabled(GL_DEPTH_TEST);
    s.cull_face = gl.IsEnabled(GL_CULL_FACE);
    gl.GetBooleanv(GL_DEPTH_WRITEMASK, &s.depth_mask);
    gl.GetBooleanv(GL_COLOR_WRITEMASK, s.color_mask);
    gl.GetFloatv(GL_LINE_WIDTH, &s.line_width);
    return s;
}

void gl_state_restore(const GlApi& gl, const GlStateSnapshot& s) {
    gl.UseProgram(GLuint(s.program));
    gl.BindVertexArray(GLuint(s.vertex_array));
    gl.BindBuffer(GL_ARRAY_BUFFER, GLuint(s.array_buffer));
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(s.draw_framebuffer));
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(s.read_framebuffer));
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D, GLuint(s.texture_2d_unit0));
    gl.ActiveTexture(GLenum(s.active_texture));
    gl.Viewport(s.viewport[0], s.viewport[1], s.viewport[2], s.viewport[3]);
    gl.DepthFunc(GLenum(s.depth_func));
    gl.CullFace(GLenum(s.cull_face_mode));
    gl.FrontFace(GLenum(s.front_face));
    gl.BlendFuncSeparate(GLenum(s.blend_src_rgb), GLenum(s.blend_dst_rgb),
                         GLenum(s.blend_src_alpha), GLenum(s.blend_dst_alpha));
    set_enabled(gl, GL_BLEND, s.blend);
    set_enabled(gl, GL_DEPTH_TEST, s.depth_test);
    set_enabled(gl, GL_CULL_FACE, s.cull_face);
    gl.DepthMask(s.depth_mask);
    gl.ColorMask(s.color_mask[0], s.color_mask[1], s.color_mask[2], s.color_mask[3]);
    gl.LineWidth(s.line_width);
}

}  // namespace stipple
