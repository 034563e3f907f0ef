// GLES 3 stipple renderer (thesis §3.2): the mesh is drawn as a plain "paper" coloured depth
// pass pushed slightly behind the surface, then every point is drawn as a round,
// antialiased dot of its computed diameter, whole when its centre passes the depth test
// against that pass (tested in the vertex shader on the depth texture), not at all otherwise.
// The mesh pass culls the back faces of single-sided triangles (double-sided ones are drawn
// from both sides) and writes depth only when the paper is the background's colour.
// All GL objects are created in renderer_init; drawing a frame creates nothing.
#pragma once
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>

#include "runtime/gl_api.h"
#include "runtime/status.h"

namespace stipple {

// Filled by pipeline_init: the image size, line width and background come from the resolved
// FrameConfig (runtime/frame_config.h, the one place for their defaults and limits), the
// capacities from the asset.
struct RendererConfig {
    int width = 0;  // pixels
    int height = 0;
    uint32_t max_points = 0;            // capacity of the point buffers
    uint32_t vertex_count = 0;          // capacity of the mesh vertex buffer
    uint32_t max_lines = 0;             // capacity of the silhouette line buffer
    float line_width = 0.0f;            // silhouette width in pixels (clamped to the GL range)
    const uint32_t* indices = nullptr;  // triangle list, uploaded once
    uint32_t triangle_count = 0;
    // Per triangle, 1 if double-sided (SidesView::triangle_double_sided): drawn from both
    // sides. The others are single-sided and the mesh pass culls their back faces (CCW
    // front, the bake's outward winding). nullptr: every triangle single-sided.
    const uint8_t* triangle_double_sided = nullptr;
    float background[3] = {};
    float paper[3] = {1.0f, 1.0f, 1.0f};  // colour of the depth pass (the object's body)
    float ink[3] = {0.0f, 0.0f, 0.0f};
    // Clip-space depth offset of the mesh pass, as a fraction of w (NDC units): keeps dots
    // lying on the surface in front of it (§3.2 "slightly behind the particles").
    float depth_bias = 0.002f;
    // Keep a float copy of the mesh pass's depth for renderer_read_depth (dot visibility
    // lists). Off by default: it costs a 4-byte-per-pixel clear and write every frame.
    bool depth_copy = false;
    // Call glGetError after each pass (depth, lines, dots) and each readback and record what
    // it reports in Renderer::gl_errors (FrameConfig::check_gl_errors). Off by default: each
    // check is a driver round trip.
    bool check_errors = false;
};

// GL errors seen by the checks (RendererConfig::check_errors) since renderer_init: how many,
// and the first one (the pass it followed and its code). Filled without allocating.
struct GlErrorLog {
    uint32_t count = 0;
    const char* first_pass = nullptr;  // "depth", "lines", "dots", "readback", "depth readback"
    GLenum first_error = GL_NO_ERROR;
};

// The name of a glGetError code ("GL_INVALID_OPERATION"), or "GL_UNKNOWN_ERROR".
const char* gl_error_name(GLenum error);

struct Renderer {
    GlApi gl;
    RendererConfig config;
    GLuint fbo = 0, color_rb = 0, depth_copy_rb = 0, depth_tex = 0;
    GLuint ink_fbo = 0;  // the colour renderbuffer alone: the dots pass samples depth_tex
    GLuint mesh_program = 0, point_program = 0;
    GLint mesh_vp = -1, mesh_bias = -1, mesh_paper = -1, point_vp = -1, point_ink = -1,
          point_depth = -1;
    GLuint mesh_vao = 0, mesh_vbo = 0, mesh_ibo = 0;
    // mesh_ibo holds the single-sided triangles first (this many), then the double-sided.
    uint32_t single_sided_count = 0;
    GLuint point_vao = 0, point_pos_vbo = 0, point_size_vbo = 0;
    GLuint line_program = 0, line_vao = 0, line_vbo = 0;
    GLint line_vp = -1, line_ink = -1;
    GlErrorLog gl_errors;  // filled only when config.check_errors
};

// Creates the framebuffer, shaders and buffers. Fails with gl_error (incomplete framebuffer,
// shader compile or link, a GL error), having released what it created.
[[nodiscard]] Status renderer_init(Renderer* r, const GlApi& gl, const RendererConfig& config);

// Draws one frame into the offscreen framebuffer.
void renderer_draw_mesh(Renderer* r, const glm::mat4& view_projection, const float* positions,
                        uint32_t vertex_count);
void renderer_draw_points(Renderer* r, const glm::mat4& view_projection, const float* positions,
                          const float* sizes, uint32_t point_count);

// Draws the mesh's triangles (mesh_ibo, mesh_vao bound) with the current program and
// framebuffer: the single-sided ones with back faces culled, the double-sided ones without.
// Which winding is culled follows the sign of det(view_projection) (a mirrored transform
// turns the back faces counter-clockwise on screen); the context's glCullFace / glFrontFace
// are not changed, and where they cannot cull that winding every triangle is drawn. Leaves
// GL_CULL_FACE off.
void renderer_draw_triangles(Renderer* r, const glm::mat4& view_projection);

// Binds the offscreen framebuffer (colour and depth; not the depth copy) and its viewport for a
// pass that draws its own geometry over the mesh pass (paintstrokes, runtime/stroke_stage.h).
void renderer_begin_overlay(Renderer* r);

// Draws `line_count` ink lines (6 floats each) depth-tested against the mesh pass.
void renderer_draw_lines(Renderer* r, const glm::mat4& view_projection, const float* lines,
                         uint32_t line_count);

// With RendererConfig::check_errors: calls glGetError and records what it reports after
// `pass` in Renderer::gl_errors (for passes drawn outside this file: runtime/app_frame.cpp).
void renderer_check_errors(Renderer* r, const char* pass);

// Reads back the frame as RGBA8, bottom row first (width * height * 4 bytes).
void renderer_read_color(Renderer* r, uint8_t* rgba);
// Reads back the mesh pass's window depth (1 = background), bottom row first; needs
// RendererConfig::depth_copy. `scratch`
// must hold width * height * 4 floats; the result is written to depth (width * height).
void renderer_read_depth(Renderer* r, float* scratch, float* depth);

// Copies the last frame to the default framebuffer (an on-screen window's back buffer) of
// width x height pixels: scaled to fit, centred, aspect kept, the borders cleared to the
// background; pixel for pixel (GL_NEAREST) when the sizes match. Leaves framebuffer 0 bound
// for reading and drawing. The caller swaps.
void renderer_blit_to_default(Renderer* r, int width, int height);

void renderer_destroy(Renderer* r);

}  // namespace stipple
