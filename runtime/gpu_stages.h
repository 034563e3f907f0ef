// The GPU path (issue 9, item 4; docs/gpu-path.md): the per-point stages of a frame, place
// (thesis Alg. 6.3), relevance (Alg. 6.4) and size (ch. 3, Alg. 3.1/3.2, §8.4), run in one
// GLES 3.0 vertex shader with transform feedback, one invocation per baked point, as the
// thesis's real-time system sized points in a vertex program (Thesis §7.3). The CPU
// still samples the clip and skins the mesh; each frame it uploads only the posed vertex
// positions and normals (two float textures). Everything else the shader reads (the points'
// host vertices and barycentric coordinates, relevance scales, rest radii, neighbour lists,
// double-sided flags) is uploaded once at init. The shader writes each point's position and
// stipple diameter (vec4) into a buffer the dots pass draws straight from; a diameter of 0
// (back-facing, behind the eye) is culled by the dots shader. No allocation per frame.
#pragma once
#include <cstdint>
#include <glm/glm.hpp>

#include "runtime/asset.h"
#include "runtime/gl_api.h"
#include "runtime/status.h"
#include "runtime/stipple_size.h"

namespace stipple {

struct Pipeline;
struct Renderer;
struct StageTimes;

// Texels per row of every data texture: 1 << kGpuRowShift (a power of two, so the shader
// turns an index into a texel with a mask and a shift). Rows are limited by
// GL_MAX_TEXTURE_SIZE (16384 on llvmpipe: 33M points or neighbours).
constexpr int kGpuRowShift = 11;
// Host vertex indices are packed 21 bits each into two words (one texel per neighbour).
constexpr uint32_t kGpuMaxVertices = 1u << 21;

struct GpuStages {
    GlApi gl;
    uint32_t point_count = 0;
    uint32_t vertex_count = 0;
    GLuint program = 0;
    GLint u_view_projection = -1, u_eye_focal = -1, u_size = -1, u_lights = -1, u_light_count = -1,
          u_ink = -1, u_ambient = -1;
    // Textures, all 1 << kGpuRowShift texels wide (units 0-3 in the transform feedback pass).
    GLuint vertex_positions = 0, vertex_normals = 0;  // RGB32F, posed every frame
    GLuint points = 0;      // RGBA32UI: host vertices packed (2 words), bits of u, bits of v
    GLuint neighbours = 0;  // RGBA32UI: the neighbour lists, each neighbour's `points` texel
    // Per-point attributes of the transform feedback pass.
    GLuint feedback_vao = 0, scale_vbo = 0, rest_vbo = 0, offsets_vbo = 0, sides_vbo = 0;
    // Transform feedback output: 4 floats per point (position xyz, diameter in pixels).
    GLuint dots = 0;
    GLuint draw_vao = 0;  // `dots` as the dots program's position and size attributes
};

// Creates the program, textures and buffers and uploads the static data: `radius_scale` is
// relevance_scale()'s output, `rest_radius` the radii used without relevance updates and for
// points without neighbours, `double_sided` per-point flags or nullptr
// (runtime/double_sided.h). Fails with gl_error (a shader, a GL error) or invalid_argument
// (more vertices, points or neighbours than the textures hold), having released what it
// created. Allocates nothing (uploads go through a fixed block on the stack).
[[nodiscard]] Status gpu_stages_init(GpuStages* g, const GlApi& gl, const Asset& asset,
                                     const float* radius_scale, const float* rest_radius,
                                     const uint8_t* double_sided);

// One frame: uploads the posed vertices (3 floats each, vertex_count) and runs place,
// relevance (when `relevance_update`, else the rest radii) and size for every point into the
// `dots` buffer. Rasterisation is off during the pass; the current framebuffer is untouched.
void gpu_stages_run(GpuStages* g, const float* vertex_positions, const float* vertex_normals,
                    const SizeParams& params, bool relevance_update);

// For tests: copies the last run's output to `out` (4 floats per point: x, y, z, diameter).
// Returns false if the buffer could not be mapped.
bool gpu_stages_read_dots(const GpuStages& g, float* out);

void gpu_stages_destroy(GpuStages* g);

// The pipeline's side (runtime/frame_pipeline.cpp, FrameConfig::path == gpu):
// at init, after the renderer, the stages over the pipeline's asset and rest-pose radii;
[[nodiscard]] Status gpu_path_init(Pipeline* p);
// per frame, after posing the mesh, what pipeline_update does besides the point stages
// (silhouettes, strokes); the points are not placed on the CPU (dot lists need the CPU path);
void gpu_path_update(Pipeline* p, StageTimes* times);
// and in the draw, in place of renderer_draw_points: the stages, then the dots from their
// buffer.
void gpu_path_draw_points(Pipeline* p);

}  // namespace stipple
