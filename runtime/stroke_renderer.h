// GLES 3 drawing of tessellated paintstrokes (runtime/paintstroke.h). GI'98 composites with an
// A-buffer; GLES has none, so segments are sorted back to front on the CPU (stroke_sort.h) and
// drawn in that order with alpha blending, depth-tested (and depth-writing) against the depth
// the frame already holds, so strokes stand behind the body and stipples behind strokes.
// docs/paintstrokes.md says why this method and measures its error against a sorted reference.
// All GL objects are created in stroke_renderer_init; a draw creates nothing.
#pragma once
#include <cstdint>
#include <glm/glm.hpp>

#include "runtime/gl_api.h"
#include "runtime/paintstroke.h"
#include "runtime/status.h"

namespace stipple {

struct StrokeRendererConfig {
    uint32_t max_vertices = 0;  // capacity of the vertex buffer (StrokeVertex)
    uint32_t max_indices = 0;   // capacity of the index buffer
    bool check_errors = false;  // glGetError after each draw (like RendererConfig::check_errors)
};

// Local shading of §4.4/§5.3 in the fragment shader: Lambert diffuse times the vertex's global
// shading factor, plus Phong specular weighted by the vertex's reflectance.
struct StrokeLighting {
    glm::vec3 light_eye{0.0f, 0.0f, 1.0f};  // unit, toward the light, eye space
    float ambient = 0.25f;
    float diffuse = 0.75f;
    float specular_exponent = 24.0f;
};

struct StrokeRenderer {
    GlApi gl;
    StrokeRendererConfig config;
    GLuint program = 0, vao = 0, vbo = 0, ibo = 0;
    GLint u_projection = -1, u_light = -1, u_ambient = -1, u_diffuse = -1, u_shininess = -1;
    uint32_t gl_error_count = 0;
    GLenum first_gl_error = GL_NO_ERROR;
};

// Creates the program and buffers. Fails with gl_error (shader compile or link, a GL error),
// having released what it created.
[[nodiscard]] Status stroke_renderer_init(StrokeRenderer* r, const GlApi& gl,
                                          const StrokeRendererConfig& config);

// Draws `index_count` indices (triangles, already in back-to-front order: stroke_sort.h)
// over `vertex_count` vertices into the framebuffer that is bound, with the viewport that is
// set. `projection` takes eye space to clip space. Turns on depth test (LEQUAL), depth writes
// and alpha blending (SRC_ALPHA, ONE_MINUS_SRC_ALPHA), culling off, and leaves them so; the
// caller's renderer resets what it needs. Counts above the capacities are clamped.
void stroke_renderer_draw(StrokeRenderer* r, const glm::mat4& projection,
                          const StrokeLighting& lighting, const StrokeVertex* vertices,
                          uint32_t vertex_count, const uint32_t* indices, uint32_t index_count);

void stroke_renderer_destroy(StrokeRenderer* r);

}  // namespace stipple
