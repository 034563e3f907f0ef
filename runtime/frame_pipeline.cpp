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
#include "runtime/frame_point_stages.h"
#include "runtime/frame_pose.h"
#include "runtime/particle_frame.h"
#include "runtime/point_placement.h"
#include "runtime/point_simd.h"
#include "runtime/point_stages.h"
#include "runtime/region_density.h"
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
void compact_point(Pipeline* p, uint32_t i, uint32_t at) {
    const float* position = p->point_positions.get() + size_t(i) * 3;
    float* draw_position = p->draw_positions.get() + size_t(at) * 3;
    draw_position[0] = position[0];
    draw_position[1] = position[1];
    draw_position[2] = position[2];
    p->draw_sizes[at] = p->size[i];
}

// Points first .. count - 1; with level of detail the baked ones are the selection's drawn
// ones (ascending, as the full stages draw them) and `first` is the baked count.
uint32_t compact_drawn_points(Pipeline* p, uint32_t first, uint32_t count) {
    uint32_t drawn = 0;
    const float* size = p->size.get();
    if (first > 0)
        for (uint32_t j = 0; j < p->clusters.run_count; ++j) {
            compact_point(p, p->clusters.run[j], drawn);
            drawn += size[p->clusters.run[j]] > 0.0f;
        }
    for (uint32_t i = first; i < count; ++i) {
        compact_point(p, i, drawn);
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
    return refinement_init(
        &p->refinement, p->refinement_domain, asset.points, p->point_positions.get(),
        p->refine_on_points ? RefinementDomain::points : RefinementDomain::mesh, &asset.mesh);
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
        !alloc(&p->skin_matrices, joints) ||
        !alloc(&p->vertex_positions, verts * 3 + kSimdPadFloats) ||
        !alloc(&p->vertex_normals, verts * 3) ||
        !alloc(&p->point_positions, capacity * 3 + kSimdPadFloats) ||
        !alloc(&p->point_normals, capacity * 3 + kSimdPadFloats) ||
        !alloc(&p->rest_radius, points) || !alloc(&p->baked_radius, points) ||
        !alloc(&p->radius, capacity) || !alloc(&p->size, capacity) ||
        !alloc(&p->radius_scale, points) || !alloc(&p->draw_positions, capacity * 3) ||
        !alloc(&p->draw_sizes, capacity) || !alloc(&p->refined_triangle, budget) ||
        !alloc(&p->refined_index, budget) ||
        !alloc(&p->triangle_front, asset.mesh.triangle_count) ||
        !alloc(&p->lines, size_t(asset.edges.edge_count) * 6) ||
        !alloc(&p->vertex_pairs, verts * 8))
        return make_status(StatusCode::out_of_memory, "out of memory for %zu points", capacity);
    if (has_avx2(point_simd_detected())) {  // the AVX2 kernels' 16-byte records, once
        if (!alloc(&p->neighbour_quads, points * 4))
            return make_status(StatusCode::out_of_memory, "out of memory for %zu points", points);
        if (!quad_neighbours(asset.points, p->neighbour_quads.get())) p->neighbour_quads.reset();
        if (asset.mesh.vertex_count <= kPointHostMaxVertices) {
            if (!alloc(&p->point_hosts, points))
                return make_status(StatusCode::out_of_memory, "out of memory for %zu points",
                                   points);
            point_hosts(asset.points, asset.mesh.indices, asset.mesh.vertex_count,
                        p->point_hosts.get());
        }
    }
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
    const uint32_t n = asset.points.point_count;
    if (n > 0) std::memcpy(p->baked_radius.get(), asset.points.radius, size_t(n) * 4);
    if (!density_corrected_radii(p->point_positions.get(), n, RegionDensityParams(),
                                 p->baked_radius.get()))  // issue 7: runtime/region_density.h
        return make_status(StatusCode::out_of_memory, "out of memory for %u points' regions", n);
    const PointsView points = pipeline_points(*p);
    relevance_scale(points, p->point_positions.get(), p->radius_scale.get());
    if (p->config.refinement_budget > 0) {
        Status st = refinement_setup(p);
        if (!st.ok()) return st;
    }
    Clock::time_point clock = Clock::now();
    pose_mesh(p, AnimationState(), nullptr, &clock);
    place_points(asset.points, asset.mesh.indices, p->vertex_positions.get(),
                 p->vertex_normals.get(), p->point_positions.get(), p->point_normals.get());
    recompute_relevance(points, p->point_positions.get(), p->radius_scale.get(), points.radius,
                        p->rest_radius.get());
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
    renderer_config_occluder(&rc, *p.asset, c);  // the OCCL occluder (renderer_occluder.cpp)
    std::memcpy(rc.background, c.background, sizeof(rc.background));
    std::memcpy(rc.paper, c.paper, sizeof(rc.paper));
    std::memcpy(rc.ink, c.ink, sizeof(rc.ink));
    rc.vertex_colours = p.style.vertex_colours.get();  // looks: runtime/style.h
    rc.part_colours = p.asset->looks.part_colour != nullptr;
    rc.dot_colours = p.style.dot_colours != nullptr;
    rc.max_creases = p.asset->looks.crease_count;
    return rc;
}

}  // namespace

namespace {

// Everything but GL: settings, every buffer (from the current allocator), the rest pose.
Status init_memory(Pipeline* p, const Asset& asset, const FrameConfig& config) {
    *p = Pipeline();
    p->asset = &asset;
    Status st = resolve_frame_config(config, &p->config);
    if (st.ok() && p->config.particle_style)  // strokes instead of stipples: docs/particles.md
        particle_style_frame_config(*p->config.particle_style, &p->config);
    if (st.ok()) st = alloc_pose_buffers(p);
    if (st.ok()) st = alloc_frame_buffers(p);
    if (st.ok()) st = place_rest_pose(p);
    if (st.ok() && asset.points.point_count > 0)  // Thesis §9.1.1: runtime/point_clusters.h
        st = point_clusters_init(&p->clusters, asset, p->baked_radius.get(), p->rest_radius.get());
    if (st.ok()) st = stroke_stage_init(&p->strokes, asset, p->config);
    if (st.ok()) st = style_init(&p->style, asset, p->point_capacity);  // runtime/style.h
    if (st.ok() && p->config.particle_style)
        st = pipeline_particle_init(&p->particles, asset, p->config);  // runtime/particle_frame.h
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
    point_simd_detected();  // the SIMD path, chosen once (runtime/point_simd.h)
    if (st.ok()) st = thread_pool_init(&p->pool, p->config.threads);
    if (st.ok()) st = renderer_init(&p->renderer, gl, renderer_config(*p));
    if (st.ok())  // the look of the camera set before the renderer existed (runtime/style.h)
        renderer_set_look(&p->renderer, p->config, p->size_params.light_direction,
                          p->style.transparent_parts);
    if (st.ok()) st = stroke_stage_init_gl(&p->strokes, gl, p->config);
    if (st.ok()) st = particle_stage_init_gl(&p->particles, gl);
    if (st.ok() && p->config.path == FramePath::gpu) st = gpu_path_init(p);
    if (!st.ok()) {
        pipeline_destroy(p);
        return st;
    }
    // Draw the rest pose once now: llvmpipe compiles shaders on first use (15-25 ms), which
    // belongs to load time, not to the first frame.
    pipeline_frame(p, AnimationState(), nullptr);
    p->particles.set.settled = false;  // the first real frame shows its particles at once
    return {};
}

void pipeline_frame(Pipeline* p, int clip, float time, StageTimes* t) {
    AnimationState state;
    state.clip = clip;
    state.time = time;
    pipeline_frame(p, state, t);
}

namespace {

// Where this frame's refinement points live, for their colours (runtime/style.h).
RefinedHosts refined_hosts(const Pipeline& p) {
    RefinedHosts r;
    r.count = p.refined_count;
    r.triangle = p.refined_triangle.get();
    r.indices = p.refine_on_points ? p.refinement_domain.indices : p.asset->mesh.indices;
    r.on_points = p.refine_on_points;
    return r;
}

// The CPU path's point part: place, relevance, refine and size, then the drawn dots compacted.
void point_part(Pipeline* p, StageTimes* t, Clock::time_point* clock) {
    const Asset& a = *p->asset;
    const bool lod = p->config.lod && p->clusters.cluster_count > 0;
    pipeline_point_stages(p, lod, t, clock);  // runtime/frame_point_stages.h
    const uint32_t baked = a.points.point_count;
    p->points_drawn = compact_drawn_points(p, lod ? baked : 0, baked + p->refined_count);
    p->dots_coloured = style_dot_colours(&p->style, a, p->config, p->size.get(), refined_hosts(*p));
    if (t) t->size += ms_since(clock);
}

// Facing, silhouette and crease lines (thesis §3.2, §8.2): they read only the posed mesh.
void line_stages(Pipeline* p, StageTimes* t, StageClock::time_point* clock) {
    const Asset& a = *p->asset;
    p->lines_drawn = 0;
    const bool creases = p->config.creases && a.looks.crease_count > 0;  // thesis §8.2
    const bool facing = (p->config.silhouettes && a.edges.edge_count > 0) || creases;
    if (facing)
        triangle_facing(a.mesh.triangle_count, a.mesh.indices, p->vertex_positions.get(),
                        p->size_params.eye, p->triangle_front.get(), true);
    // The mesh pass draws only what may face the eye (runtime/renderer_front.cpp).
    renderer_set_front_faces(&p->renderer, facing ? p->triangle_front.get() : nullptr,
                             p->view_projection);
    if (p->config.silhouettes && a.edges.edge_count > 0)
        p->lines_drawn = silhouette_lines(a.edges, p->triangle_front.get(),
                                          p->vertex_positions.get(), p->lines.get());
    p->style.creases_drawn =
        creases ? crease_lines(a.looks, p->triangle_front.get(), p->vertex_positions.get(),
                               p->style.crease_lines.get())
                : 0;
    if (t) t->silhouette += ms_since(clock);
}

// The worker's stage times into the frame's.
void add_point_times(StageTimes* t, const StageTimes& w) {
    t->select += w.select;
    t->place += w.place;
    t->relevance += w.relevance;
    t->refine += w.refine;
    t->size += w.size;
}

// The point part on one of the pool's workers, beside the caller's mesh pass (llvmpipe shades
// and bins the mesh on the calling thread, so the point stages take the other core). The
// stages run on that worker alone: the pool is lent to this one task, and every stage gives
// the same bytes on any thread count (runtime/point_stages.h). Their times go to `times`
// (null: not timed), each stage's field written by the worker only.
struct PointPartTask {
    Pipeline* p;
    StageTimes* times;
};
void point_part_task(void* context, uint32_t, uint32_t) {
    const PointPartTask& task = *static_cast<const PointPartTask*>(context);
    Clock::time_point clock = Clock::now();
    point_part(task.p, task.times, &clock);
}

// Paintstrokes (runtime/stroke_stage.h): after the point part, whose radii their roots read.
void stroke_stage(Pipeline* p, StageTimes* t, Clock::time_point* clock) {
    stroke_stage_update(&p->strokes, *p->asset, pipeline_stroke_input(*p), p->config.stroke_lod_px);
    if (t) t->strokes += ms_since(clock);
}

// The point part started on the worker (when the pool has one) and joined.
struct BesidePart {
    ThreadPool pool;
    StageTimes times;
    PointPartTask task{nullptr, nullptr};
    bool on = false;
};
void point_part_begin(Pipeline* p, BesidePart* b, bool timed) {
    b->on = p->pool.threads > 1;
    if (!b->on) return;
    b->pool = p->pool;
    p->pool = ThreadPool();  // the task's until it is finished
    b->task = PointPartTask{p, timed ? &b->times : nullptr};
    thread_pool_begin(&b->pool, 1, point_part_task, &b->task);
}
void point_part_join(Pipeline* p, BesidePart* b, StageTimes* t) {
    thread_pool_finish(&b->pool);
    p->pool = b->pool;
    if (t) add_point_times(t, b->times);
}

void draw_lines(Pipeline* p) {
    renderer_draw_line_sets(&p->renderer, p->view_projection, p->lines.get(), p->lines_drawn,
                            p->style.crease_lines.get(), p->style.creases_drawn);
}

// What the frame draws over the mesh pass, in order: strokes, lines (unless drawn already),
// dots; then glFinish.
void draw_ink(Pipeline* p, bool lines) {
    if (p->strokes.enabled) {  // over the depth pass, into its colour and depth, before the ink
        renderer_begin_overlay(&p->renderer);
        stroke_stage_draw(&p->strokes, pipeline_stroke_input(*p));
    }
    if (lines) draw_lines(p);
    if (p->config.path == FramePath::gpu)  // place, relevance and size run here, on the GPU
        gpu_path_draw_points(p);
    else
        renderer_draw_dots(
            &p->renderer, p->view_projection, p->draw_positions.get(), p->draw_sizes.get(),
            p->dots_coloured ? p->style.dot_colours.get() : nullptr, p->points_drawn);
    p->renderer.gl.Finish();
}

}  // namespace

// The CPU path submits the mesh pass (and the lines, which come next unless strokes lie
// between them) as soon as the mesh is posed and its facing known, and flushes it, so the
// driver fills the depth while this thread runs the point stages (on llvmpipe the rasterizer
// threads; the dots pass, whose vertex shader reads that depth, would otherwise wait for it
// with nothing to do). With a worker in the pool (FrameConfig::threads > 1) the point part
// runs on it from as soon as the mesh is posed, beside the facing and silhouette stages and
// the mesh pass: llvmpipe shades and bins the mesh on this thread, inside glDrawElements (7 ms
// of the horse's 97k triangles), and the point stages take the other core meanwhile. The GL
// commands and their order are those of pipeline_update followed by the passes, and the stages'
// bytes do not depend on the thread that runs them: the picture is the same.
void pipeline_frame(Pipeline* p, const AnimationState& state, StageTimes* t) {
    if (p->particles.enabled) {  // GI'01 strokes instead of stipples
        pipeline_particle_frame(p, &p->particles, state, t);
        return;
    }
    const bool gpu = p->config.path == FramePath::gpu;
    const bool early_lines = !gpu && !p->strokes.enabled;
    if (gpu) pipeline_update(p, state, t);
    Clock::time_point clock = Clock::now();
    if (!gpu) pose_mesh(p, state, t, &clock);
    // The point part runs beside the line stages and the mesh pass when the pool has a worker
    // (it reads only the posed mesh; the frame's GL calls stay on this thread, and the pool is
    // the task's until it is finished).
    BesidePart beside;
    if (!gpu) point_part_begin(p, &beside, t != nullptr);
    if (!gpu) line_stages(p, t, &clock);
    renderer_draw_fill(&p->renderer, p->view_projection, p->vertex_positions.get(),
                       p->vertex_normals.get(), p->asset->mesh.vertex_count);
    if (early_lines) draw_lines(p);
    if (!gpu) {
        p->renderer.gl.Flush();
        if (beside.on) {
            point_part_join(p, &beside, t);
        } else {
            if (t) t->draw += ms_since(&clock);
            point_part(p, t, &clock);
        }
        if (t) t->draw += ms_since(&clock);
        stroke_stage(p, t, &clock);
    }
    draw_ink(p, !early_lines);
    // Dots and lines lie on the mesh, so the next frame clears only its picture
    // (runtime/renderer_dirty.cpp); paintstrokes reach past it.
    if (!p->strokes.enabled)
        renderer_set_drawn_mesh(&p->renderer, p->view_projection, p->vertex_positions.get(),
                                p->asset->mesh.vertex_count, p->draw_sizes.get(),
                                gpu ? 0 : p->points_drawn, p->config.max_point_size);
    if (t) t->draw += ms_since(&clock);
}

// With a worker in the pool the point part runs on it beside the line stages, as in
// pipeline_frame (its stages on one thread: splitting them in ranges over this machine's two
// vCPUs was slower than one thread, the ranges' points moving between the cores' caches).
void pipeline_update(Pipeline* p, const AnimationState& state, StageTimes* t) {
    Clock::time_point clock = Clock::now();
    pose_mesh(p, state, t, &clock);
    if (p->config.path == FramePath::gpu) return gpu_path_update(p, t);  // runtime/gpu_stages.h
    BesidePart beside;
    point_part_begin(p, &beside, t != nullptr);
    if (!beside.on) point_part(p, t, &clock);
    line_stages(p, t, &clock);
    if (beside.on) {
        point_part_join(p, &beside, t);
        clock = Clock::now();
    }
    stroke_stage(p, t, &clock);
}

void pipeline_line_and_stroke_stages(Pipeline* p, StageTimes* t, StageClock::time_point* clock) {
    line_stages(p, t, clock);
    stroke_stage(p, t, clock);
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
    s.tone_gamma = c.tone_gamma;  // the tone curve (runtime/stipple_size.h)
    s.tone_contrast = c.tone_contrast;
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
    renderer_set_look(&r, c, s.light_direction, p->style.transparent_parts);  // runtime/style.h
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
    c.style = view.style;  // looks: runtime/style.h
    c.toon_bands = view.toon_bands;
    c.toon_shade = view.toon_shade;
    c.toon_ink = view.toon_ink;
    c.tone_gamma = view.tone_gamma;
    c.tone_contrast = view.tone_contrast;
    std::memcpy(c.fill, view.fill, sizeof(c.fill));
    c.creases = view.creases;
    c.max_point_size = view.max_point_size;
    c.smooth_slope = view.smooth_slope;
    c.relevance_update = view.relevance_update;
    c.stroke_quality = view.stroke_quality;
    c.stroke_tol_theta = view.stroke_tol_theta;
    c.stroke_tol_z = view.stroke_tol_z;
    c.stroke_lod_px = view.stroke_lod_px;
    c.stroke_nudge = view.stroke_nudge;
    c.silhouettes = view.silhouettes;
    c.lod = view.lod;
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
    thread_pool_destroy(&p->pool);
    gpu_stages_destroy(&p->gpu);
    stroke_stage_destroy(&p->strokes);
    particle_stage_destroy(&p->particles);
    renderer_destroy(&p->renderer);
    *p = Pipeline();
}

}  // namespace stipple
