#include "runtime/stroke_stage.h"

#include <new>

#include "runtime/stroke_anchor.h"
#include "runtime/stroke_sort.h"

namespace stipple {
namespace {

// Whether the LOD keeps stroke `s`: its root point's relevance radius, at the root's distance,
// covers at least lod_px pixels (the hierarchy's coarse-to-fine order makes this a prefix of
// the fur in a uniform view; thesis §9.1.1).
bool lod_keeps(const format::StrokeRecord& s, const StrokePoint& root, const float* radius,
               float focal_px, float lod_px) {
    if (lod_px <= 0.0f || s.root_point == format::kNoRootPoint || !radius) return true;
    const float distance = -root.position.z;
    if (!(distance > 0.0f)) return false;
    return radius[s.root_point] * focal_px >= lod_px * distance;
}

}  // namespace

Status stroke_stage_init(StrokeStage* s, const Asset& asset, const FrameConfig& config) {
    *s = StrokeStage();
    const StrokesView& v = asset.strokes;
    if (!config.strokes || v.stroke_count == 0) return {};
    const uint32_t vertices = config.stroke_vertex_budget;
    // A segment takes at least 4 vertices and 2 triangles, at most ~3 indices per vertex.
    const uint32_t indices = vertices * 3, segments = vertices / 4 + 1;
    if (!alloc(&s->points, v.point_count) || !alloc(&s->vertices, vertices) ||
        !alloc(&s->indices, indices) || !alloc(&s->sorted_indices, indices) ||
        !alloc(&s->segments, segments) || !alloc(&s->order, segments) ||
        !alloc(&s->sort_scratch, size_t(segments) * 2))
        return make_status(StatusCode::out_of_memory, "stroke buffers (%u vertices)", vertices);
    s->mesh.vertices = s->vertices.get();
    s->mesh.vertex_capacity = vertices;
    s->mesh.indices = s->indices.get();
    s->mesh.index_capacity = indices;
    s->mesh.segments = s->segments.get();
    s->mesh.segment_capacity = segments;
    stroke_stage_configure(s, config);
    return {};
}

Status stroke_stage_init_gl(StrokeStage* s, const GlApi& gl, const FrameConfig& config) {
    if (!s->vertices) return {};  // no strokes
    StrokeRendererConfig rc;
    rc.max_vertices = s->mesh.vertex_capacity;
    rc.max_indices = s->mesh.index_capacity;
    rc.check_errors = config.check_gl_errors;
    Status st = stroke_renderer_init(&s->renderer, gl, rc);
    if (!st.ok()) return st;
    s->enabled = true;
    return {};
}

void stroke_stage_configure(StrokeStage* s, const FrameConfig& config) {
    s->params.quality = config.stroke_quality;
    s->params.tol_theta_px = config.stroke_tol_theta;
    s->params.tol_z_px = config.stroke_tol_z;
    s->params.nudge = config.stroke_nudge;
}

void stroke_stage_update(StrokeStage* s, const Asset& asset, const StrokeFrameInput& in,
                         float lod_px) {
    s->stats = TessellationStats();
    s->strokes_drawn = 0;
    s->mesh.vertex_count = s->mesh.index_count = s->mesh.segment_count = 0;
    s->mesh.overflow = false;
    if (!s->enabled) return;
    const StrokesView& v = asset.strokes;
    anchor_strokes(v, asset.mesh, in.positions, in.normals, in.skin_matrices, in.view,
                   s->points.get());
    StrokeCamera camera;
    camera.focal_px = in.focal_px;
    s->params.light_eye = in.light_eye;
    for (uint32_t i = 0; i < v.stroke_count && !s->mesh.overflow; ++i) {
        const format::StrokeRecord& r = v.strokes[i];
        const StrokePoint* cp = s->points.get() + r.first_point;
        if (!lod_keeps(r, cp[0], in.point_radius, in.focal_px, lod_px)) continue;
        StrokeStyle style;
        style.op_centre = float(r.op_centre) * (1.0f / 255.0f);
        style.op_edge = float(r.op_edge) * (1.0f / 255.0f);
        tessellate_stroke(cp, r.point_count, style, i, camera, s->params, &s->mesh, &s->stats);
        ++s->strokes_drawn;
    }
    sort_segments_back_to_front(s->mesh, s->order.get(), s->sort_scratch.get());
    gather_sorted_indices(s->mesh, s->order.get(), s->sorted_indices.get());
}

void stroke_stage_draw(StrokeStage* s, const StrokeFrameInput& in) {
    if (!s->enabled || s->mesh.index_count == 0) return;
    StrokeLighting lighting;
    lighting.light_eye = in.light_eye;
    stroke_renderer_draw(&s->renderer, in.projection, lighting, s->vertices.get(),
                         s->mesh.vertex_count, s->sorted_indices.get(), s->mesh.index_count);
}

void stroke_stage_destroy(StrokeStage* s) {
    if (s->enabled) stroke_renderer_destroy(&s->renderer);
    *s = StrokeStage();
}

}  // namespace stipple
