// Stage 4 of view-dependent particles on the GPU (GI'01 §2: "render strokes ... typically in
// 2-D at the particle's transformed screen-space position"): each StrokeInstance is one
// instanced quad textured with its brush from the atlas of runtime/brush_textures.h. A stroke
// is drawn whole or not at all, by the depth test of its centre against the polygon pass made
// in its vertex shader (like the stipple dots, runtime/renderer.h), so strokes may reach past
// the outline as painted ones do, yet strokes on the far side stay hidden.
// All GL objects are made in particle_renderer_init; drawing creates nothing.
#pragma once
#include <cstdint>

#include "runtime/gl_api.h"
#include "runtime/particle_style.h"
#include "runtime/status.h"

namespace stipple {

struct ParticleRenderer {
    GlApi gl;
    uint32_t capacity = 0;  // instances per draw
    GLuint program = 0, vao = 0, vbo = 0, atlas = 0;
    GLint u_viewport = -1, u_depth = -1, u_atlas = -1, u_test_depth = -1;
};

[[nodiscard]] Status particle_renderer_init(ParticleRenderer* r, const GlApi& gl,
                                            uint32_t capacity);

// Draws strokes[0 .. count) (count is clamped to the capacity) into `framebuffer`, a
// width x height colour target, testing each stroke's centre against `depth_texture` (the
// polygon pass's window depth, same size; 0: no test), in the viewport at (x0, y0) (the
// application's, runtime/app_frame.h). Blends over what is there; leaves blending off and
// the vertex array unbound.
void particle_renderer_draw(ParticleRenderer* r, GLuint framebuffer, GLuint depth_texture,
                            int width, int height, const StrokeInstance* strokes, uint32_t count,
                            int x0 = 0, int y0 = 0);

void particle_renderer_destroy(ParticleRenderer* r);

}  // namespace stipple
