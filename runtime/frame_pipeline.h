// One frame of animated stippling as a pipeline of plain stages over flat arrays
// (thesis Alg. 6.4 wrapped around Alg. 3.2):
//   sample clip -> skin mesh -> place points -> recompute relevance -> size
//   -> silhouette edges -> draw.
// Every buffer is allocated in pipeline_init from the asset's counts; a frame allocates
// nothing.
#pragma once
#include <cstdint>
#include <glm/glm.hpp>
#include <memory>

#include "runtime/asset.h"
#include "runtime/frame_config.h"
#include "runtime/gpu_stages.h"
#include "runtime/memory.h"
#include "runtime/particle_stage.h"
#include "runtime/point_clusters.h"
#include "runtime/point_refinement.h"
#include "runtime/point_simd.h"
#include "runtime/point_triangulation.h"
#include "runtime/renderer.h"
#include "runtime/stipple_size.h"
#include "runtime/stroke_stage.h"
#include "runtime/thread_pool.h"

namespace stipple {

// What pose to draw: one clip, optionally blended with a second (walk -> run crossfades are
// a second clip whose weight ramps from 0 to 1).
struct AnimationState {
    int clip = -1;        // -1: the rest pose
    float time = 0.0f;    // seconds; clips loop
    int blend_clip = -1;  // layered clip, or -1
    float blend_time = 0.0f;
    float blend_weight = 0.0f;  // in [0, 1]: 0 shows only `clip`, 1 only `blend_clip`
};

struct StageTimes {  // milliseconds
    // select: the level of detail's choice of points (runtime/point_clusters.h), before place;
    // relevance: with relevance recompute on the AVX2 path, the fused relevance + size pass
    // (runtime/point_stages.h), size then only what follows it
    double sample = 0, skin = 0, select = 0, place = 0, relevance = 0, refine = 0, size = 0,
           silhouette = 0, strokes = 0, draw = 0, readback = 0;
};

struct Pipeline {
    const Asset* asset = nullptr;
    FrameConfig config;  // resolved (runtime/frame_config.h)
    glm::mat4 view_projection = glm::mat4(1.0f);
    glm::mat4 view = glm::mat4(1.0f), projection = glm::mat4(1.0f);  // view_projection's parts
    float focal_px = 0.0f;                        // pixels per unit at unit distance (this zoom)
    int viewport_width = 0, viewport_height = 0;  // what the camera projects to
    glm::vec3 light_eye{0.0f, 0.0f, 1.0f};        // the key light, toward it, eye space
    SizeParams size_params;
    Renderer renderer;

    // Two sampled poses (clip and blend clip) and their blend, each node_count; a sampling
    // context per slot (cursors: the largest clip's channel count); morph weights per slot.
    Buffer<anim::Trs> locals[3];
    Buffer<uint32_t> cursors[2];
    anim::SamplingContext contexts[2];
    Buffer<float> morph_weights[3];                  // morph slot count each
    Buffer<anim::DqsJoint> dq_joints;                // joint_count
    Buffer<glm::mat4> models;                        // node_count
    Buffer<glm::mat4> skin_matrices;                 // joint_count
    Buffer<float> vertex_positions, vertex_normals;  // 3 * vertex_count
    // Each posed vertex as 8 floats, x y z |n| nx ny nz 1/|n| (runtime/point_simd.h's
    // pair_vertices), filled at the start of the frame's point stages: the clusters' tests and AVX2
    // place.
    Buffer<float> vertex_pairs;
    // Points of the frame: the baked hierarchy (point_count) followed by the run-time
    // refinement's extra points (up to refinement_budget); capacity = point_count + budget.
    uint32_t point_capacity = 0;
    Buffer<float> point_positions, point_normals;  // 3 * capacity
    Buffer<float> radius_scale;                    // point_count, see relevance_scale()
    // 4 per baked point when every list holds at most 4 (runtime/point_simd.h's
    // quad_neighbours; AVX2 relevance reads them), else null.
    Buffer<uint32_t> neighbour_quads;
    // AVX2 place's 16-byte hosts, one per baked point (runtime/point_simd.h's point_hosts),
    // or null (meshes of more than 2^21 vertices).
    Buffer<PointHost> point_hosts;
    Buffer<float> draw_positions, draw_sizes;  // the dots with a size, compacted
    Buffer<float> rest_radius;                 // point_count
    // The baked radii, the coarse ranks' following their prefix's surface density
    // (runtime/region_density.h): what every stipple stage reads instead of the asset's.
    Buffer<float> baked_radius;  // point_count
    Buffer<float> radius, size;  // capacity
    RefinementMesh refinement;
    // The refinement's triangles: a triangulation of the baked points when the bake has enough
    // of them (runtime/point_triangulation.h), else the render mesh.
    PointTriangulation point_triangles;
    MeshView refinement_domain;
    bool refine_on_points = false;
    Buffer<uint32_t> refined_triangle, refined_index;  // budget
    uint32_t refined_count = 0;                        // extra points in the last frame
    RefinementStats refinement_stats;
    Buffer<uint8_t> point_double_sided;  // point_count, or null: runtime/double_sided.h
    Buffer<uint8_t> triangle_front;      // triangle_count
    Buffer<float> lines;                 // 6 * edge_count
    uint32_t points_drawn = 0;           // size > 0 in the last frame
    uint32_t lines_drawn = 0;            // silhouette lines
    ParticleStage particles;             // FrameConfig::particle_style (runtime/particle_frame.h)
    StrokeStage strokes;                 // paintstrokes (empty without STRK)
    StyleBuffers style;                  // looks: runtime/style.h (empty for an asset without LOOK)
    bool dots_coloured = false;          // the last frame's dots carry style.dot_colours
    GpuStages gpu;                       // FrameConfig::path == gpu: runtime/gpu_stages.h
    // Level of detail (FrameConfig::lod, runtime/point_clusters.h); lod_sizes_clear: every
    // baked point outside the last selection has size 0.
    PointClusters clusters;
    bool lod_sizes_clear = false;
    ThreadPool pool;  // FrameConfig::threads: the point stages' ranges (runtime/point_stages.h)
};

// Resolves `config` (resolve_frame_config: defaults, limits), takes every buffer a frame needs
// and creates the renderer. Fails with invalid_argument (a setting out of range),
// out_of_memory or gl_error.
// Every buffer comes from `allocator` (runtime/memory.h; default: operator new); with a
// block allocator the block must hold pipeline_memory_bytes(asset, config) bytes (16-byte
// aligned, or 15 bytes more).
[[nodiscard]] Status pipeline_init(Pipeline* p, const Asset& asset, const GlApi& gl,
                                   const FrameConfig& config,
                                   const Allocator& allocator = Allocator());

// The bytes pipeline_init takes from its allocator for `asset` and `config` (every buffer,
// rounded as a block allocator rounds them), found by running the CPU half of the init with a
// counting allocator: as slow as that half, no GL needed. 0 if `config` is invalid or memory
// ran out. Several pipelines over one asset each take this much; the asset is shared.
size_t pipeline_memory_bytes(const Asset& asset, const FrameConfig& config);

// Poses the mesh as `state` says, then runs every CPU stage and draws. Stage times are added
// to `times` if it is not null.
void pipeline_frame(Pipeline* p, const AnimationState& state, StageTimes* times);

// The same for one clip at `time` seconds (-1: rest pose).
void pipeline_frame(Pipeline* p, int clip, float time, StageTimes* times);

// The CPU half of pipeline_frame: poses the mesh and runs every point, silhouette and stroke
// stage for the camera set last (pipeline_set_camera or the orbit camera), drawing nothing.
void pipeline_update(Pipeline* p, const AnimationState& state, StageTimes* times);

// Sets the camera the next frames see: `view` takes the posed mesh's space to eye space,
// `projection` eye space to clip space (perspective, GL conventions), for a viewport of the
// given size in pixels (the stipple sizes are in its pixels). pipeline_init and
// pipeline_set_view set the orbit camera (runtime/camera.h); runtime/app_frame.h sets the
// application's.
// `model` takes the posed space to world space (world-space lights are turned by its inverse).
void pipeline_set_camera(Pipeline* p, const glm::mat4& view, const glm::mat4& projection,
                         int viewport_width, int viewport_height,
                         const glm::mat4& model = glm::mat4(1.0f));

// What the stroke stage reads from the last update.
StrokeFrameInput pipeline_stroke_input(const Pipeline& p);

// Changes what needs no new memory between frames: the orbit camera (zoom, yaw, pitch,
// fov_degrees), the tone settings (constant_tone, dark_tone, max_point_size, smooth_slope,
// relevance_update, lod), lights and ambient, colours (background, paper, ink), silhouettes and
// their width, and the stroke settings (quality, tolerances, LOD, nudge). The other fields of
// `view` (sizes, budgets, skinning) are ignored. `view` is resolved like pipeline_init's
// config; on invalid_argument the pipeline keeps its settings. Per-frame changes of an
// embedded character go through here too (the C API's stipple_player_set_*).
[[nodiscard]] Status pipeline_set_view(Pipeline* p, const FrameConfig& view);

// Points of the last frame: baked ones, then the run-time refinement's.
// The asset's points with the pipeline's radii (Pipeline::baked_radius), as the stipple stages
// see them.
inline PointsView pipeline_points(const Pipeline& p) {
    PointsView v = p.asset->points;
    v.radius = p.baked_radius.get();
    return v;
}

inline uint32_t pipeline_point_count(const Pipeline& p) {
    return (p.asset ? p.asset->points.point_count : 0) + p.refined_count;
}

// GL errors the checks saw since pipeline_init (FrameConfig::check_gl_errors; always empty
// without it): a count and the first error's pass and code (gl_error_name names it).
inline const GlErrorLog& pipeline_gl_errors(const Pipeline& p) {
    return p.renderer.gl_errors;
}

// Stable id of point i of the last frame: baked points keep their index; an extra point is
// ((host triangle + 1) << 32) | its rank in the triangle's sequence, the same every frame.
uint64_t pipeline_point_id(const Pipeline& p, uint32_t i);

// Projects point i of the last frame to pixels (origin top-left) and window depth.
glm::vec3 pipeline_project(const Pipeline& p, uint32_t i);

// A dot of the last frame as seen: stable id (pipeline_point_id), centre in pixels (origin
// top-left) and diameter in pixels.
struct VisibleDot {
    uint64_t id;
    float x, y, size;
};

// The dots the last frame drew where the picture shows them: size > 0, centre inside the
// image and not hidden by the mesh (the depth test the GPU makes, at the centre pixel or
// interpolated from the 2x2 texels around it; the depth copy holds the mesh pass only, so a
// dot hidden by a paintstroke still counts).
// `depth` is renderer_read_depth's output (bottom row first). Writes at most `capacity`
// (p.point_capacity is always enough) and returns the count.
uint32_t pipeline_visible_dots(const Pipeline& p, const float* depth, VisibleDot* out,
                               uint32_t capacity);

// The dots the last frame sized (size > 0, centre inside the image and on the mesh) that the
// mesh in front hides (the same test): the complement of pipeline_visible_dots near the
// object (one of the 2x2 texels around the centre on it). Coherence measures use it to tell
// occlusion (a leg passing in front of the other) from dots the size rule dropped
// (docs/measure.md).
uint32_t pipeline_hidden_dots(const Pipeline& p, const float* depth, VisibleDot* out,
                              uint32_t capacity);

// A paintstroke's root in the last frame: the first control point as drawn and the host
// surface point it is anchored at (the stipple stage's own placement of the root's hierarchy
// point, or the anchor itself for strokes without one), both in pixels (origin top-left).
struct StrokeRootSample {
    uint32_t stroke;
    float x, y;
    float surface_x, surface_y;
};

// Writes at most `capacity` roots (asset.strokes.stroke_count is enough); 0 when strokes are
// off or the asset has none.
uint32_t pipeline_stroke_roots(const Pipeline& p, StrokeRootSample* out, uint32_t capacity);

void pipeline_destroy(Pipeline* p);

}  // namespace stipple
