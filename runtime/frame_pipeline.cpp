#include "runtime/frame_pipeline.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <new>

#include "runtime/camera.h"
#include "runtime/double_sided.h"
#include "runtime/frame_pose.h"
#include "runtime/point_placement.h"
#include "runtime/silhouette.h"
#include "runtime/stroke_anchor.h"

namespace stipple {

namespace {

using Clock = StageClock;

// Orbit camera around what is framed (runtime/camera.h), in the pipeline's image.
void setup_camera(Pipeline* p) {
    const FrameConfig& c = p->config;
    const OrbitCamera cam = orbit_camera(*p->asset, c, p->vertex_positions.get());
    pipeline_set_camera(p, cam.view, cam.projection, c.width, c.height);
}

// Only dots with a size go to the GPU: at 100k points a frame draws ~5k, and uploading
// and vertex-shading the other 95% cost llvmpipe more than this compaction costs here.
uint32_t compact_drawn_points(Pipeline* p, uint32_t count) {
    uint32_t drawn = 0;
    const float* size = p->size.get();
    const float* position = p->point_positions.get();
    float* draw_size = p->draw_sizes.get();
    float* draw_position = p->draw_positions.get();
    for (uint32_t i = 0; i < count; ++i) {
        draw_position[drawn * 3] = position[i * 3];
        draw_position[drawn * 3 + 1] = position[i * 3 + 1];
        draw_position[drawn * 3 + 2] = position[i * 3 + 2];
        draw_size[drawn] = size[i];
        drawn += size[i] > 0.0f;
    }
    return drawn;
}

}  // namespace

// What the stroke stage reads from this frame.
StrokeFrameInput pipeline_stroke_input(const Pipeline& p) {
    StrokeFrameInput in;
    in.positions = p.vertex_positions.get();
    in.normals = p.vertex_normals.get();
    in.skin_matrices = p.asset->skinned ? p.skin_matrices.get() : nullptr;
    in.point_radius = p.radius.get();
    in.view = p.view;
    in.projection = p.projection;
    in.focal_px = p.focal_px;
    in.light_eye = p.light_eye;
    return in;
}

namespace {

// The finest quarter of the bake is where the run-time refinement takes over: extra points
// can be drawn only where the size rule draws baked points of that region size, so while none
// of them has a size (full views of a dense bake) the frame needs no refinement at all.
bool hierarchy_running_out(const float* size, uint32_t baked) {
    for (uint32_t i = baked - baked / 4; i < baked; ++i)
        if (size[i] > 0.0f) return true;
    return baked < 4;
}

// Baked points enough for their own triangulation to be the refinement's domain.
constexpr uint32_t kMinTriangulatedPoints = 256;

// Chooses the refinement's domain and builds its tables; p->point_positions/normals hold the
// baked points in the bind pose.
Status refinement_setup(Pipeline* p) {
    const Asset& asset = *p->asset;
    const uint32_t n = asset.points.point_count;
    p->refinement_domain = asset.mesh;
    p->refine_on_points = false;
    if (n >= kMinTriangulatedPoints) {
        const double area = surface_area(asset.mesh);
        Status st =
            triangulate_points(n, p->point_positions.get(), p->point_normals.get(), area,
                               &asset.mesh, asset.points.host_triangle, &p->point_triangles);
        if (!st.ok()) return st;
        // A sparse or torn result (scattered points) falls back to the render mesh.
        if (p->point_triangles.triangle_count >= n) {
            MeshView& d = p->refinement_domain;
            d.vertex_count = n;
            d.triangle_count = p->point_triangles.triangle_count;
            d.positions = p->point_positions.get();
            d.normals = p->point_normals.get();
            d.indices = p->point_triangles.indices.get();
            p->refine_on_points = true;
        }
    }
    return refinement_init(&p->refinement, p->refinement_domain, asset.points,
                           p->point_positions.get(),
                           p->refine_on_points ? RefinementDomain::points : RefinementDomain::mesh);
}

// The pose buffers: three local poses and morph weight sets, two sampling contexts.
Status alloc_pose_buffers(Pipeline* p) {
    const Asset& asset = *p->asset;
    const uint32_t nodes = asset.skinned ? asset.skin.skeleton.node_count : 0;
    uint32_t max_channels = 0;
    for (uint32_t c = 0; c < asset.clip_count; ++c)
        max_channels = std::max(max_channels, asset.clips[c].channel_count);
    for (int slot = 0; slot < 3; ++slot)
        if (!alloc(&p->locals[slot], nodes) ||
            !alloc(&p->morph_weights[slot], asset.morph.weight_count))
            return make_status(StatusCode::out_of_memory, "out of memory for %u nodes", nodes);
    for (int slot = 0; slot < 2; ++slot) {
        if (!alloc(&p->cursors[slot], max_channels))
            return make_status(StatusCode::out_of_memory, "out of memory for sampling cursors");
        p->contexts[slot].cursors = anim::Span<uint32_t>(p->cursors[slot].get(), max_channels);
    }
    return {};
}

// The mesh, point and line buffers, sized for the baked points plus the refinement budget.
Status alloc_frame_buffers(Pipeline* p) {
    const Asset& asset = *p->asset;
    const uint32_t nodes = asset.skinned ? asset.skin.skeleton.node_count : 0;
    const uint32_t joints = asset.skinned ? asset.skin.skeleton.joint_count : 0;
    const size_t verts = asset.mesh.vertex_count, points = asset.points.point_count;
    const uint32_t budget = p->config.refinement_budget;
    const size_t capacity = points + budget;
    if (capacity > 0x7FFFFFFFu)
        return make_status(StatusCode::invalid_argument,
                           "%zu points + refinement budget %u is too many", points, budget);
    p->point_capacity = uint32_t(capacity);
    if (!alloc(&p->dq_joints, joints) || !alloc(&p->models, nodes) ||
        !alloc(&p->skin_matrices, joints) || !alloc(&p->vertex_positions, verts * 3) ||
        !alloc(&p->vertex_normals, verts * 3) || !alloc(&p->point_positions, capacity * 3) ||
        !alloc(&p->point_normals, capacity * 3) || !alloc(&p->rest_radius, points) ||
        !alloc(&p->radius, capacity) || !alloc(&p->size, capacity) ||
        !alloc(&p->radius_scale, points) || !alloc(&p->draw_positions, capacity * 3) ||
        !alloc(&p->draw_sizes, capacity) || !alloc(&p->refined_triangle, budget) ||
        !alloc(&p->refined_index, budget) ||
        !alloc(&p->triangle_front, asset.mesh.triangle_count) ||
        !alloc(&p->lines, size_t(asset.edges.edge_count) * 6))
        return make_status(StatusCode::out_of_memory, "out of memory for %zu points", capacity);
    if (asset.sides.triangle_double_sided) {  // runtime/double_sided.h: per-point flags, once
        if (!alloc(&p->point_double_sided, points))
            return make_status(StatusCode::out_of_memory, "out of memory for %zu points", points);
        if (!double_sided_point_flags(asset.points.point_count, asset.points.host_triangle,
                                      asset.sides.triangle_double_sided,
                                      p->point_double_sided.get()))
            p->point_double_sided.reset();  // no point lies on a double-sided triangle
    }
    return {};
}

// Bind pose (the bake's space): how each baked radius relates to its neighbour distances,
// and the refinement's tables. Then the rest pose: camera bounds, and the radii used when
// relevance updates are off (the baked radii expressed in the same space as the posed mesh).
Status place_rest_pose(Pipeline* p) {
    const Asset& asset = *p->asset;
    place_points(asset.points, asset.mesh.indices, asset.mesh.positions, asset.mesh.normals,
                 p->point_positions.get(), p->point_normals.get());
    relevance_scale(asset.points, p->point_positions.get(), p->radius_scale.get());
    if (p->config.refinement_budget > 0) {
        Status st = refinement_setup(p);
        if (!st.ok()) return st;
    }
    Clock::time_point clock = Clock::now();
    pose_mesh(p, AnimationState(), nullptr, &clock);
    place_points(asset.points, asset.mesh.indices, p->vertex_positions.get(),
                 p->vertex_normals.get(), p->point_positions.get(), p->point_normals.get());
    recompute_relevance(asset.points, p->point_positions.get(), p->radius_scale.get(),
                        asset.points.radius, p->rest_radius.get());
    setup_camera(p);
    return {};
}

// The renderer's settings: the resolved frame settings and the asset's buffer sizes.
RendererConfig renderer_config(const Pipeline& p) {
    const FrameConfig& c = p.config;
    RendererConfig rc;
    rc.width = c.width;
    rc.height = c.height;
    rc.max_points = p.point_capacity;
    rc.vertex_count = p.asset->mesh.vertex_count;
    rc.max_lines = p.asset->edges.edge_count;
    rc.line_width = c.line_width;
    rc.depth_copy = c.depth_readback;
    rc.check_errors = c.check_gl_errors;
    rc.indices = p.asset->mesh.indices;
    rc.triangle_count = p.asset->mesh.triangle_count;
    rc.triangle_double_sided = p.asset->sides.triangle_double_sided;
    std::memcpy(rc.background, c.background, sizeof(rc.background));
    std::memcpy(rc.paper, c.paper, sizeof(rc.paper));
    std::memcpy(rc.ink, c.ink, sizeof(rc.ink));
    return rc;
}

}  // namespace

namespace {

// Everything but GL: settings, every buffer (from the current allocator), the rest pose.
Status init_memory(Pipeline* p, const Asset& asset, const FrameConfig& config) {
    *p = Pipeline();
    p->asset = &asset;
    Status st = resolve_frame_config(config, &p->config);
    if (st.ok()) st = alloc_pose_buffers(p);
    if (st.ok()) st = alloc_frame_buffers(p);
    if (st.ok()) st = place_rest_pose(p);
    if (st.ok()) st = stroke_stage_init(&p->strokes, asset, p->config);
    return st;
}

}  // namespace

size_t pipeline_memory_bytes(const Asset& asset, const FrameConfig& config) {
    CountingArena arena;
    {
        AllocatorScope scope(counting_allocator(&arena));
        std::unique_ptr<Pipeline> p(new (std::nothrow) Pipeline());
        if (!p) return 0;
        const bool ok = init_memory(p.get(), asset, config).ok();
        pipeline_destroy(p.get());
        if (!ok) return 0;
    }
    return arena.bytes;
}

Status pipeline_init(Pipeline* p, const Asset& asset, const GlApi& gl, const FrameConfig& config,
                     const Allocator& allocator) {
    AllocatorScope scope(allocator);
    Status st = init_memory(p, asset, config);
    if (st.ok()) st = renderer_init(&p->renderer, gl, renderer_config(*p));
    if (st.ok()) st = stroke_stage_init_gl(&p->strokes, gl, p->config);
    if (!st.ok()) {
        pipeline_destroy(p);
        return st;
    }
    // Draw the rest pose once now: llvmpipe compiles shaders on first use (15-25 ms), which
    // belongs to load time, not to the first frame.
    pipeline_frame(p, AnimationState(), nullptr);
    return {};
}

void pipeline_frame(Pipeline* p, int clip, float time, StageTimes* t) {
    AnimationState state;
    state.clip = clip;
    state.time = time;
    pipeline_frame(p, state, t);
}

void pipeline_frame(Pipeline* p, const AnimationState& state, StageTimes* t) {
    pipeline_update(p, state, t);
    Clock::time_point clock = Clock::now();
    renderer_draw_mesh(&p->renderer, p->view_projection, p->vertex_positions.get(),
                       p->asset->mesh.vertex_count);
    if (p->strokes.enabled) {  // over the depth pass, into its colour and depth, before the ink
        renderer_begin_overlay(&p->renderer);
        stroke_stage_draw(&p->strokes, pipeline_stroke_input(*p));
    }
    renderer_draw_lines(&p->renderer, p->view_projection, p->lines.get(), p->lines_drawn);
    renderer_draw_points(&p->renderer, p->view_projection, p->draw_positions.get(),
                         p->draw_sizes.get(), p->points_drawn);
    p->renderer.gl.Finish();
    if (t) t->draw += ms_since(&clock);
}

void pipeline_update(Pipeline* p, const AnimationState& state, StageTimes* t) {
    const Asset& a = *p->asset;
    Clock::time_point clock = Clock::now();
    pose_mesh(p, state, t, &clock);
    place_points(a.points, a.mesh.indices, p->vertex_positions.get(), p->vertex_normals.get(),
                 p->point_positions.get(), p->point_normals.get());
    face_double_sided_points(a.points.point_count, p->point_double_sided.get(),
                             p->point_positions.get(), p->point_normals.get(), p->size_params.eye);
    if (t) t->place += ms_since(&clock);
    const uint32_t baked = a.points.point_count;
    if (p->config.relevance_update)
        recompute_relevance(a.points, p->point_positions.get(), p->radius_scale.get(),
                            p->rest_radius.get(), p->radius.get());
    else
        std::memcpy(p->radius.get(), p->rest_radius.get(), size_t(baked) * 4);
    if (t) t->relevance += ms_since(&clock);
    size_stipples(baked, p->point_positions.get(), p->point_normals.get(), p->radius.get(),
                  p->size_params, p->size.get());
    if (t) t->size += ms_since(&clock);
    // Where the baked hierarchy runs out, continue it (extra points after the baked ones).
    p->refined_count = 0;
    p->refinement_stats = RefinementStats();
    if (p->config.refinement_budget > 0 && hierarchy_running_out(p->size.get(), baked)) {
        RefinedPoints extra;
        extra.capacity = p->config.refinement_budget;
        extra.positions = p->point_positions.get() + size_t(baked) * 3;
        extra.normals = p->point_normals.get() + size_t(baked) * 3;
        extra.radius = p->radius.get() + baked;
        extra.triangle = p->refined_triangle.get();
        extra.index = p->refined_index.get();
        if (p->refine_on_points) {  // corners are the baked points, as placed this frame
            MeshView domain = p->refinement_domain;
            domain.positions = p->point_positions.get();
            domain.normals = p->point_normals.get();  // double-sided ones already face the eye
            refine_points(&p->refinement, domain, domain.positions, domain.normals, nullptr,
                          p->size_params, p->config.relevance_update, &extra, &p->refinement_stats);
        } else {
            refine_points(&p->refinement, a.mesh, p->vertex_positions.get(),
                          p->vertex_normals.get(), a.sides.triangle_double_sided, p->size_params,
                          p->config.relevance_update, &extra, &p->refinement_stats);
        }
        p->refined_count = extra.count;
        if (t) t->refine += ms_since(&clock);
        size_stipples(extra.count, extra.positions, extra.normals, extra.radius, p->size_params,
                      p->size.get() + baked);
        fade_baked_points(p->refinement, a.points, p->size.get());
    }
    const uint32_t count = baked + p->refined_count;
    p->points_drawn = compact_drawn_points(p, count);
    if (t) t->size += ms_since(&clock);
    p->lines_drawn = 0;
    if (p->config.silhouettes && a.edges.edge_count > 0) {
        triangle_facing(a.mesh.triangle_count, a.mesh.indices, p->vertex_positions.get(),
                        p->size_params.eye, p->triangle_front.get());
        p->lines_drawn = silhouette_lines(a.edges, p->triangle_front.get(),
                                          p->vertex_positions.get(), p->lines.get());
    }
    if (t) t->silhouette += ms_since(&clock);
    stroke_stage_update(&p->strokes, a, pipeline_stroke_input(*p), p->config.stroke_lod_px);
    if (t) t->strokes += ms_since(&clock);
}

void pipeline_set_camera(Pipeline* p, const glm::mat4& view, const glm::mat4& projection,
                         int viewport_width, int viewport_height, const glm::mat4& model) {
    const FrameConfig& c = p->config;
    p->view_projection = projection * view;
    p->view = view;
    p->projection = projection;
    // projection[1][1] = cot(half the vertical field of view) for perspective projections.
    p->focal_px = 0.5f * float(viewport_height) * projection[1][1];
    p->viewport_width = viewport_width;
    p->viewport_height = viewport_height;
    SizeParams& s = p->size_params;
    s.view_projection = p->view_projection;
    const glm::mat4 inverse_view = glm::inverse(view);
    s.eye = glm::vec3(inverse_view[3]);
    s.viewport_height = float(viewport_height);
    s.max_point_size = c.max_point_size;
    s.smooth_slope = c.smooth_slope;
    s.constant_tone = c.constant_tone;
    s.dark_tone = c.dark_tone;
    // The lights to the pose's space: camera-space ones through the inverse view, world-space
    // ones through the inverse model (app frames; identity for the player).
    const glm::mat4 inverse_model = glm::inverse(model);
    s.light_count = c.light_count;
    s.ambient = c.ambient;
    for (int k = 0; k < c.light_count; ++k) {
        const Light& l = c.lights[k];
        const glm::vec4 d(l.direction[0], l.direction[1], l.direction[2], 0.0f);
        s.light_direction[k] =
            glm::normalize(glm::vec3((l.camera_space ? inverse_view : inverse_model) * d));
        s.light_intensity[k] = l.intensity;
    }
    // Paintstrokes shade with the first light (eye space), or a headlight without lights.
    p->light_eye = c.light_count > 0
                       ? glm::normalize(glm::vec3(view * glm::vec4(s.light_direction[0], 0.0f)))
                       : glm::vec3(0.0f, 0.0f, 1.0f);
    Renderer& r = p->renderer;  // colours and line width, read at every pass
    std::memcpy(r.config.paper, c.paper, sizeof(r.config.paper));
    std::memcpy(r.config.ink, c.ink, sizeof(r.config.ink));
    std::memcpy(r.config.background, c.background, sizeof(r.config.background));
    r.config.line_width = c.line_width;
}

Status pipeline_set_view(Pipeline* p, const FrameConfig& in) {
    FrameConfig view;
    Status st = resolve_frame_config(in, &view);
    if (!st.ok()) return st;
    FrameConfig& c = p->config;
    c.zoom = view.zoom;
    c.yaw_degrees = view.yaw_degrees;
    c.pitch_degrees = view.pitch_degrees;
    c.fov_degrees = view.fov_degrees;
    c.constant_tone = view.constant_tone;
    c.dark_tone = view.dark_tone;
    c.max_point_size = view.max_point_size;
    c.smooth_slope = view.smooth_slope;
    c.relevance_update = view.relevance_update;
    c.stroke_quality = view.stroke_quality;
    c.stroke_tol_theta = view.stroke_tol_theta;
    c.stroke_tol_z = view.stroke_tol_z;
    c.stroke_lod_px = view.stroke_lod_px;
    c.stroke_nudge = view.stroke_nudge;
    c.silhouettes = view.silhouettes;
    c.line_width = view.line_width;
    std::memcpy(c.background, view.background, sizeof(c.background));
    std::memcpy(c.paper, view.paper, sizeof(c.paper));
    std::memcpy(c.ink, view.ink, sizeof(c.ink));
    c.light_count = view.light_count;
    std::memcpy(c.lights, view.lights, sizeof(c.lights));
    c.ambient = view.ambient;
    stroke_stage_configure(&p->strokes, c);
    setup_camera(p);
    return {};
}

void pipeline_destroy(Pipeline* p) {
    stroke_stage_destroy(&p->strokes);
    renderer_destroy(&p->renderer);
    *p = Pipeline();
}

}  // namespace stipple
