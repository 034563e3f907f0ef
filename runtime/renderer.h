// GLES 3 stipple renderer (thesis §3.2): the mesh is drawn as a plain "paper" coloured depth
// pass pushed slightly behind the surface, then every point is drawn as a round,
// antialiased dot of its computed diameter, whole when it passes the depth test against that
// pass at its centre pixel or against the depth interpolated from the 2x2 texels around its
// centre (in the vertex shader, on the depth texture; runtime/renderer_shaders.h), not at all
// otherwise.
// Looks (runtime/style.h, renderer_draw_fill / renderer_draw_dots): a toon or opaque-parts-only
// mesh pass, dots in their own colours, dots that see through transparent parts.
// The mesh pass culls the back faces of single-sided triangles (double-sided ones are drawn
// from both sides) and writes depth only when the paper is the background's colour.
// All GL objects are created in renderer_init; drawing a frame creates nothing.
#pragma once
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>

#include "runtime/frame_config.h"
#include "runtime/gl_api.h"
#include "runtime/status.h"
#include "runtime/style.h"

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
    // Looks (runtime/style.h, runtime/renderer_style.cpp). RGBA8 per vertex (StyleBuffers::
    // vertex_colours: part colour, alpha 0 on transparent parts), uploaded once; nullptr: none.
    const uint8_t* vertex_colours = nullptr;
    bool part_colours = false;  // vertex_colours carry the parts' colours (toon fills with them)
    bool dot_colours = false;   // a per-dot RGBA8 buffer (renderer_draw_dots' colours)
    uint32_t max_creases = 0;   // crease lines drawn with the silhouettes (line buffer capacity)
    // The simplified occluder (runtime/renderer_occluder.cpp; the asset's OCCL section): the
    // depth-only mesh pass draws these triangles, pushed `occluder_push` object units away
    // from the eye, instead of the single-sided ones. 0 triangles: none.
    const uint32_t* occluder_indices = nullptr;
    uint32_t occluder_triangle_count = 0;
    float occluder_push = 0.0f;
};

// The look of the next frames (set by pipeline_set_camera from the resolved FrameConfig).
struct RendererLook {
    Style style = Style::classic;
    int toon_bands = 3;
    float toon_shade = 0.6f;  // level of the darkest toon band
    float toon_ink = 0.4f;    // toon dots: the fill colour times this
    float fill[3] = {1.0f, 1.0f, 1.0f};
    bool transparent_parts = false;  // vertex alpha marks see-through parts (else all of it)
    int light_count = 0;
    float lights[kMaxLights][4] = {};  // toward the light (the mesh's space, unit), intensity
    float ambient = 0.0f;
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
    // Looks (runtime/renderer_style.cpp): the styled mesh pass and its extra vertex buffers
    // (normals at location 1, vertex colours at 2), dot colours (location 2 of point_vao).
    RendererLook look;
    GLuint style_program = 0, mesh_normal_vbo = 0, mesh_colour_vbo = 0, point_colour_vbo = 0;
    GLint style_vp = -1, style_bias = -1, style_fill = -1, style_toon = -1, style_shade = -1,
          style_lights = -1, style_light_count = -1, style_ambient = -1, style_cut = -1;
    GLint point_use_colour = -1, point_see_through = -1;
    // The mesh pass's front faces (runtime/renderer_front.cpp, renderer_set_front_faces): the
    // per-triangle facing flags of this frame (silhouette.h), valid for front_vp only, and
    // front_ibo, which holds the single-sided triangles among them that may face the eye
    // (front_count of them, or kFrontNotBuilt until the first mesh pass that uses them).
    static constexpr uint32_t kFrontNotBuilt = 0xFFFFFFFFu;
    const uint8_t* front_faces = nullptr;
    glm::mat4 front_vp = glm::mat4(0.0f);
    uint32_t front_count = kFrontNotBuilt;
    GLuint front_ibo = 0;
    // The occluder's pass (runtime/renderer_occluder.cpp); occluder_enabled: used by the
    // depth-only mesh passes (set at init when the config has one; tests turn it off).
    GLuint occluder_program = 0, occluder_ibo = 0;
    GLint occluder_vp = -1, occluder_bias = -1, occluder_paper = -1, occluder_eye = -1,
          occluder_push = -1;
    bool occluder_enabled = false;
    // What the next renderer_clear_frame clears (runtime/renderer_dirty.cpp): x, y, width,
    // height in pixels of what has been drawn since the last clear; width < 0: all of it.
    int dirty[4] = {0, 0, -1, -1};
    float cleared_background[3] = {};  // the background the last clear painted
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

// The facing of this frame's triangles (triangle_facing's flags for the posed vertices the mesh
// passes draw and the eye of `view_projection`; runtime/silhouette.h), or nullptr: with them,
// renderer_draw_triangles hands the GPU only the single-sided triangles that may face the eye
// instead of having it cull the rest, for passes drawn with this same view_projection (a
// perspective one). The picture is the same: the triangles left out are those the GPU culls.
// `front` must stay valid until the next call. (runtime/renderer_front.cpp)
void renderer_set_front_faces(Renderer* r, const uint8_t* front, const glm::mat4& view_projection);
// renderer_draw_triangles' part: when the flags apply to `view_projection`, writes the
// single-sided triangles that may face the eye into r->front_ibo (once per set of flags), sets
// *count to their number and returns true.
bool renderer_front_triangles(Renderer* r, const glm::mat4& view_projection, uint32_t* count);
// renderer_init's and renderer_destroy's part for front_ibo.
void renderer_init_front(Renderer* r);
void renderer_destroy_front(Renderer* r);

// The simplified occluder (runtime/renderer_occluder.cpp; issue 9 item 5). Sets rc's
// occluder from the asset's OCCL section when c.occluder is on; push: the bake's measured
// deviation times a margin (runtime/renderer_occluder.cpp).
struct Asset;
void renderer_config_occluder(RendererConfig* rc, const Asset& asset, const FrameConfig& c);
// renderer_init's and renderer_destroy's part for it.
[[nodiscard]] Status renderer_init_occluder(Renderer* r);
void renderer_destroy_occluder(Renderer* r);
// renderer_draw_mesh's part: when the occluder is enabled and the pass writes only depth
// (paper the background's colour; the depth copy too), draws the occluder with back faces
// culled and then the double-sided triangles with the current (mesh) program, and returns
// true; else draws nothing and returns false.
bool renderer_draw_occluder(Renderer* r, const glm::mat4& view_projection);

// Clearing only what was drawn (runtime/renderer_dirty.cpp). renderer_clear_frame clears the
// dirty rectangle (all of the image unless renderer_set_drawn_box narrowed it since the
// last draw, or when the background changed) and leaves it all dirty; every draw entry point
// marks it all dirty. renderer_set_drawn_box, called after a frame's passes, narrows it to the
// screen rectangle of the box [lo, hi] (the mesh's space) under `view_projection`, grown by
// `margin_px` (dots' and lines' half width): what those passes drew must lie inside.
void renderer_mark_dirty(Renderer* r);
void renderer_set_drawn_box(Renderer* r, const glm::mat4& view_projection, const glm::vec3& lo,
                            const glm::vec3& hi, float margin_px);
// renderer_set_drawn_box for the box of the posed mesh's `vertex_count` vertices and a margin
// for dots up to the largest of max_point_size and sizes[0 .. size_count) in diameter and for
// the lines: what pipeline_frame drew when everything lies on the mesh (no paintstrokes).
void renderer_set_drawn_mesh(Renderer* r, const glm::mat4& view_projection, const float* positions,
                             uint32_t vertex_count, const float* sizes, uint32_t size_count,
                             float max_point_size);
// renderer_clear_frame's part: enables the scissor test on the dirty rectangle when it is not
// all of the image (returns true: the caller disables it after clearing).
bool renderer_scissor_dirty(Renderer* r);

// Binds the offscreen framebuffer (colour and depth; not the depth copy) and its viewport for a
// pass that draws its own geometry over the mesh pass (paintstrokes, runtime/stroke_stage.h).
void renderer_begin_overlay(Renderer* r);

// Draws `line_count` ink lines (6 floats each) depth-tested against the mesh pass.
void renderer_draw_lines(Renderer* r, const glm::mat4& view_projection, const float* lines,
                         uint32_t line_count);
// The same for two sets of lines in one draw (silhouettes, then crease lines, thesis §8.2);
// the line buffer holds config.max_lines + config.max_creases.
void renderer_draw_line_sets(Renderer* r, const glm::mat4& view_projection, const float* lines,
                             uint32_t line_count, const float* more, uint32_t more_count);

// Looks (runtime/style.h; runtime/renderer_style.cpp). The mesh pass of r->look.style: classic
// is renderer_draw_mesh; toon fills with a band ramp of the look's lights over `normals`
// (thesis §7.2); colour is classic's pass; transparent fills only the opaque parts (none
// when no part is marked), so the dots and lines of the others see through (§7.4).
void renderer_draw_fill(Renderer* r, const glm::mat4& view_projection, const float* positions,
                        const float* normals, uint32_t vertex_count);
// Dots as renderer_draw_points, in r->look's ink: one RGBA8 colour per dot (`colours`, needs
// config.dot_colours) or the style's (classic, transparent: ink; colour: fill; toon: fill
// times toon_ink). In the transparent style a dot is drawn where no opaque part hides it.
void renderer_draw_dots(Renderer* r, const glm::mat4& view_projection, const float* positions,
                        const float* sizes, const uint8_t* colours, uint32_t point_count);
// Binds the offscreen framebuffer and clears its colour, depth copy and depth (the start of
// every mesh pass).
void renderer_clear_frame(Renderer* r);
// Sets r->look from the resolved frame settings; `light_directions` (c.light_count of them)
// are in the mesh's space, toward the light, unit (SizeParams::light_direction).
void renderer_set_look(Renderer* r, const FrameConfig& c, const glm::vec3* light_directions,
                       bool transparent_parts);
// renderer_init's and renderer_destroy's part for the looks.
[[nodiscard]] Status renderer_init_looks(Renderer* r);
void renderer_destroy_looks(Renderer* r);

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

// The dots pass (renderer_draw_points) over dots already on the GPU: `vao` binds attribute 0
// (position, 3 floats) and 1 (diameter) from a buffer of `point_count` dots, e.g. the GPU
// path's transform feedback output (runtime/gpu_stages.h). Dots of diameter 0 are culled.
void renderer_draw_points_from(Renderer* r, const glm::mat4& view_projection, GLuint vao,
                               uint32_t point_count);

}  // namespace stipple
