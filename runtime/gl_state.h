// The GL state a stipple draw into the application's frame changes (runtime/app_frame.h),
// saved before the draw and put back after it, so the application finds its program, vertex
// array, buffers, framebuffers, viewport, blending, depth and colour settings, line width and
// texture unit 0 as it left them. Plain glGet calls: a few dozen driver queries per draw.
#pragma once
#include "runtime/gl_api.h"

namespace stipple {

struct GlStateSnapshot {
    GLint program = 0, vertex_array = 0, array_buffer = 0;
    GLint draw_framebuffer = 0, read_framebuffer = 0;
    GLint active_texture = GL_TEXTURE0, texture_2d_unit0 = 0;
    GLint viewport[4] = {};
    GLint depth_func = GL_LESS;
    GLint cull_face_mode = GL_BACK, front_face = GL_CCW;
    GLint blend_src_rgb = GL_ONE, blend_dst_rgb = GL_ZERO, blend_src_alpha = GL_ONE,
          blend_dst_alpha = GL_ZERO;
    GLboolean blend = GL_FALSE, depth_test = GL_FALSE, cull_face = GL_FALSE;
    GLboolean depth_mask = GL_TRUE;
    GLboolean color_mask[4] = {GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE};
    GLfloat line_width = 1.0f;
};

GlStateSnapshot gl_state_save(const GlApi& gl);
void gl_state_restore(const GlApi& gl, const GlStateSnapshot& s);

}  // namespace stipple
